// RoughDielectric's evaluation, density and sampling, out of line so that the BSDF dispatch
// (bsdf.h) stays small enough to inline on Lambertian scenes. See rough_dielectric.h.
#include "materials/rough_dielectric.h"

namespace dualight {

Color eval_f(const RoughDielectric& b, const Vec3& wo, const Vec3& wi, TransportMode mode) {
  using namespace rough_dielectric_detail;
  HalfVector h;
  if (!half_vector(b, wo, wi, h)) return Color(0.f);
  const float DG = microfacet_D(b.distribution, h.m) * smith_G(b.distribution, wo, wi, h.m);
  const float F = fresnel_dielectric(dot(wo, h.m), b.eta).R;
  if (h.reflect) return Color(F * DG / (4.f * std::abs(wo.z * wi.z)));
  const float scale = mode == TransportMode::Radiance ? 1.f / (h.eta * h.eta) : 1.f;
  const float denom = dot(wo, h.m) + h.eta * dot(wi, h.m);
  const float f = scale * (1.f - F) * DG * h.eta * h.eta * dot(wo, h.m) * dot(wi, h.m) / (wo.z * wi.z * denom * denom);
  return Color(std::abs(f));
}

float pdf_w(const RoughDielectric& b, const Vec3& wo, const Vec3& wi, TransportMode) {
  using namespace rough_dielectric_detail;
  HalfVector h;
  if (!half_vector(b, wo, wi, h)) return 0.f;
  const Vec3 wo_up = wo.z > 0.f ? wo : -wo;
  const float p_reflect = reflect_probability(b, wo);
  return (h.reflect ? p_reflect : 1.f - p_reflect) * visible_normal_pdf(b.distribution, wo_up, h.m) *
         half_jacobian(wo, wi, h);
}

bool sample(const RoughDielectric& b, const Vec3& wo, Point2 u, TransportMode mode, BsdfSample& s) {
  if (wo.z == 0.f) return false;
  const bool reflect = choose_lobe(u.u, rough_dielectric_detail::reflect_probability(b, wo));
  const Vec3 m = sample_visible_normal(b.distribution, wo.z > 0.f ? wo : -wo, u);
  const float cos_om = dot(wo, m);
  if (reflect) {
    s.wi = reflect_about(wo, m);
  } else {
    const Fresnel F = fresnel_dielectric(cos_om, b.eta);
    if (F.R >= 1.f) return false;  // total internal reflection at this microfacet
    s.wi = refract_about(wo, m, cos_om, F);
  }
  if (reflect != (s.wi.z * wo.z > 0.f)) return false;
  s.eta = reflect ? 1.f : (wo.z > 0.f ? b.eta : 1.f / b.eta);  // as the half vector's (rough_dielectric.h)
  return finish_sample(b, wo, s.wi, mode, s);
}

}  // namespace dualight
