// Points of a triangle in barycentrics: the centroids of its split into n x n similar triangles
// (the midpoint rule of equal-area parts, for means over a triangle), and the barycentrics of a
// point in its plane (the Gram system of its two edges).
#pragma once
#include <vector>

#include "core/sampling.h"
#include "core/vec3.h"

namespace dualight {

// Barycentrics (b1, b2) of corners 1 and 2 of the centroids of an n x n split of a triangle:
// (i + 1/3, j + 1/3) / n for the n (n + 1) / 2 upright parts and (i + 2/3, j + 2/3) / n for the
// n (n - 1) / 2 inverted ones, each upright part followed by its inverted neighbour.
inline std::vector<Point2> centroid_grid(int n) {
  std::vector<Point2> out;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n - i; ++j) {
      out.push_back({(i + 1.f / 3.f) / n, (j + 1.f / 3.f) / n});
      if (i + j <= n - 2) out.push_back({(i + 2.f / 3.f) / n, (j + 2.f / 3.f) / n});
    }
  }
  return out;
}

// Barycentrics (b1, b2) of corners 1 and 2 of p, a point in the plane of triangle (p0, p1, p2);
// (0, 0) for a degenerate triangle.
inline Point2 barycentrics(const Vec3& p0, const Vec3& p1, const Vec3& p2, const Vec3& p) {
  const Vec3 e1 = p1 - p0, e2 = p2 - p0, d = p - p0;
  const float d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), dp1 = dot(d, e1), dp2 = dot(d, e2);
  const float det = d11 * d22 - d12 * d12;
  if (det == 0.f) return {0.f, 0.f};
  return {(d22 * dp1 - d12 * dp2) / det, (d11 * dp2 - d12 * dp1) / det};
}

}  // namespace dualight
