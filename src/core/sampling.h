// Warps from the unit square and the MIS heuristics; each warp's pdf sits beside it.
#pragma once
#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace dualight {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

struct Point2 {
  float u, v;
};

// sin x and cos x for |x| <= pi / 4, within 1 ulp of the correctly rounded values: Cephes'
// sinf and cosf polynomials [Moshier 1992], without their range reduction (the concentric map's
// angles need none). Inline, where std::sin and std::cos call libm.
inline void sincos_within_pi_over_4(float x, float& s, float& c) {
  const float z = x * x;
  s = x + x * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
  c = 1.f - 0.5f * z + z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
}

// Uniform points on the unit disk, Shirley and Chiu's concentric map [Shirley-Chiu 1997];
// density 1 / pi. In the sectors around the x axis the angle is (pi / 4) b / a; around the y
// axis it is pi / 2 - (pi / 4) a / b, whose cosine and sine are the sine and cosine of
// (pi / 4) a / b.
inline Point2 square_to_uniform_disk(Point2 p) {
  const float a = 2.f * p.u - 1.f, b = 2.f * p.v - 1.f;
  if (a == 0.f && b == 0.f) return {0.f, 0.f};
  const bool x_sector = a * a > b * b;
  const float r = x_sector ? a : b;
  float s, c;
  sincos_within_pi_over_4((kPi / 4.f) * ((x_sector ? b : a) / r), s, c);
  return x_sector ? Point2{r * c, r * s} : Point2{r * s, r * c};
}

// Cosine-weighted hemisphere around +z (Malley's method on the concentric disk).
inline Vec3 square_to_cosine_hemisphere(Point2 p) {
  const Point2 d = square_to_uniform_disk(p);
  return {d.u, d.v, std::sqrt(std::max(0.f, 1.f - d.u * d.u - d.v * d.v))};
}
inline float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.f ? cos_theta * kInvPi : 0.f; }

// Uniform barycentrics (b1, b2) on a triangle; b0 = 1 - b1 - b2.
inline Point2 square_to_uniform_triangle(Point2 p) {
  const float su = std::sqrt(p.u);
  return {p.v * su, 1.f - su};
}

// Uniform directions on the unit sphere (z uniform in [-1, 1], Archimedes), density 1 / (4 pi).
inline Vec3 square_to_uniform_sphere(Point2 p) {
  const float z = 1.f - 2.f * p.v;
  const float r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.f * kPi * p.u;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline constexpr float kUniformSpherePdf = 0.25f * kInvPi;

// Uniform directions in the cone of half-angle acos(cos_max) around +z, density
// 1 / (2 pi (1 - cos_max)).
inline Vec3 square_to_uniform_cone(Point2 p, float cos_max) {
  const float z = 1.f - p.v * (1.f - cos_max);
  const float r = std::sqrt(std::max(0.f, 1.f - z * z)), phi = 2.f * kPi * p.u;
  return {r * std::cos(phi), r * std::sin(phi), z};
}
inline float uniform_cone_pdf(float cos_max) { return 0.5f * kInvPi / (1.f - cos_max); }

// A point of [0, 1) with density proportional to (1 - x) a + x b (a, b >= 0), by inverting its
// CDF, the root of a quadratic written so that it does not cancel (pbrt-v4's SampleLinear); u
// where both are 0.
inline float sample_linear(float u, float a, float b) {
  if (!(a + b > 0.f)) return u;
  const float x = u * (a + b) / (a + std::sqrt((1.f - u) * a * a + u * b * b));
  return std::min(x, 0x1.fffffep-1f);
}

// [Veach 1997, eq. 9.13] with beta = 2; pdfs of one sample per technique.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a2 = pdf_a * pdf_a, b2 = pdf_b * pdf_b;
  return a2 > 0.f ? a2 / (a2 + b2) : 0.f;
}

}  // namespace dualight
