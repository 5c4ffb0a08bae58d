// Two-sided ideal specular reflector, as Mitsuba's `twosided(conductor)` with material "none"
// scaled by `specular_reflectance`: one Dirac lobe, the mirror direction, weight = reflectance.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace dualight {

struct Mirror {
  Color reflectance;
};

constexpr BsdfFlags flags(const Mirror&) { return BsdfFlags::SpecularReflection; }
inline Color diffuse_reflectance(const Mirror&) { return Color(0.f); }

inline Color eval_f(const Mirror&, const Vec3&, const Vec3&, TransportMode) { return Color(0.f); }
inline float pdf_w(const Mirror&, const Vec3&, const Vec3&, TransportMode) { return 0.f; }
inline bool sample(const Mirror& b, const Vec3& wo, Point2, TransportMode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  s.wi = reflect_local(wo);
  s.pdf_w = 1.f;
  s.weight = b.reflectance;
  s.delta = true;
  return true;
}
inline DeltaLobe delta_lobe(const Mirror& b, const Vec3& wo, const Vec3& wi) {
  DeltaLobe lobe;
  lobe.refraction = !same_hemisphere(wo, wi);
  if (lobe.refraction) return lobe;
  lobe.coef = b.reflectance;
  lobe.prob = 1.f;
  return lobe;
}
// The lobe's direction from wo (local, wo.z != 0); a mirror has no refraction.
inline bool delta_direction(const Mirror&, const Vec3& wo, bool refraction, Vec3& wi) {
  if (refraction) return false;
  wi = reflect_local(wo);
  return true;
}

}  // namespace dualight
