// Thin dielectric sheet (a window pane), as Mitsuba 3's `thindielectric`: two parallel
// interfaces so close that light leaves where it entered, either reflected or passing straight
// through, with the reflectance of all internal bounces summed, R' = R + T^2 R / (1 - R^2) =
// 2R / (1 + R) [Mitsuba 3 docs; pbrt-v4 sec. 9.5.1 ThinDielectricBxDF]. Both sides alike, and
// radiance is not rescaled: the light leaves in the medium it came from.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace dualight {

struct ThinDielectric {
  float eta;
};

constexpr BsdfFlags flags(const ThinDielectric&) {
  return BsdfFlags::SpecularReflection | BsdfFlags::SpecularTransmission;
}
inline Color diffuse_reflectance(const ThinDielectric&) { return Color(0.f); }

inline float thin_reflectance(float cos_o, float eta) {
  const float R = fresnel_dielectric(std::abs(cos_o), eta).R;
  return R < 1.f ? 2.f * R / (1.f + R) : 1.f;
}

inline Color eval_f(const ThinDielectric&, const Vec3&, const Vec3&, TransportMode) { return Color(0.f); }
inline float pdf_w(const ThinDielectric&, const Vec3&, const Vec3&, TransportMode) { return 0.f; }

inline bool sample(const ThinDielectric& b, const Vec3& wo, Point2 u, TransportMode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  const float R = thin_reflectance(wo.z, b.eta);
  const bool reflect = u.u < R;
  s.wi = reflect ? reflect_local(wo) : -wo;
  s.pdf_w = reflect ? R : 1.f - R;
  s.weight = Color(1.f);  // R / R or T / T
  s.delta = true;
  return s.pdf_w > 0.f;
}
inline DeltaLobe delta_lobe(const ThinDielectric& b, const Vec3& wo, const Vec3& wi) {
  DeltaLobe lobe;
  lobe.refraction = !same_hemisphere(wo, wi);
  const float R = thin_reflectance(wo.z, b.eta);
  lobe.prob = lobe.refraction ? 1.f - R : R;
  lobe.coef = Color(lobe.prob);
  return lobe;
}
// The lobe's direction from wo: the mirror direction, or straight through.
inline bool delta_direction(const ThinDielectric&, const Vec3& wo, bool refraction, Vec3& wi) {
  wi = refraction ? -wo : reflect_local(wo);
  return true;
}

}  // namespace dualight
