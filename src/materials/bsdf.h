// Scattering functions: a closed set held in a std::variant, evaluated by free functions. Each
// member lives in its own file with its flags and maths; everything else asks through the
// dispatchers here, and decides by flags (bsdf_flags.h), never by the member's type.
//
// Directions are local (z along the surface's geometric normal, which for a dielectric points to
// the exterior) and point away from the surface; wo is the direction the path arrived from
// (towards the camera in radiance mode, towards the light in importance mode). TransportMode says
// which quantity flows along the path, for BSDFs that are not symmetric (refraction
// [Veach 1997, ch. 5]).
//
// Delta (Dirac) lobes scatter into discrete directions: eval_f and pdf_w are 0 for every
// direction pair, and only `sample` can find their directions. Its pdf_w is then the discrete
// probability of the lobe it picked (1 for a mirror, the Fresnel reflectance or transmittance
// for glass) and BsdfSample::delta is set.
#pragma once
#include <variant>

#include "materials/conductor.h"
#include "materials/dielectric.h"
#include "materials/lambertian.h"
#include "materials/mirror.h"
#include "materials/plastic.h"
#include "materials/rough_conductor.h"
#include "materials/rough_dielectric.h"
#include "materials/rough_plastic.h"
#include "materials/thin_dielectric.h"

namespace dualight {

using Bsdf = std::variant<Lambertian, Mirror, Dielectric, Conductor, RoughConductor, ThinDielectric,
                          RoughDielectric, Plastic, RoughPlastic>;

inline BsdfFlags flags(const Bsdf& b) {
  return std::visit([](const auto& x) { return flags(x); }, b);
}

// The hot three (evaluation, density, sampling) take Lambertian surfaces inline and the other
// members out of line (bsdf.cpp): a dispatch over all nine is too large to inline, and the
// call it became made Lambertian scenes 3-5 % slower (BDPT's vertices evaluate it most).
// Which member a BSDF is decides nothing here but where its code lives.
namespace bsdf_dispatch {
Color eval_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m);
float pdf_w(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m);
bool sample(const Bsdf& b, const Vec3& wo, Point2 u, TransportMode m, BsdfSample& s);
Color eval_f_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m);
float pdf_w_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m);
}  // namespace bsdf_dispatch

inline Color eval_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  if (const auto* x = std::get_if<Lambertian>(&b)) return eval_f(*x, wo, wi, m);
  return bsdf_dispatch::eval_f(b, wo, wi, m);
}
inline float pdf_w(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  if (const auto* x = std::get_if<Lambertian>(&b)) return pdf_w(*x, wo, wi, m);
  return bsdf_dispatch::pdf_w(b, wo, wi, m);
}
inline bool sample(const Bsdf& b, const Vec3& wo, Point2 u, TransportMode m, BsdfSample& s) {
  if (const auto* x = std::get_if<Lambertian>(&b)) return sample(*x, wo, u, m, s);
  return bsdf_dispatch::sample(b, wo, u, m, s);
}

// eval_f and pdf_w of world directions wo, wi (unit) in the frame Frame::from_normal(ns): the
// same values as eval_f/pdf_w of frame.to_local(wo), frame.to_local(wi). A Lambertian BSDF
// needs only the two cosines; the others build the frame out of line. (Built before a branch
// on the member, the frame was computed whole for Lambertian surfaces too: BDPT took 9 % more
// instructions to render the Cornell box.)
inline Color eval_f_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m) {
  if (const auto* x = std::get_if<Lambertian>(&b)) {
    return eval_f(*x, Vec3(0.f, 0.f, dot(wo, ns)), Vec3(0.f, 0.f, dot(wi, ns)), m);
  }
  return bsdf_dispatch::eval_f_world(b, ns, wo, wi, m);
}
inline float pdf_w_world(const Bsdf& b, const Vec3& ns, const Vec3& wo, const Vec3& wi, TransportMode m) {
  if (const auto* x = std::get_if<Lambertian>(&b)) {
    return pdf_w(*x, Vec3(0.f, 0.f, dot(wo, ns)), Vec3(0.f, 0.f, dot(wi, ns)), m);
  }
  return bsdf_dispatch::pdf_w_world(b, ns, wo, wi, m);
}

// The Dirac lobe joining wo (camera side) and wi (light side), local directions.
inline DeltaLobe delta_lobe(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  return std::visit([&](const auto& x) { return delta_lobe(x, wo, wi); }, b);
}
// The direction of the Dirac lobe (`refraction` or reflection) from local wo, wo.z != 0.
inline bool delta_direction(const Bsdf& b, const Vec3& wo, bool refraction, Vec3& wi) {
  return std::visit([&](const auto& x) { return delta_direction(x, wo, refraction, wi); }, b);
}
// The albedo of the diffuse lobe (0 without one): radiosity's rho.
inline Color diffuse_reflectance(const Bsdf& b) {
  return std::visit([](const auto& x) { return diffuse_reflectance(x); }, b);
}
// BsdfSample::eta of local directions (wo, wi): the IOR on wi's side over wo's where the BSDF
// refracts between them, else 1. Members that bend light across their surface say so with their
// own refraction_eta; the rest (reflectors, and the thin sheet, whose light leaves in the medium
// it came from) take this one.
template <class Member>
float refraction_eta(const Member&, const Vec3&, const Vec3&) {
  return 1.f;
}
inline float refraction_eta(const Bsdf& b, const Vec3& wo, const Vec3& wi) {
  return std::visit([&](const auto& x) { return refraction_eta(x, wo, wi); }, b);
}
// True when every lobe is a Dirac delta: connections to this vertex carry nothing.
inline bool is_delta(const Bsdf& b) { return is_delta(flags(b)); }

}  // namespace dualight
