#include "geometry/scene.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include "geometry/surface_clearance.h"

namespace dualight {

// The unit normal and twice the area of a triangle whose cross product's squared length leaves
// float's range (edges beyond about 1.4e9 overflow it, below about 1e-10 underflow): in double.
// A Cornell box scaled by 1e7 had normals of 0 and infinite areas, and its direct light failed.
std::pair<Vec3, float> Scene::normal_and_double_area(uint32_t prim) const {
  double e[2][3];
  for (int k = 0; k < 2; ++k) {
    for (int a = 0; a < 3; ++a) e[k][a] = static_cast<double>(vertex(prim, k + 1)[a]) - vertex(prim, 0)[a];
  }
  const double c[3] = {e[0][1] * e[1][2] - e[0][2] * e[1][1], e[0][2] * e[1][0] - e[0][0] * e[1][2],
                       e[0][0] * e[1][1] - e[0][1] * e[1][0]};
  const double len = std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
  if (!(len > 0.0)) return {Vec3(0.f), 0.f};
  return {Vec3(static_cast<float>(c[0] / len), static_cast<float>(c[1] / len), static_cast<float>(c[2] / len)),
          static_cast<float>(len)};
}

// The emitter on triangle `prim` (its normal and area known): its material's radiance, or its
// radiance texture, whose mean over the triangle is then the emitter's power.
AreaEmitter Scene::area_emitter(uint32_t prim) const {
  const Material& m = material(prim);
  AreaEmitter e{vertex(prim, 0), vertex(prim, 1), vertex(prim, 2), plane_[prim].n, area_[prim], prim, m.emission};
  e.uv0 = surface_uv(prim, 0.f, 0.f);
  e.uv1 = surface_uv(prim, 1.f, 0.f);
  e.uv2 = surface_uv(prim, 0.f, 1.f);
  if (m.emission_texture) {
    e.texture = &*m.emission_texture;
    e.Le = mean_rgb_over_triangle(*e.texture, e.uv0, e.uv1, e.uv2);
    if (!(e.Le.x >= 0.f && e.Le.y >= 0.f && e.Le.z >= 0.f && std::isfinite(max_component(e.Le)))) {
      throw std::invalid_argument("emission textures must be finite and >= 0");
    }
  }
  return e;
}

Scene::Scene(std::vector<float> positions, std::vector<uint32_t> triangles, std::vector<uint32_t> material_of,
             std::vector<Material> materials, std::vector<Emitter> emitters, std::vector<float> normals,
             std::vector<float> uvs, bool robust_intersections)
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
  set_vertex_normals(normals);
  set_vertex_uvs(std::move(uvs));

  bounds_min_ = Vec3(std::numeric_limits<float>::infinity());
  bounds_max_ = -bounds_min_;
  for (size_t v = 0; v < n_vertices; ++v) {
    const Vec3 p(positions_[3 * v], positions_[3 * v + 1], positions_[3 * v + 2]);
    bounds_min_ = vmin(bounds_min_, p);
    bounds_max_ = vmax(bounds_max_, p);
  }
  sphere_ = dualight::bounding_sphere(bounds_min_, bounds_max_);
  const float extent = max_component(bounds_max_ - bounds_min_);
  if (extent < 1.f) offset_scale_ = std::exp2(std::floor(std::log2(extent)));
  eye_clearance_ = 1e-6f * extent;

