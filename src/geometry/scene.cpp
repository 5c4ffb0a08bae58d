#include "geometry/scene.h"

#include <limits>
#include <stdexcept>
#include <string>

namespace dualight {

Scene::Scene(std::vector<float> positions, std::vector<uint32_t> triangles, std::vector<uint32_t> material_of,
             std::vector<Material> materials)
    : positions_(std::move(positions)),
      triangles_(std::move(triangles)),
      material_of_(std::move(material_of)),
      materials_(std::move(materials)) {
  if (positions_.size() % 3 != 0 || triangles_.size() % 3 != 0) {
    throw std::invalid_argument("positions and triangles must hold 3 values per item");
  }
  const size_t n_vertices = positions_.size() / 3, n_triangles = triangles_.size() / 3;
  if (n_triangles == 0) throw std::invalid_argument("scene is empty: it has no triangles");
  if (material_of_.size() != n_triangles) {
    throw std::invalid_argument("material_of needs one entry per triangle");
  }
  for (const float x : positions_) {
    if (!std::isfinite(x)) throw std::invalid_argument("vertex positions must be finite");
  }
  for (const uint32_t i : triangles_) {
    if (i >= n_vertices) throw std::invalid_argument("triangle index out of range");
  }
  for (const uint32_t m : material_of_) {
    if (m >= materials_.size()) throw std::invalid_argument("material index out of range");
  }

  bounds_min_ = Vec3(std::numeric_limits<float>::infinity());
  bounds_max_ = -bounds_min_;
  for (size_t v = 0; v < n_vertices; ++v) {
    const Vec3 p(positions_[3 * v], positions_[3 * v + 1], positions_[3 * v + 2]);
    bounds_min_ = vmin(bounds_min_, p);
    bounds_max_ = vmax(bounds_max_, p);
  }

  normal_.resize(n_triangles);
  area_.resize(n_triangles);
  std::vector<double> emitter_power;
  for (uint32_t prim = 0; prim < n_triangles; ++prim) {
    const Vec3 c = cross(vertex(prim, 1) - vertex(prim, 0), vertex(prim, 2) - vertex(prim, 0));
    const float len = length(c);
    if (!(len > 0.f)) {
      throw std::invalid_argument("triangle " + std::to_string(prim) + " has zero area");
    }
    normal_[prim] = c / len;
    area_[prim] = 0.5f * len;
    const Color& Le = materials_[material_of_[prim]].emission;
    if (!is_black(Le)) {
      emissive_.push_back(prim);
      emitter_power.push_back(static_cast<double>(area_[prim]) * average(Le));
    }
  }
  emitter_pmf_by_prim_.assign(n_triangles, 0.f);
  if (!emissive_.empty()) {
    emitter_distribution_ = DiscreteDistribution(emitter_power);
    for (size_t i = 0; i < emissive_.size(); ++i) {
      emitter_pmf_by_prim_[emissive_[i]] = emitter_distribution_.pmf(i);
    }
  }
  accel_ = std::make_unique<EmbreeAccel>(positions_, triangles_);
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  const RayHit rh = accel_->intersect(ray);
  if (!rh.hit()) return false;
  const uint32_t prim = rh.prim;
  hit.p = vertex(prim, 0) * (1.f - rh.u - rh.v) + vertex(prim, 1) * rh.u + vertex(prim, 2) * rh.v;
  hit.n = normal_[prim];
  hit.t = rh.t;
  hit.prim = prim;
  hit.material = &materials_[material_of_[prim]];
  return true;
}

bool Scene::visible(const Vec3& p0, const Vec3& n0, const Vec3& p1, const Vec3& n1) const {
  const Vec3 d = p1 - p0;
  const Vec3 o0 = offset_ray_origin(p0, dot(n0, d) > 0.f ? n0 : -n0);
  const Vec3 o1 = offset_ray_origin(p1, dot(n1, d) < 0.f ? n1 : -n1);
  // Unnormalised direction: t in (0, 1) spans the segment; stop just short of the far end.
  Ray ray{o0, o1 - o0, 1.f - 1e-4f};
  return !accel_->occluded(ray);
}

EmitterSample Scene::sample_emitter(float u_select, Point2 u) const {
  const size_t i = emitter_distribution_.sample(u_select);
  const uint32_t prim = emissive_[i];
  const Point2 b = square_to_uniform_triangle(u);
  EmitterSample s;
  s.p = vertex(prim, 0) * (1.f - b.u - b.v) + vertex(prim, 1) * b.u + vertex(prim, 2) * b.v;
  s.n = normal_[prim];
  s.Le = materials_[material_of_[prim]].emission;
  s.pdf_a = emitter_distribution_.pmf(i) / area_[prim];
  return s;
}

float Scene::emitter_pdf_a(uint32_t prim) const { return emitter_pmf_by_prim_[prim] / area_[prim]; }

}  // namespace dualight
