// Lower bounds on the distance between triangles, from separating axes: the gap between two
// triangles' extents along any unit axis is at most their distance (the measure behind the
// separating axis test of Gottschalk, Lin and Manocha's OBBTree, SIGGRAPH 1996). The axes
// tried are the coordinate axes (the bounding boxes' distance) and the two triangles' normals,
// which give the exact distance between parallel or box-separated faces, the common case of a
// light below a ceiling. Computed in double; the float result is rounded down. (The normals
// are float unit vectors, so a gap along one is off by a few parts in 1e7: far inside the
// factor of 2 that Scene::visible keeps from the bound.)
#include "geometry/surface_clearance.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/scene.h"

namespace dualight {
namespace {

struct Interval {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
};

double gap(const Interval& a, const Interval& b) { return std::max({0.0, b.lo - a.hi, a.lo - b.hi}); }

double dot_d(const Vec3& a, const Vec3& b) {
  return static_cast<double>(a.x) * b.x + static_cast<double>(a.y) * b.y + static_cast<double>(a.z) * b.z;
}

Interval extent_along(const Scene& scene, uint32_t prim, const Vec3& axis) {
  Interval e;
  for (int k = 0; k < 3; ++k) {
    const double s = dot_d(axis, scene.vertex(prim, k));
    e.lo = std::min(e.lo, s), e.hi = std::max(e.hi, s);
  }
  return e;
}

struct Box {
  Interval axis[3];
};

Box box_of(const Scene& scene, uint32_t prim) {
  Box b;
  for (int a = 0; a < 3; ++a) {
    for (int k = 0; k < 3; ++k) {
      const double s = scene.vertex(prim, k)[a];
      b.axis[a].lo = std::min(b.axis[a].lo, s), b.axis[a].hi = std::max(b.axis[a].hi, s);
    }
  }
  return b;
}

double box_distance(const Box& a, const Box& b) {
  double d2 = 0.0;
  for (int k = 0; k < 3; ++k) d2 += gap(a.axis[k], b.axis[k]) * gap(a.axis[k], b.axis[k]);
  return std::sqrt(d2);
}

// The least |coordinate| any point of the triangle has on its largest axis: what Scene::visible's
// filter tolerance (1e-5 of max(1, the target point's largest |coordinate|)) is at least.
double least_magnitude(const Box& b) {
  double m = 0.0;
  for (const Interval& i : b.axis) {
    if (i.lo > 0.0 || i.hi < 0.0) m = std::max(m, std::min(std::abs(i.lo), std::abs(i.hi)));
  }
  return m;
}

bool coplanar(const Scene& scene, uint32_t target, uint32_t prim, double slack) {
  if (std::abs(dot(scene.normal(target), scene.normal(prim))) < 1.f - 1e-5f) return false;  // as the filter
  const Vec3 n = scene.normal(target), v0 = scene.vertex(target, 0);
  for (int k = 0; k < 3; ++k) {
    if (std::abs(dot_d(n, scene.vertex(prim, k) - v0)) > slack) return false;
  }
  return true;
}

float rounded_down(double x) {
  const float f = static_cast<float>(std::min(x, static_cast<double>(std::numeric_limits<float>::max())));
  return static_cast<double>(f) > x ? std::nextafter(f, 0.f) : f;
}

float clearance(const Scene& scene, const std::vector<Box>& boxes, uint32_t target) {
  const double slack = kCoplanarSlack * std::max(1.0, least_magnitude(boxes[target]));
  const Interval along_n = extent_along(scene, target, scene.normal(target));
  double c = std::numeric_limits<double>::infinity();
  for (uint32_t prim = 0; prim < boxes.size() && c > 0.0; ++prim) {
    if (prim == target) continue;
    const double d_box = box_distance(boxes[target], boxes[prim]);
    if (d_box >= c || coplanar(scene, target, prim, slack)) continue;
    const Vec3 m = scene.normal(prim);
    const double d = std::max({d_box, gap(along_n, extent_along(scene, prim, scene.normal(target))),
                               gap(extent_along(scene, target, m), extent_along(scene, prim, m))});
    c = std::min(c, d);
  }
  return rounded_down(c);
}

}  // namespace

std::vector<float> emitter_clearances(const Scene& scene, uint64_t max_pairs) {
  const size_t n = scene.triangle_count();
  std::vector<float> c(n, 0.f);
  uint64_t emitting = 0;
  for (uint32_t prim = 0; prim < n; ++prim) emitting += scene.emitter_at(prim) != nullptr ? 1 : 0;
  if (emitting == 0 || emitting * n > max_pairs) return c;
  std::vector<Box> boxes(n);
  for (uint32_t prim = 0; prim < n; ++prim) boxes[prim] = box_of(scene, prim);
  for (uint32_t prim = 0; prim < n; ++prim) {
    if (scene.emitter_at(prim) != nullptr) c[prim] = clearance(scene, boxes, prim);
  }
  return c;
}

}  // namespace dualight