  plane_.resize(n_triangles);
  area_.resize(n_triangles);
  emitter_of_prim_.assign(n_triangles, kNoEmitter);
  for (uint32_t prim = 0; prim < n_triangles; ++prim) {
    const Vec3 c = cross(vertex(prim, 1) - vertex(prim, 0), vertex(prim, 2) - vertex(prim, 0));
    float len = length(c);
    Vec3 normal = c / len;
    if (!std::isfinite(len) || !(len > 1e-30f)) std::tie(normal, len) = normal_and_double_area(prim);
    if (!(len > 0.f)) {
      throw std::invalid_argument("triangle " + std::to_string(prim) + " has zero area");
    }
    plane_[prim] = {normal, vertex(prim, 0)};
    area_[prim] = 0.5f * len;
    if (material(prim).emits()) {
      emitter_of_prim_[prim] = static_cast<uint32_t>(emitters_.size());
      emitters_.push_back(area_emitter(prim));
    }
  }
  const size_t emitter_triangles = emitters_.size();
  for (Emitter& e : emitters) {
    if (has_any(flags(e), EmitterFlags::Surface)) {
      throw std::invalid_argument("surface emitters come from the materials' emission, not the emitter list");
    }
    attach_scene(e, sphere_);
    const double p = power(e);
    if (!(p >= 0.0 && std::isfinite(p))) throw std::invalid_argument("emitter power must be finite and >= 0");
    emitters_.push_back(std::move(e));
  }
  for (const Emitter& e : emitters_) {
    hittable_emitter_ = hittable_emitter_ || !is_delta_light(e);
    if (!is_infinite(e) || is_delta_direction(e)) continue;
    // As Mitsuba 3 ("Only one environment emitter can be specified per scene"): the sky a ray
    // escapes to is one emitter, whose density BDPT's vertex at infinity carries.
    if (environment_ != nullptr) throw std::invalid_argument("a scene takes one environment (constant or envmap)");
    environment_ = &e;
  }
  emitter_sampler_ = PowerEmitterSampler(emitters_);
  MaterialFeatures used;
  for (const uint32_t m : material_of_) {
    const BsdfFlags f = flags(materials_[m].bsdf);
    used.specular = used.specular || has_specular(f);
    used.transmission = used.transmission || has_transmission(f);
    used.all_diffuse = used.all_diffuse && is_diffuse_reflector(f);
    used.mixed_delta = used.mixed_delta || mixes_delta(f);
  }
  std::vector<Vec3> plane_normals(plane_.size());  // for the scene's features alone
  std::transform(plane_.begin(), plane_.end(), plane_normals.begin(), [](const TrianglePlane& p) { return p.n; });
  features_ = compute_scene_features(positions_, triangles_, plane_normals, used, emitter_triangles);
  robust_intersections_ = robust_intersections;
  accel_ = std::make_unique<EmbreeAccel>(positions_, triangles_, robust_intersections);
  clearance_ = emitter_clearances(*this);
}

void Scene::set_vertex_normals(const std::vector<float>& normals) {
  if (normals.empty()) return;
  if (normals.size() != positions_.size()) throw std::invalid_argument("normals must hold 3 values per vertex");
  vertex_normal_.resize(normals.size() / 3);
  for (size_t v = 0; v < vertex_normal_.size(); ++v) {
    const Vec3 n(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    const float len = length(n);
    if (!std::isfinite(len)) throw std::invalid_argument("vertex normals must be finite");
    vertex_normal_[v] = len > 0.f ? n / len : Vec3(0.f);
  }
  smooth_.resize(triangles_.size() / 3);
  for (size_t prim = 0; prim < smooth_.size(); ++prim) {
    bool all = true;
    for (int k = 0; k < 3; ++k) all = all && !is_black(vertex_normal_[triangles_[3 * prim + k]]);
    smooth_[prim] = all;
  }
}

Vec3 Scene::interpolated_normal(uint32_t prim, float u, float v) const {
  const uint32_t* t = &triangles_[3 * prim];
  const Vec3 n = vertex_normal_[t[0]] * (1.f - u - v) + vertex_normal_[t[1]] * u + vertex_normal_[t[2]] * v;
  const float len = length(n);
  return len > 0.f ? n / len : plane_[prim].n;  // opposite normals cancelling: the face's own
}

void Scene::set_vertex_uvs(std::vector<float> uvs) {
  if (uvs.empty()) return;
  if (uvs.size() != positions_.size() / 3 * 2) throw std::invalid_argument("uvs must hold 2 values per vertex");
  for (const float x : uvs) {
    if (std::isinf(x)) throw std::invalid_argument("uvs must be finite (NaN marks a mesh without them)");
  }
  uv_ = std::move(uvs);
  has_uv_.resize(triangles_.size() / 3);
  for (size_t prim = 0; prim < has_uv_.size(); ++prim) {
    bool all = true;
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = triangles_[3 * prim + k];
      all = all && !std::isnan(uv_[2 * v]) && !std::isnan(uv_[2 * v + 1]);
    }
    has_uv_[prim] = all;
  }
}

Point2 Scene::interpolated_uv(uint32_t prim, float u, float v) const {
  const uint32_t* t = &triangles_[3 * prim];
  const float w = 1.f - u - v;
  return {w * uv_[2 * t[0]] + u * uv_[2 * t[1]] + v * uv_[2 * t[2]],
          w * uv_[2 * t[0] + 1] + u * uv_[2 * t[1] + 1] + v * uv_[2 * t[2] + 1]};
}

void Scene::intersect(const RayPacket& rays, HitPacket& hits) const {
  accel_->intersect(rays, hits);
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    if (hits.prim[i] == RayHit::kNoHit || hits.t[i] != 0.f) continue;
    RayHit rh;
    rh.t = hits.t[i], rh.u = hits.u[i], rh.v = hits.v[i], rh.prim = hits.prim[i];
    rh = past_start_plane(rays.ray(i), rh);  // rare: as intersect() below
    hits.t[i] = rh.t, hits.u[i] = rh.u, hits.v[i] = rh.v, hits.prim[i] = rh.prim;
  }
}

