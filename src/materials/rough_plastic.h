// Rough plastic, as Mitsuba 3's `roughplastic`: a diffuse base under a rough dielectric coat
// [Weidlich and Wilkie 2007; Mitsuba 3 docs]. The coat reflects by microfacets (F D G /
// (4 cos_o cos_i), Beckmann or GGX, isotropic); the base's light passes the coat with the rough
// interface's directional transmittance t(cos) both ways and bounces inside it with its
// hemispherical internal reflectance: f_d = rho / (1 - R_int rho_or_1) t(cos_o) t(cos_i) /
// (eta^2 pi). t and R_int are tabulated at construction exactly as Mitsuba does (64 cosines,
// Gauss-Legendre over visible normals), so the two renderers evaluate the same BSDF.
// Reflects on its front only unless `two_sided`; symmetric.
#pragma once
#include <array>
#include <memory>

#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/lobe_choice.h"
#include "materials/microfacet.h"

namespace dualight {

inline constexpr int kRoughTransmittanceResolution = 64;

// The coat's directional transmittance t(cos) at cos = k / 63, and its internal reflectance.
struct RoughCoatTables {
  std::array<float, kRoughTransmittanceResolution> external_transmittance{};
  float internal_reflectance = 0.f;
};

struct RoughPlastic {
  Microfacet distribution;
  Color diffuse_reflectance{0.5f};
  Color specular_reflectance{1.f};
  float eta = 1.49f;
  bool nonlinear = false;
  bool two_sided = false;
  // Made by make_rough_plastic and shared by copies (it keeps the Bsdf variant small).
  std::shared_ptr<const RoughCoatTables> coat;
};

// A rough plastic with its tables (a few milliseconds: 64 x 32^2 and 64 x 128^2 quadrature
// points). The distribution must be isotropic, as Mitsuba requires.
RoughPlastic make_rough_plastic(const Microfacet& distribution, const Color& diffuse_reflectance,
                                const Color& specular_reflectance, float eta, bool nonlinear, bool two_sided);

constexpr BsdfFlags flags(const RoughPlastic&) {
  return BsdfFlags::Glossy | BsdfFlags::DiffuseReflection;
}
inline Color diffuse_reflectance(const RoughPlastic& b) { return b.diffuse_reflectance; }

namespace rough_plastic_detail {

inline float transmittance(const RoughPlastic& b, float cos_theta) {
  const float x = cos_theta * (kRoughTransmittanceResolution - 1);
  const int i = std::min(static_cast<int>(x), kRoughTransmittanceResolution - 2);
  const float t = x - static_cast<float>(i);
  const auto& table = b.coat->external_transmittance;
  return (1.f - t) * table[static_cast<size_t>(i)] + t * table[static_cast<size_t>(i + 1)];
}
inline float specular_probability(const RoughPlastic& b, float t_o) {
  const float s = average(b.specular_reflectance), d = average(b.diffuse_reflectance);
  const float w = s / (s + d);
  const float p_s = (1.f - t_o) * w, p_d = t_o * (1.f - w);
  return p_s + p_d > 0.f ? p_s / (p_s + p_d) : 1.f;
}

}  // namespace rough_plastic_detail

Color eval_f(const RoughPlastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
float pdf_w(const RoughPlastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
bool sample(const RoughPlastic& b, const Vec3& wo_in, Point2 u, TransportMode mode, BsdfSample& s);
inline DeltaLobe delta_lobe(const RoughPlastic&, const Vec3&, const Vec3&) { return {}; }
inline bool delta_direction(const RoughPlastic&, const Vec3&, bool, Vec3&) { return false; }

}  // namespace dualight
