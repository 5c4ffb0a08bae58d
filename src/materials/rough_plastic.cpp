// The tables of rough plastic's coat, computed as Mitsuba 3's `roughplastic` does
// (eval_transmittance / eval_reflectance in its microfacet.h): the fraction of light from
// direction w that a rough dielectric interface transmits (reflects), integrated over the
// visible normals with a product Gauss-Legendre rule on the sampling square, including the
// masking of the scattered direction.
#include "materials/rough_plastic.h"

#include "core/quadrature.h"

namespace dualight {

namespace {

// Transmitted (or, with `reflected`, reflected) fraction of light arriving from w (w.z > 0) at a
// rough interface of relative IOR eta.
float interface_albedo(const Microfacet& d, const Vec3& w, float eta, bool reflected) {
  const Quadrature q = gauss_legendre(eta > 1.f ? 32 : 128);
  double sum = 0.0;
  for (size_t i = 0; i < q.nodes.size(); ++i) {
    for (size_t j = 0; j < q.nodes.size(); ++j) {
      const Point2 u{static_cast<float>(0.5 * q.nodes[i] + 0.5), static_cast<float>(0.5 * q.nodes[j] + 0.5)};
      const Vec3 m = sample_visible_normal(d, w, u);
      const float cos_wm = dot(w, m);
      const Fresnel F = fresnel_dielectric(cos_wm, eta);
      float value = 0.f;
      if (reflected) {
        const Vec3 r = reflect_about(w, m);
        if (r.z > 0.f) value = smith_G1(d, r, m) * F.R;
      } else if (F.R < 1.f) {
        const Vec3 t = refract_about(w, m, cos_wm, F);
        if (t.z < 0.f) value = smith_G1(d, t, m) * (1.f - F.R);
      }
      sum += value * q.weights[i] * q.weights[j] * 0.25;
    }
  }
  return static_cast<float>(sum);
}

}  // namespace

RoughPlastic make_rough_plastic(const Microfacet& distribution, const Color& diffuse_reflectance,
                                const Color& specular_reflectance, float eta, bool nonlinear, bool two_sided) {
  auto tables = std::make_shared<RoughCoatTables>();
  double internal = 0.0;
  for (int k = 0; k < kRoughTransmittanceResolution; ++k) {
    const float mu = std::max(1e-6f, static_cast<float>(k) / (kRoughTransmittanceResolution - 1));
    const Vec3 w(std::sqrt(1.f - mu * mu), 0.f, mu);
    tables->external_transmittance[static_cast<size_t>(k)] = interface_albedo(distribution, w, eta, false);
    internal += interface_albedo(distribution, w, 1.f / eta, true) * mu;
  }
  // Mitsuba's estimate of 2 * integral of R(mu) mu dmu: twice the mean over the 64 cosines.
  tables->internal_reflectance = static_cast<float>(2.0 * internal / kRoughTransmittanceResolution);
  return {distribution, diffuse_reflectance, specular_reflectance, eta, nonlinear, two_sided, std::move(tables)};
}

Color eval_f(const RoughPlastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  using namespace rough_plastic_detail;
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return Color(0.f);
  const Vec3 m = normalize(wo + wi);
  const float DG = microfacet_D(b.distribution, m) * smith_G(b.distribution, wo, wi, m);
  const Color coat = b.specular_reflectance * (fresnel_dielectric(dot(wo, m), b.eta).R * DG / (4.f * wo.z * wi.z));
  const Color& rho = b.diffuse_reflectance;
  const Color denom = b.nonlinear ? Color(1.f) - rho * b.coat->internal_reflectance : Color(1.f - b.coat->internal_reflectance);
  const float T = transmittance(b, wo.z) * transmittance(b, wi.z) * kInvPi / (b.eta * b.eta);
  return coat + rho / denom * T;
}

float pdf_w(const RoughPlastic& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode) {
  Vec3 wo = wo_in, wi = wi_in;
  if (!pair_to_front(b.two_sided, wo, wi)) return 0.f;
  const float p_s = rough_plastic_detail::specular_probability(b, rough_plastic_detail::transmittance(b, wo.z));
  const Vec3 m = normalize(wo + wi);
  const float coat = microfacet_D(b.distribution, m) * smith_G1(b.distribution, wo, m) / (4.f * wo.z);
  return p_s * coat + (1.f - p_s) * cosine_hemisphere_pdf(wi.z);
}

bool sample(const RoughPlastic& b, const Vec3& wo_in, Point2 u, TransportMode mode, BsdfSample& s) {
  Vec3 wo = wo_in;
  bool flipped = false;
  if (!to_front(b.two_sided, wo, flipped)) return false;
  const float p_s = rough_plastic_detail::specular_probability(b, rough_plastic_detail::transmittance(b, wo.z));
  Vec3 wi = choose_lobe(u.u, p_s) ? reflect_about(wo, sample_visible_normal(b.distribution, wo, u))
                                  : square_to_cosine_hemisphere(u);
  if (!(wi.z > 0.f)) return false;
  if (flipped) wi.z = -wi.z;
  return finish_sample(b, wo_in, wi, mode, s);
}

}  // namespace dualight