void Scene::intersect(const int32_t* active, RayHit16& p, Coherence coherence) const {
  alignas(64) float tmax[RayHit16::kLanes];  // the rays' own, for past_start_plane
  std::memcpy(tmax, p.tmax, sizeof tmax);
  accel_->intersect(active, p, coherence);
  // The lanes that hit at t = 0, found without a branch per lane (mispredicted where rays escape,
  // those cost the caustic box 1 % of its render time).
  alignas(64) int32_t at_start[RayHit16::kLanes];
  int32_t any = 0;
  for (int i = 0; i < RayHit16::kLanes; ++i) {
    at_start[i] = (p.prim[i] != RayHit::kNoHit) & (p.tmax[i] == 0.f);
    any |= at_start[i];
  }
  if (any == 0) return;
  for (int i = 0; i < RayHit16::kLanes; ++i) {
    if (at_start[i] == 0) continue;
    // Rare: as intersect() below.
    const Ray ray{{p.ox[i], p.oy[i], p.oz[i]}, {p.dx[i], p.dy[i], p.dz[i]}, tmax[i], p.tmin[i]};
    const RayHit rh = past_start_plane(ray, RayHit{p.tmax[i], p.u[i], p.v[i], p.prim[i]});
    p.tmax[i] = rh.t, p.u[i] = rh.u, p.v[i] = rh.v, p.prim[i] = rh.prim;
  }
}

RayHit Scene::past_start_plane(const Ray& ray, RayHit rh) const {
  if (rh.hit() && rh.t == 0.f && plane_offset(rh.prim, ray.o) == 0.f) {
    // A ray leaving the edge where two walls meet starts in the other wall's plane, offset
    // along its own normal only: Embree reports that wall at t = 0, a point the ray does not
    // reach through it (it leaves the plane). Past it, the ray's real first hit (issue 18: a
    // camera path went on from that point along the wall and its next connection left the
    // closed cell). Rare: only exactly coplanar origins.
    Ray past = ray;
    past.tmin = std::numeric_limits<float>::min();
    rh = accel_->intersect(past);
  }
  return rh;
}

bool Scene::intersect(const Ray& ray, SurfaceHit& hit) const {
  const RayHit rh = past_start_plane(ray, accel_->intersect(ray));
  if (!rh.hit()) return false;
  hit = surface_hit(rh.prim, rh.u, rh.v, rh.t);
  return true;
}

SurfaceHit Scene::surface_hit(uint32_t prim, float u, float v, float t) const {
  SurfaceHit hit;
  hit.p = vertex(prim, 0) * (1.f - u - v) + vertex(prim, 1) * u + vertex(prim, 2) * v;
  hit.n = plane_[prim].n;
  hit.ns = shading_normal(prim, u, v);
  hit.uv = surface_uv(prim, u, v);
  hit.t = t;
  hit.prim = prim;
  hit.material = &materials_[material_of_[prim]];
  hit.emitter = emitter_at(prim);
  return hit;
}

namespace {

// Hits that are the target itself, or a triangle coplanar with it at the target point (a
// neighbour sharing the point up to rounding), do not block. Nor does a triangle whose plane
// the segment does not cross: origin and target strictly on one side of it. A point on the
// edge where two walls meet lies in both planes: offset along its own normal, a path vertex
// there still starts its segment in the other wall's plane (Embree reports that wall at t = 0),
// and a target there ends it in that plane (a hit at t = 1). Such a wall blocks only when the
// point's own triangle lies on the far side of it from the segment's other end: a furnace lost
// connections from and to its edges, and a closed cell must not leak through its own edges
// (issue 18). Signs are exact for axis-aligned walls; elsewhere a point within rounding of
// another surface stays ambiguous.
struct VisibilityQuery {
  const Scene* scene;
  uint32_t target, origin_triangle;
  Vec3 origin, direction, target_point, target_normal;

  // Which side of the plane of `prim` triangle `t` lies on: its vertex farthest from the plane.
  float side_of(uint32_t t, uint32_t prim) const {
    float far = 0.f;
    for (int k = 0; k < 3; ++k) {
      const float s = scene->plane_offset(prim, scene->vertex(t, k));
      if (std::abs(s) > std::abs(far)) far = s;
    }
    return far;
  }

