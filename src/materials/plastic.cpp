// Plastic's evaluation, density and sampling, out of line so that the BSDF dispatch
// (bsdf.h) stays small enough to inline on Lambertian scenes. See plastic.h.
#include "materials/plastic.h"

namespace dualight {

Color eval_f(const Plastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return Color(0.f);
  const float T = (1.f - fresnel_dielectric(wo.z, b.eta).R) * (1.f - fresnel_dielectric(wi.z, b.eta).R);
  return plastic_detail::base_term(b.diffuse_reflectance, b.eta, b.nonlinear) * T;
}

float pdf_w(const Plastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return 0.f;
  const float p_s = plastic_detail::specular_probability(fresnel_dielectric(wo.z, b.eta).R, b.diffuse_reflectance,
                                                         b.specular_reflectance);
  return (1.f - p_s) * cosine_hemisphere_pdf(wi.z);
}

bool sample(const Plastic& b, const Vec3& wo_in, Point2 u, TransportMode mode, BsdfSample& s) {
  Vec3 wo = wo_in;
  bool flipped = false;
  if (!to_front(b.two_sided, wo, flipped)) return false;
  const float F_o = fresnel_dielectric(wo.z, b.eta).R;
  const float p_s = plastic_detail::specular_probability(F_o, b.diffuse_reflectance, b.specular_reflectance);
  if (choose_lobe(u.u, p_s)) {
    s.wi = reflect_local(wo_in);
    s.pdf_w = p_s;
    s.weight = b.specular_reflectance * (F_o / p_s);
    s.delta = true;
    return true;
  }
  Vec3 wi = square_to_cosine_hemisphere(u);
  if (flipped) wi.z = -wi.z;
  return finish_sample(b, wo_in, wi, mode, s);
}

}  // namespace dualight
