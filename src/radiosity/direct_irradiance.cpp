#include "radiosity/direct_irradiance.h"

#include <cmath>
#include <stdexcept>

#include "core/parallel.h"

namespace dualight {

namespace {

// Barycentrics (b1, b2) of the centroids of an n x n split of a triangle.
std::vector<Point2> centroid_grid(int n) {
  std::vector<Point2> out;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n - i; ++j) {
      out.push_back({(i + 1.f / 3.f) / n, (j + 1.f / 3.f) / n});
      if (i + j <= n - 2) out.push_back({(i + 2.f / 3.f) / n, (j + 2.f / 3.f) / n});
    }
  }
  return out;
}

// Irradiance at p (on a patch of normal n) from one delta emitter, visibility included. Patches
// are one-sided, as the form factors and Mitsuba's diffuse BSDF: light behind the patch (a sun
// on a wall's outside) does not count.
Color irradiance_from(const Scene& scene, const Emitter& e, const Vec3& p, const Vec3& n) {
  LightSample ls;
  if (!sample_Li(e, 1.f, p, {0.5f, 0.5f}, ls)) return Color(0.f);
  const float cos_theta = dot(n, ls.wi);
  if (!(cos_theta > 0.f)) return Color(0.f);
  return scene.visible_point(p, n, ls.p) ? ls.Le * cos_theta : Color(0.f);
}

}  // namespace

std::vector<Color> direct_irradiance(const Scene& patches, int points_per_axis, int threads,
                                     RenderControl& control) {
  if (points_per_axis < 1 || points_per_axis > 64) throw std::invalid_argument("points_per_axis must be in [1, 64]");
  std::vector<const Emitter*> points;
  for (const Emitter& e : patches.emitters()) {
    if (is_delta_light(e)) points.push_back(&e);
  }
  const size_t n = patches.triangle_count();
  std::vector<Color> H(n, Color(0.f));
  control.total.store(n);
  if (points.empty()) return H;
  const std::vector<Point2> grid = centroid_grid(points_per_axis);
  parallel_for_each_index(threads, n, [&](size_t k) {
    if (control.cancelled()) return;
    const uint32_t prim = static_cast<uint32_t>(k);
    const Vec3 normal = patches.normal(prim);
    Color sum(0.f);
    for (const Point2 b : grid) {
      const Vec3 p = patches.vertex(prim, 0) * (1.f - b.u - b.v) + patches.vertex(prim, 1) * b.u +
                     patches.vertex(prim, 2) * b.v;
      for (const Emitter* e : points) sum += irradiance_from(patches, *e, p, normal);
    }
    H[k] = sum / static_cast<float>(grid.size());
    control.done.fetch_add(1, std::memory_order_relaxed);
  });
  return H;
}

}  // namespace dualight
