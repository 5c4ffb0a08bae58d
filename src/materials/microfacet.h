// Microfacet normal distributions for rough conductors, dielectrics and plastics: Beckmann and
// GGX (Trowbridge-Reitz), isotropic or anisotropic (alpha_u along the local x axis, alpha_v
// along y), with Smith's separable masking-shadowing [Walter et al. 2007, "Microfacet Models
// for Refraction through Rough Surfaces", eqs. 25-34; Heitz 2014, "Understanding the
// Masking-Shadowing Function"] and sampling of the normals visible from a direction
// [Heitz and d'Eon 2014, "Importance Sampling Microfacet-Based BSDFs using the Distribution of
// Visible Normals" (Beckmann); Heitz 2018, "Sampling the GGX Distribution of Visible Normals"].
//
// Parameters follow Mitsuba 3's `roughconductor`/`roughdielectric`/`roughplastic`: alpha is the
// RMS slope (Beckmann) or the GGX width, clamped below at 1e-4 as Mitsuba does, and Beckmann's
// G1 is Walter et al.'s rational fit (< 0.35 % error), so scene files map one to one.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "core/sampling.h"

namespace dualight {

enum class MicrofacetType : uint8_t { Beckmann = 0, GGX = 1 };

struct Microfacet {
  MicrofacetType type = MicrofacetType::Beckmann;
  float alpha_u = 0.1f, alpha_v = 0.1f;
};

// Mitsuba's floor on roughness: below it the lobe is numerically a Dirac delta.
inline constexpr float kMinAlpha = 1e-4f;
inline Microfacet make_microfacet(MicrofacetType type, float alpha_u, float alpha_v) {
  return {type, std::max(alpha_u, kMinAlpha), std::max(alpha_v, kMinAlpha)};
}

// Normal distribution D(m), per unit projected area (integrates cos(m) D(m) dm to 1).
inline float microfacet_D(const Microfacet& d, const Vec3& m) {
  if (m.z <= 0.f) return 0.f;
  const float cos2 = m.z * m.z;
  const float x = m.x / d.alpha_u, y = m.y / d.alpha_v;
  float D;
  if (d.type == MicrofacetType::Beckmann) {
    D = std::exp(-(x * x + y * y) / cos2) / (kPi * d.alpha_u * d.alpha_v * cos2 * cos2);
  } else {
    const float s = x * x + y * y + cos2;
    D = 1.f / (kPi * d.alpha_u * d.alpha_v * s * s);
  }
  return D * m.z > 1e-20f ? D : 0.f;  // as Mitsuba: no denormal tails
}

// Smith's masking of microfacet normal m seen from v; 0 when v sees m's back or the
// macrosurface disagrees on the side.
inline float smith_G1(const Microfacet& d, const Vec3& v, const Vec3& m) {
  if (dot(v, m) * v.z <= 0.f) return 0.f;
  const float xy2 = (d.alpha_u * v.x) * (d.alpha_u * v.x) + (d.alpha_v * v.y) * (d.alpha_v * v.y);
  if (xy2 == 0.f) return 1.f;
  const float tan2_alpha = xy2 / (v.z * v.z);
  if (d.type == MicrofacetType::GGX) return 2.f / (1.f + std::sqrt(1.f + tan2_alpha));
  const float a = 1.f / std::sqrt(tan2_alpha);
  if (a >= 1.6f) return 1.f;
  return (3.535f * a + 2.181f * a * a) / (1.f + 2.276f * a + 2.577f * a * a);  // [Walter 2007, eq. 27]
}

inline float smith_G(const Microfacet& d, const Vec3& wo, const Vec3& wi, const Vec3& m) {
  return smith_G1(d, wo, m) * smith_G1(d, wi, m);
}

// Density of sample_visible_normal: D_wo(m) = G1(wo, m) |wo . m| D(m) / wo.z (wo.z > 0).
inline float visible_normal_pdf(const Microfacet& d, const Vec3& wo, const Vec3& m) {
  if (wo.z <= 0.f) return 0.f;
  return microfacet_D(d, m) * smith_G1(d, wo, m) * std::abs(dot(wo, m)) / wo.z;
}

// Inverse error function, single precision [Giles 2010, "Approximating the erfinv function"].
float erfinv(float x);

// A normal m drawn from D_wo (wo.z > 0) by two uniform numbers.
Vec3 sample_visible_normal(const Microfacet& d, const Vec3& wo, Point2 u);

}  // namespace dualight
