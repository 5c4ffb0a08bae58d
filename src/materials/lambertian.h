// Two-sided Lambertian reflector, as Mitsuba's `twosided(diffuse)` and pbrt's `diffuse`:
// f = albedo / pi on the side wo is on, sampled by a cosine-weighted hemisphere.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace dualight {

struct Lambertian {
  Color albedo;
};

constexpr BsdfFlags flags(const Lambertian&) { return BsdfFlags::DiffuseReflection; }
inline Color diffuse_reflectance(const Lambertian& b) { return b.albedo; }

inline Color eval_f(const Lambertian& b, const Vec3& wo, const Vec3& wi, TransportMode) {
  return same_hemisphere(wo, wi) ? b.albedo * kInvPi : Color(0.f);
}
inline float pdf_w(const Lambertian&, const Vec3& wo, const Vec3& wi, TransportMode) {
  return same_hemisphere(wo, wi) ? cosine_hemisphere_pdf(std::abs(wi.z)) : 0.f;
}
inline bool sample(const Lambertian& b, const Vec3& wo, Point2 u, TransportMode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  s.wi = square_to_cosine_hemisphere(u);
  if (wo.z < 0.f) s.wi.z = -s.wi.z;
  s.pdf_w = cosine_hemisphere_pdf(std::abs(s.wi.z));
  if (!(s.pdf_w > 0.f)) return false;
  s.weight = b.albedo;  // (albedo / pi) * cos / (cos / pi)
  s.delta = false;
  return true;
}
// No Dirac lobe.
inline DeltaLobe delta_lobe(const Lambertian&, const Vec3&, const Vec3&) { return {}; }
inline bool delta_direction(const Lambertian&, const Vec3&, bool, Vec3&) { return false; }

}  // namespace dualight
