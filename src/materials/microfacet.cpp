// Sampling the distribution of visible normals: GGX by projecting a uniform disk onto the
// stretched hemisphere [Heitz 2018], Beckmann by inverting the slope distribution's CDF in the
// erf domain with Newton steps [Heitz and d'Eon 2014, sec. 4; the smooth numerical inversion
// Jakob uses in Mitsuba, which keeps primary-sample-space MLT continuous].
#include "materials/microfacet.h"

namespace dualight {

float erfinv(float x) {
  float w = -std::log(std::max((1.f - x) * (1.f + x), 1e-30f));
  float p;
  if (w < 5.f) {
    w -= 2.5f;
    p = 2.81022636e-08f;
    for (const float c : {3.43273939e-07f, -3.5233877e-06f, -4.39150654e-06f, 0.00021858087f, -0.00125372503f,
                          -0.00417768164f, 0.246640727f, 1.50140941f}) {
      p = c + p * w;
    }
  } else {
    w = std::sqrt(w) - 3.f;
    p = -0.000200214257f;
    for (const float c : {0.000100950558f, 0.00134934322f, -0.00367342844f, 0.00573950773f, -0.0076224613f,
                          0.00943887047f, 1.00167406f, 2.83297682f}) {
      p = c + p * w;
    }
  }
  return p * x;
}

namespace {

// Slopes of the visible normals of the unit-roughness Beckmann surface seen at cos_theta
// (direction in the xz plane).
Point2 beckmann_visible_slope(float cos_theta, Point2 u) {
  const float sin_theta = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  const float tan_theta = sin_theta / cos_theta, cot_theta = cos_theta / sin_theta;
  const float max_x = std::erf(cot_theta);  // the search interval, in the erf domain
  u.u = std::clamp(u.u, 1e-6f, 1.f - 1e-6f);
  u.v = std::clamp(u.v, 1e-6f, 1.f - 1e-6f);
  // Start from the exact answer at grazing incidence, the most nonlinear case.
  float x = max_x - (max_x + 1.f) * std::erf(std::sqrt(-std::log(u.u)));
  const float inv_sqrt_pi = 0.56418958354775628f;
  const float target = u.u * (1.f + max_x + inv_sqrt_pi * tan_theta * std::exp(-cot_theta * cot_theta));
  for (int i = 0; i < 3; ++i) {
    const float slope = erfinv(x);
    const float value = 1.f + x + inv_sqrt_pi * tan_theta * std::exp(-slope * slope) - target;
    x -= value / (1.f - slope * tan_theta);
  }
  return {erfinv(x), erfinv(2.f * u.v - 1.f)};
}

Vec3 beckmann_visible_normal(const Microfacet& d, const Vec3& wo, Point2 u) {
  const Vec3 w = normalize(Vec3(d.alpha_u * wo.x, d.alpha_v * wo.y, wo.z));  // stretch to alpha 1
  const float sin_theta = std::sqrt(std::max(0.f, w.x * w.x + w.y * w.y));
  const float cos_phi = sin_theta > 0.f ? w.x / sin_theta : 1.f, sin_phi = sin_theta > 0.f ? w.y / sin_theta : 0.f;
  const Point2 s = beckmann_visible_slope(w.z, u);
  const float sx = (cos_phi * s.u - sin_phi * s.v) * d.alpha_u;  // rotate and unstretch
  const float sy = (sin_phi * s.u + cos_phi * s.v) * d.alpha_v;
  return normalize(Vec3(-sx, -sy, 1.f));
}

Vec3 ggx_visible_normal(const Microfacet& d, const Vec3& wo, Point2 u) {
  const Vec3 vh = normalize(Vec3(d.alpha_u * wo.x, d.alpha_v * wo.y, wo.z));
  const float len2 = vh.x * vh.x + vh.y * vh.y;
  const Vec3 t1 = len2 > 0.f ? Vec3(-vh.y, vh.x, 0.f) / std::sqrt(len2) : Vec3(1.f, 0.f, 0.f);
  const Vec3 t2 = cross(vh, t1);
  const float r = std::sqrt(u.u), phi = 2.f * kPi * u.v;
  const float p1 = r * std::cos(phi);
  const float s = 0.5f * (1.f + vh.z);
  const float p2 = (1.f - s) * std::sqrt(std::max(0.f, 1.f - p1 * p1)) + s * r * std::sin(phi);
  const Vec3 nh = t1 * p1 + t2 * p2 + vh * std::sqrt(std::max(0.f, 1.f - p1 * p1 - p2 * p2));
  return normalize(Vec3(d.alpha_u * nh.x, d.alpha_v * nh.y, std::max(1e-6f, nh.z)));
}

}  // namespace

Vec3 sample_visible_normal(const Microfacet& d, const Vec3& wo, Point2 u) {
  return d.type == MicrofacetType::GGX ? ggx_visible_normal(d, wo, u) : beckmann_visible_normal(d, wo, u);
}

}  // namespace dualight
