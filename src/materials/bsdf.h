// Scattering functions: a closed set held in a std::variant, evaluated by free functions.
// Directions are local (z along the surface normal) and point away from the surface; wo is the
// direction the path arrived from (towards the camera in radiance mode). TransportMode says which
// quantity flows along the path, for BSDFs that are not symmetric (refraction, shading normals).
#pragma once
#include <variant>

#include "core/sampling.h"
#include "core/vec3.h"

namespace dualight {

enum class TransportMode { Radiance, Importance };

// Two-sided Lambertian reflector, as Mitsuba's `twosided(diffuse)` and pbrt's `diffuse`.
struct Lambertian {
  Color albedo;
};

using Bsdf = std::variant<Lambertian>;

struct BsdfSample {
  Vec3 wi;
  Color weight;  // f * |cos(wi)| / pdf_w
  float pdf_w = 0.f;
};

inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.f; }

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
  return true;
}

inline Color eval_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return eval_f(x, wo, wi, m); }, b);
}
inline float pdf_w(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return pdf_w(x, wo, wi, m); }, b);
}
inline bool sample(const Bsdf& b, const Vec3& wo, Point2 u, TransportMode m, BsdfSample& s) {
  return std::visit([&](const auto& x) { return sample(x, wo, u, m, s); }, b);
}

}  // namespace dualight
