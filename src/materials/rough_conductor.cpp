// RoughConductor's evaluation, density and sampling, out of line so that the BSDF dispatch
// (bsdf.h) stays small enough to inline on Lambertian scenes. See rough_conductor.h.
#include "materials/rough_conductor.h"

namespace dualight {

Color eval_f(const RoughConductor& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return Color(0.f);
  const Vec3 m = normalize(wo + wi);
  const float DG = microfacet_D(b.distribution, m) * smith_G(b.distribution, wo, wi, m);
  if (!(DG > 0.f)) return Color(0.f);
  return fresnel_conductor(dot(wo, m), b.eta, b.k) * b.specular_reflectance * (DG / (4.f * wo.z * wi.z));
}

float pdf_w(const RoughConductor& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return 0.f;
  const Vec3 m = normalize(wo + wi);
  // D_wo(m) / (4 |wi . m|), and wi . m = wo . m for a reflection.
  return microfacet_D(b.distribution, m) * smith_G1(b.distribution, wo, m) / (4.f * wo.z);
}

bool sample(const RoughConductor& b, const Vec3& wo_in, Point2 u, TransportMode, BsdfSample& s) {
  Vec3 wo = wo_in;
  bool flipped = false;
  if (!to_front(b.two_sided, wo, flipped)) return false;
  const Vec3 m = sample_visible_normal(b.distribution, wo, u);
  Vec3 wi = reflect_about(wo, m);
  if (!(wi.z > 0.f)) return false;
  s.pdf_w = microfacet_D(b.distribution, m) * smith_G1(b.distribution, wo, m) / (4.f * wo.z);
  if (!(s.pdf_w > 0.f)) return false;
  // f cos_i / pdf = F G1(wi) with visible-normal sampling.
  s.weight = fresnel_conductor(dot(wo, m), b.eta, b.k) * b.specular_reflectance * smith_G1(b.distribution, wi, m);
  if (flipped) wi.z = -wi.z;
  s.wi = wi;
  s.delta = false;
  return true;
}

}  // namespace dualight
