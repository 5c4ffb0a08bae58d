// Smooth dielectric interface (glass, water), as Mitsuba's `dielectric`: Fresnel-weighted choice
// of ideal reflection and refraction [pbrt-v4 sec. 9.5; Veach 1997, sec. 5.2]. eta = interior
// IOR / exterior IOR; the normal faces out.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace dualight {

struct Dielectric {
  float eta;
};

constexpr BsdfFlags flags(const Dielectric&) {
  return BsdfFlags::SpecularReflection | BsdfFlags::SpecularTransmission;
}
inline Color diffuse_reflectance(const Dielectric&) { return Color(0.f); }

inline Color eval_f(const Dielectric&, const Vec3&, const Vec3&, TransportMode) { return Color(0.f); }
inline float pdf_w(const Dielectric&, const Vec3&, const Vec3&, TransportMode) { return 0.f; }

// The IOR on wi's side over the IOR on wo's side (BsdfSample::eta of the pair): 1 for a reflection.
inline float refraction_eta(const Dielectric& b, const Vec3& wo, const Vec3& wi) {
  return same_hemisphere(wo, wi) ? 1.f : (wo.z >= 0.f ? b.eta : 1.f / b.eta);
}

// Snell's law: the refracted direction of wo, on the other side of the interface.
inline Vec3 refract_local(const Vec3& wo, const Fresnel& F) {
  const float inv = 1.f / F.eta_ratio;
  return {-wo.x * inv, -wo.y * inv, wo.z > 0.f ? -F.cos_t : F.cos_t};
}

inline bool sample(const Dielectric& b, const Vec3& wo, Point2 u, TransportMode mode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  const Fresnel F = fresnel_dielectric(wo.z, b.eta);
  s.delta = true;
  if (u.u < F.R) {
    s.wi = reflect_local(wo);
    s.pdf_w = F.R;
    s.weight = Color(1.f);  // R / R
    s.eta = 1.f;
    return true;
  }
  const float inv = 1.f / F.eta_ratio;
  s.wi = refract_local(wo, F);
  s.pdf_w = 1.f - F.R;
  // Radiance is not conserved across the interface, importance is: L scales by (eta_o / eta_i)^2
  // from the wi side to the wo side [Veach 1997, sec. 5.2]; (1 - R) / (1 - R) cancels.
  s.weight = Color(mode == TransportMode::Radiance ? inv * inv : 1.f);
  s.eta = F.eta_ratio;
  return s.pdf_w > 0.f;
}

inline DeltaLobe delta_lobe(const Dielectric& b, const Vec3& wo, const Vec3& wi) {
  DeltaLobe lobe;
  lobe.refraction = !same_hemisphere(wo, wi);
  const Fresnel F = fresnel_dielectric(wo.z, b.eta);
  if (!lobe.refraction) {
    lobe.coef = Color(F.R);
    lobe.prob = F.R;
    return lobe;
  }
  // Radiance scales by (eta on the eye side / eta on the light side)^2 = 1 / eta_ratio^2.
  lobe.importance_ratio = 1.f / (F.eta_ratio * F.eta_ratio);
  lobe.prob = 1.f - F.R;
  lobe.coef = Color(lobe.prob * lobe.importance_ratio);
  return lobe;
}

// The lobe's direction from wo (local, wo.z != 0); false under total internal reflection.
inline bool delta_direction(const Dielectric& b, const Vec3& wo, bool refraction, Vec3& wi) {
  if (!refraction) {
    wi = reflect_local(wo);
    return true;
  }
  const Fresnel F = fresnel_dielectric(wo.z, b.eta);
  if (F.R >= 1.f) return false;
  wi = refract_local(wo, F);
  return true;
}

}  // namespace dualight