  bool segment_stays_on_one_side(uint32_t prim) const {
    const float s0 = scene->plane_offset(prim, origin), s1 = scene->plane_offset(prim, target_point);
    const auto same_side = [](float a, float b) { return a != 0.f && b != 0.f && (a > 0.f) == (b > 0.f); };
    if (s0 == 0.f && s1 == 0.f) return false;  // the segment in the plane: it may lie on prim
    if (s0 == 0.f) {
      return origin_triangle != Scene::kNoTriangle && same_side(side_of(origin_triangle, prim), s1);
    }
    if (s1 == 0.f) return same_side(side_of(target, prim), s0);
    return same_side(s0, s1);
  }

  // From o0 (off the surface of triangle `origin_tri`, Scene::shadow_origin) to p1 on triangle
  // `target_tri`: the ray is aimed at p1 itself (t = 1), so surfaces beyond it never count; any
  // other surface before it blocks, however close to p1 it stands, so walls meeting the target's
  // surface do not leak. (Built in place: Embree's filter reads it.)
  VisibilityQuery(const Scene& s, const Vec3& o0, const Vec3& p1, uint32_t target_tri, uint32_t origin_tri)
      : scene(&s),
        target(target_tri),
        origin_triangle(origin_tri),
        origin(o0),
        direction(p1 - origin),
        target_point(p1),
        target_normal(s.normal(target_tri)) {}
  Ray ray() const { return Ray{origin, direction, 1.f}; }
  // How far from the target's plane a hit may lie and still be in it (computed only for the
  // rare hits on a triangle parallel to the target).
  float tolerance() const {
    return 1e-5f * std::max(1.f, max_component(vmax(vmax(target_point, -target_point), vmax(origin, -origin))));
  }

  static bool ignore(const void* user, uint32_t prim, float t) {
    const auto* q = static_cast<const VisibilityQuery*>(user);
    if (prim == q->target || q->segment_stays_on_one_side(prim)) return true;
    const Scene::TrianglePlane& plane = q->scene->plane(prim);
    if (std::abs(dot(q->target_normal, plane.n)) < 1.f - 1e-5f) return false;
    const Vec3 hit = q->origin + q->direction * t;
    const float tolerance = q->tolerance();
    return std::abs(dot(q->target_normal, hit - q->target_point)) <= tolerance &&
           std::abs(dot(q->target_normal, plane.p0 - q->target_point)) <= tolerance;
  }
};

}  // namespace

float short_stop(const Vec3& d, float target_clearance) {
  const float margin = 0.5f * target_clearance / length(d);
  return margin >= 1e-5f ? 1.f - std::min(margin, 0.5f) : 0.f;
}

bool Scene::visible(const Vec3& p0, const Vec3& n0, const Vec3& p1, uint32_t target, uint32_t origin) const {
  const VisibilityQuery query(*this, shadow_origin(p0, n0, p1), p1, target, origin);
  const HitFilter filter{&VisibilityQuery::ignore, &query};
  Ray ray = query.ray();
  const float stop = short_stop(ray.d, clearance_[target]);
  if (stop > 0.f) ray.tmax = stop;
  return !accel_->occluded(ray, &filter);
}

namespace {

// Lane i of a ShadowPacket as visible()'s filter: its VisibilityQuery, built only at a hit (a
// segment with a short stop hits nothing unless it is blocked).
struct LaneVisibility {
  const Scene* scene;
  const Scene::ShadowPacket* ends;
  int lane;

  static bool ignore(const void* user, uint32_t prim, float t) {
    const auto& [scene, q, i] = *static_cast<const LaneVisibility*>(user);
    const VisibilityQuery query(*scene, {q->o0x[i], q->o0y[i], q->o0z[i]}, {q->p1x[i], q->p1y[i], q->p1z[i]},
                                q->target[i], q->origin[i]);
    return VisibilityQuery::ignore(&query, prim, t);
  }
};

}  // namespace

void Scene::occluded(RayHit16& packet, const ShadowPacket& ends) const {
  constexpr int kLanes = RayHit16::kLanes;
  LaneVisibility lanes[kLanes];
  HitFilter filter[kLanes];
  const HitFilter* filters[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    lanes[i] = LaneVisibility{this, &ends, i};
    filter[i] = HitFilter{&LaneVisibility::ignore, &lanes[i]};
    filters[i] = &filter[i];
  }
  accel_->occluded(ends.active, packet, filters);
}

bool Scene::visible_point(const Vec3& p0, const Vec3& n0, const Vec3& p1) const {
  const Vec3 o0 = shadow_origin(p0, n0, p1);
  // To the eye, short of it by eye_clearance (surfaces through the pinhole do not block it).
  const Vec3 to_eye = p1 - o0;
  const float stop = 1.f - eye_clearance_ / length(to_eye);
  return !(stop > 0.f) || !accel_->occluded(Ray{o0, to_eye, stop});
}

}  // namespace dualight
