// Rough dielectric interface (frosted glass), as Mitsuba 3's `roughdielectric`: microfacet
// reflection and refraction [Walter et al. 2007, eqs. 20-21] with Beckmann or GGX normals.
// eta = interior IOR / exterior IOR, the normal faces out. Not symmetric: in Radiance mode the
// refracted part scales by (eta_wo / eta_wi)^2, the solid-angle compression Walter et al. omit
// [Veach 1997, sec. 5.2], so bidirectional estimators see the adjoint BSDF in Importance mode.
//
// Sampling picks reflection with the macro-surface's Fresnel reflectance (clamped to
// [0.05, 0.95] so both lobes stay reachable), then a visible normal; Mitsuba picks by the
// microfacet's Fresnel term, which needs a third random number. Same BSDF, a different pdf.
#pragma once
#include <algorithm>

#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/lobe_choice.h"
#include "materials/microfacet.h"

namespace dualight {

struct RoughDielectric {
  Microfacet distribution;
  float eta;
};

constexpr BsdfFlags flags(const RoughDielectric&) {
  return BsdfFlags::Glossy | BsdfFlags::Reflection | BsdfFlags::Transmission;
}
inline Color diffuse_reflectance(const RoughDielectric&) { return Color(0.f); }

// The IOR on wi's side over the IOR on wo's side (BsdfSample::eta of the pair): 1 for a reflection.
inline float refraction_eta(const RoughDielectric& b, const Vec3& wo, const Vec3& wi) {
  return wo.z * wi.z > 0.f ? 1.f : (wo.z > 0.f ? b.eta : 1.f / b.eta);
}

namespace rough_dielectric_detail {

// The probability of sampling the reflection lobe from wo.
inline float reflect_probability(const RoughDielectric& b, const Vec3& wo) {
  return std::clamp(fresnel_dielectric(wo.z, b.eta).R, 0.05f, 0.95f);
}

// The microfacet normal (z > 0) joining wo and wi, and the IOR ratio eta_wi / eta_wo; false
// when the pair is degenerate or a side disagrees with the microsurface.
struct HalfVector {
  Vec3 m;
  float eta = 1.f;  // IOR on wi's side / IOR on wo's side
  bool reflect = false;
};
inline bool half_vector(const RoughDielectric& b, const Vec3& wo, const Vec3& wi, HalfVector& h) {
  if (wo.z == 0.f || wi.z == 0.f) return false;
  h.reflect = wo.z * wi.z > 0.f;
  h.eta = refraction_eta(b, wo, wi);
  const Vec3 m = wo + wi * h.eta;
  const float len = length(m);
  if (!(len > 0.f)) return false;
  h.m = m.z < 0.f ? m / -len : m / len;
  return dot(wo, h.m) * wo.z > 0.f && dot(wi, h.m) * wi.z > 0.f;
}

// |d m / d wi|: the Jacobian from microfacet normals to directions [Walter 2007, eqs. 14, 17].
inline float half_jacobian(const Vec3& wo, const Vec3& wi, const HalfVector& h) {
  if (h.reflect) return 1.f / (4.f * std::abs(dot(wi, h.m)));
  const float denom = dot(wo, h.m) + h.eta * dot(wi, h.m);
  return h.eta * h.eta * std::abs(dot(wi, h.m)) / (denom * denom);
}

}  // namespace rough_dielectric_detail

Color eval_f(const RoughDielectric& b, const Vec3& wo, const Vec3& wi, TransportMode mode);

float pdf_w(const RoughDielectric& b, const Vec3& wo, const Vec3& wi, TransportMode);

bool sample(const RoughDielectric& b, const Vec3& wo, Point2 u, TransportMode mode, BsdfSample& s);
inline DeltaLobe delta_lobe(const RoughDielectric&, const Vec3&, const Vec3&) { return {}; }
inline bool delta_direction(const RoughDielectric&, const Vec3&, bool, Vec3&) { return false; }

}  // namespace dualight
