// Smooth plastic, as Mitsuba 3's `plastic`: a diffuse base under a smooth dielectric coat of
// relative IOR eta [Weidlich and Wilkie 2007; Mitsuba 3 docs]. The coat reflects F(cos_o) in the
// mirror direction (a Dirac lobe, times `specular_reflectance`); light that enters scatters in
// the base, bounces inside the coat (internal reflectance Fdr, hemispherically averaged) and
// leaves through it: f_d = rho / (1 - Fdr_int rho_or_1) (1 - F_o)(1 - F_i) / (eta^2 pi), with
// rho_or_1 = rho when `nonlinear` (the base's colour deepens with each bounce) and 1 otherwise.
// Reflects on its front only unless `two_sided`. The lobe is picked with Mitsuba's weights
// (Fresnel times the specular and diffuse reflectances' means).
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/lobe_choice.h"

namespace dualight {

struct Plastic {
  Color diffuse_reflectance{0.5f};
  Color specular_reflectance{1.f};
  float eta = 1.49f;  // polypropylene / air
  bool nonlinear = false;
  bool two_sided = false;
};

constexpr BsdfFlags flags(const Plastic&) {
  return BsdfFlags::SpecularReflection | BsdfFlags::DiffuseReflection;
}
inline Color diffuse_reflectance(const Plastic& b) { return b.diffuse_reflectance; }

namespace plastic_detail {

// The base's albedo after the internal bounces, divided by eta^2 pi (f_d without the coat's
// transmittances).
inline Color base_term(const Color& rho, float eta, bool nonlinear) {
  const float fdr = fresnel_diffuse_reflectance(1.f / eta);
  const Color denom = nonlinear ? Color(1.f) - rho * fdr : Color(1.f - fdr);
  return rho / denom * (kInvPi / (eta * eta));
}
// The probability of picking the coat's mirror lobe at wo (front side).
inline float specular_probability(float F_o, const Color& diffuse, const Color& specular) {
  const float s = average(specular), d = average(diffuse);
  const float w = s / (s + d);
  const float p_s = F_o * w, p_d = (1.f - F_o) * (1.f - w);
  return p_s + p_d > 0.f ? p_s / (p_s + p_d) : 1.f;
}

}  // namespace plastic_detail

Color eval_f(const Plastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
float pdf_w(const Plastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
bool sample(const Plastic& b, const Vec3& wo_in, Point2 u, TransportMode mode, BsdfSample& s);
inline DeltaLobe delta_lobe(const Plastic& b, const Vec3& wo, const Vec3& wi) {
  DeltaLobe lobe;
  Vec3 o = wo, i = wi;
  lobe.refraction = !same_hemisphere(wo, wi);
  if (!pair_to_front(b.two_sided, o, i)) return lobe;
  const float F_o = fresnel_dielectric(o.z, b.eta).R;
  lobe.coef = b.specular_reflectance * F_o;
  lobe.prob = plastic_detail::specular_probability(F_o, b.diffuse_reflectance, b.specular_reflectance);
  return lobe;
}
inline bool delta_direction(const Plastic& b, const Vec3& wo, bool refraction, Vec3& wi) {
  return front_mirror_direction(b.two_sided, wo, refraction, wi);
}

}  // namespace dualight
