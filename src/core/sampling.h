// Warps from the unit square and the MIS heuristics; each warp's pdf sits beside it.
#pragma once
#include <cmath>

#include "core/vec3.h"

namespace dualight {

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kInvPi = 0.31830988618379067154f;

struct Point2 {
  float u, v;
};

// Uniform points on the unit disk, Shirley and Chiu's concentric map [Shirley-Chiu 1997];
// density 1 / pi.
inline Point2 square_to_uniform_disk(Point2 p) {
  const float a = 2.f * p.u - 1.f, b = 2.f * p.v - 1.f;
  float r = 0.f, phi = 0.f;
  if (a != 0.f || b != 0.f) {
    if (a * a > b * b) {
      r = a;
      phi = (kPi / 4.f) * (b / a);
    } else {
      r = b;
      phi = (kPi / 2.f) - (kPi / 4.f) * (a / b);
    }
  }
  return {r * std::cos(phi), r * std::sin(phi)};
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

// [Veach 1997, eq. 9.13] with beta = 2; pdfs of one sample per technique.
inline float power_heuristic(float pdf_a, float pdf_b) {
  const float a2 = pdf_a * pdf_a, b2 = pdf_b * pdf_b;
  return a2 > 0.f ? a2 / (a2 + b2) : 0.f;
}

}  // namespace dualight
