// Scattering functions: a closed set held in a std::variant, evaluated by free functions.
// Directions are local (z along the surface's geometric normal, which for a dielectric points to
// the exterior) and point away from the surface; wo is the direction the path arrived from
// (towards the camera in radiance mode, towards the light in importance mode). TransportMode says
// which quantity flows along the path, for BSDFs that are not symmetric (refraction
// [Veach 1997, ch. 5]).
//
// Delta (Dirac) BSDFs, Mirror and Dielectric, scatter into discrete directions: eval_f and pdf_w
// are 0 for every direction pair, and only `sample` can find their directions. Its pdf_w is then
// the discrete probability of the lobe it picked (1 for a mirror, the Fresnel reflectance or
// transmittance for glass) and BsdfSample::delta is set.
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

// Two-sided ideal specular reflector, as Mitsuba's `twosided(conductor)` with material "none"
// scaled by `specular_reflectance`.
struct Mirror {
  Color reflectance;
};

// Smooth dielectric interface (glass, water), as Mitsuba's `dielectric`: Fresnel-weighted choice
// of ideal reflection and refraction. eta = interior IOR / exterior IOR; the normal faces out.
struct Dielectric {
  float eta;
};

using Bsdf = std::variant<Lambertian, Mirror, Dielectric>;

struct BsdfSample {
  Vec3 wi;
  Color weight;        // f * |cos(wi)| / pdf_w
  float pdf_w = 0.f;   // solid-angle density, or the lobe's probability when `delta`
  bool delta = false;  // wi is a Dirac direction: no other strategy can generate it
};

inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.f; }

// Unpolarised Fresnel reflectance of a smooth interface. cos_i is the cosine of the incident
// direction with the normal (negative: arriving from the interior); eta = interior / exterior IOR.
struct Fresnel {
  float R;          // reflectance (1 under total internal reflection)
  float cos_t;      // |cosine| of the refracted direction
  float eta_ratio;  // IOR on the refracted side / IOR on the incident side
};
inline Fresnel fresnel_dielectric(float cos_i, float eta) {
  const float eta_ratio = cos_i >= 0.f ? eta : 1.f / eta;
  const float ci = std::min(std::abs(cos_i), 1.f);
  const float sin2_t = (1.f - ci * ci) / (eta_ratio * eta_ratio);
  if (sin2_t >= 1.f) return {1.f, 0.f, eta_ratio};
  const float ct = std::sqrt(1.f - sin2_t);
  const float rs = (ci - eta_ratio * ct) / (ci + eta_ratio * ct);
  const float rp = (eta_ratio * ci - ct) / (eta_ratio * ci + ct);
  return {0.5f * (rs * rs + rp * rp), ct, eta_ratio};
}

inline Vec3 reflect_local(const Vec3& w) { return {-w.x, -w.y, w.z}; }

// --- Lambertian
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

// --- Mirror (delta)
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

// --- Dielectric (delta)
inline Color eval_f(const Dielectric&, const Vec3&, const Vec3&, TransportMode) { return Color(0.f); }
inline float pdf_w(const Dielectric&, const Vec3&, const Vec3&, TransportMode) { return 0.f; }
inline bool sample(const Dielectric& b, const Vec3& wo, Point2 u, TransportMode mode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  const Fresnel F = fresnel_dielectric(wo.z, b.eta);
  s.delta = true;
  if (u.u < F.R) {
    s.wi = reflect_local(wo);
    s.pdf_w = F.R;
    s.weight = Color(1.f);  // R / R
    return true;
  }
  // Snell's law; the refracted direction leaves on the other side of the interface.
  const float inv = 1.f / F.eta_ratio;
  s.wi = {-wo.x * inv, -wo.y * inv, wo.z > 0.f ? -F.cos_t : F.cos_t};
  s.pdf_w = 1.f - F.R;
  // Radiance is not conserved across the interface, importance is: L scales by (eta_o / eta_i)^2
  // from the wi side to the wo side [Veach 1997, sec. 5.2]; (1 - R) / (1 - R) cancels.
  s.weight = Color(mode == TransportMode::Radiance ? inv * inv : 1.f);
  return s.pdf_w > 0.f;
}

// --- dispatch
inline Color eval_f(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return eval_f(x, wo, wi, m); }, b);
}
inline float pdf_w(const Bsdf& b, const Vec3& wo, const Vec3& wi, TransportMode m) {
  return std::visit([&](const auto& x) { return pdf_w(x, wo, wi, m); }, b);
}
inline bool sample(const Bsdf& b, const Vec3& wo, Point2 u, TransportMode m, BsdfSample& s) {
  return std::visit([&](const auto& x) { return sample(x, wo, u, m, s); }, b);
}
// True when every lobe is a Dirac delta: connections to this vertex carry nothing.
inline bool is_delta(const Bsdf& b) { return !std::holds_alternative<Lambertian>(b); }

}  // namespace dualight
