// The scene as rendered: immutable triangles with materials and emitters, committed to Embree
// once at construction. Everything that renders takes a `const Scene&`.
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "core/bounding_sphere.h"
#include "core/ray.h"
#include "core/sampling.h"
#include "geometry/embree_accel.h"
#include "geometry/scene_features.h"
#include "lights/emitter_sampler.h"
#include "materials/bsdf.h"
#include "materials/textured_bsdf.h"

namespace dualight {

// A triangle's description: its BSDF and, when non-black or textured, the radiance it emits
// from its front side (the side of the right-hand-rule normal), which makes it an AreaEmitter.
// `textures` drive some of the BSDF's parameters, looked up at each point's (u, v); `bsdf` holds
// their means (what radiosity and the material's flags see).
struct Material {
  Bsdf bsdf;
  Color emission;
  std::vector<TextureSlot> textures;
  std::optional<Texture> emission_texture;  // the radiance at each point's (u, v); `emission` unused

  bool textured() const { return !textures.empty(); }
  bool emits() const { return emission_texture.has_value() || !is_black(emission); }
  // The BSDF at surface coordinates uv.
  Bsdf bsdf_at(Point2 uv) const { return textured_bsdf(bsdf, textures, uv); }
};

// f(the BSDF of material m at surface coordinates uv). Untextured surfaces pass the material's
// own BSDF: the lookup, a call the compiler cannot see through, stays off their path. Forced
// inline: as a call, BDPT took 2 % more instructions on the Cornell box.
template <class F>
[[gnu::always_inline]] inline decltype(auto) with_bsdf(const Material& m, Point2 uv, F&& f) {
  if (!m.textured()) return f(m.bsdf);
  return f(m.bsdf_at(uv));
}


struct SurfaceHit {
  Vec3 p;          // position, from barycentrics (more accurate than o + t d)
  Vec3 n;          // unit geometric normal, right-hand rule on the triangle's vertex order
  Vec3 ns;         // unit shading normal: the vertex normals interpolated, n on flat triangles
  Point2 uv;       // surface coordinates: the vertices' interpolated, else the barycentrics of 1, 2
  float t = 0.f;
  uint32_t prim = 0;
  const Material* material = nullptr;
  const Emitter* emitter = nullptr;  // the emitter on this triangle, if any
};

// An emitter picked by the scene's power-proportional choice, with that choice's probability.
struct EmitterChoice {
  const Emitter* emitter = nullptr;
  float pmf = 0.f;
};

// Where a shadow ray from o0 along d = p1 - o0 (Scene::visible's) may stop: short of the
// target by half the target's clearance (surface_clearance.h), so the rest of the segment meets
// no surface but the target's own and those coplanar with it, which the filter ignores. Up to
// there, the filtered answer is the answer to t = 1, and an unblocked ray hits nothing, so
// Embree calls no filter at the target (the path tracer runs about 5 % faster on the Cornell and
// caustic boxes); a blocker goes through the filter in the same query. 0 where there is no such
// stop: a target touching another surface, or a segment too long for half the clearance to
// stand clear of t's rounding (1e-5 of it). The path tracer's lanes compute the same lane-wide
// (path_lanes_kernel.h, visible).
float short_stop(const Vec3& d, float target_clearance);

class Scene {
 public:
  // positions: xyz per vertex; triangles: 3 vertex indices each; material_of: index per triangle;
  // emitters: those not on the triangles (every emissive triangle is an AreaEmitter already),
  // kept after the area emitters; normals: empty, or xyz per vertex, where a triangle whose three
  // vertices all have non-zero normals is smooth-shaded (its shading normal interpolates them,
  // Phong's normal interpolation) and any zero normal keeps the triangle flat; uvs: empty, or
  // (u, v) per vertex, NaN where a mesh has none (its triangles take their barycentrics, as in
  // Mitsuba); robust_intersections: Embree's robust mode (EmbreeAccel). Throws
  // std::invalid_argument on any malformed input (the Python layer validates first, so these
  // checks guard the C++ API itself).
  Scene(std::vector<float> positions, std::vector<uint32_t> triangles, std::vector<uint32_t> material_of,
        std::vector<Material> materials, std::vector<Emitter> emitters = {}, std::vector<float> normals = {},
        std::vector<float> uvs = {}, bool robust_intersections = true);

  size_t triangle_count() const { return area_.size(); }
  Vec3 vertex(uint32_t prim, int corner) const {
    const uint32_t v = triangles_[3 * prim + corner];
    return {positions_[3 * v], positions_[3 * v + 1], positions_[3 * v + 2]};
  }
  Vec3 normal(uint32_t prim) const { return plane_[prim].n; }
  // The shading normal at barycentrics (u, v) of vertices 1 and 2: the geometric normal on flat
  // triangles. (Inline for scenes without vertex normals or texture coordinates, most of them.)
  Vec3 shading_normal(uint32_t prim, float u, float v) const {
    return smooth_.empty() || !smooth_[prim] ? plane_[prim].n : interpolated_normal(prim, u, v);
  }
  // Whether triangle `prim` interpolates vertex normals (else its shading normal is n).
  bool smooth_shaded(uint32_t prim) const { return !smooth_.empty() && smooth_[prim] != 0; }
  // The surface coordinates at barycentrics (u, v) of vertices 1 and 2.
  Point2 surface_uv(uint32_t prim, float u, float v) const {
    return has_uv_.empty() || !has_uv_[prim] ? Point2{u, v} : interpolated_uv(prim, u, v);
  }
  float area(uint32_t prim) const { return area_[prim]; }
  const Material& material(uint32_t prim) const { return materials_[material_of_[prim]]; }
  size_t emitter_count() const { return emitters_.size(); }
  const std::vector<Emitter>& emitters() const { return emitters_; }
  // The emitter on triangle `prim`, or nullptr.
  const Emitter* emitter_at(uint32_t prim) const {
    const uint32_t i = emitter_of_prim_[prim];
    return i == kNoEmitter ? nullptr : &emitters_[i];
  }
  // The emitter at infinity that rays leaving the scene see (a constant or image environment; at
  // most one, as in Mitsuba), a pointer into emitters(); nullptr in most scenes, which then look
  // nothing up on a miss.
  const Emitter* environment() const { return environment_; }
  // Whether a path can hit some emitter (an area light or an environment): false when every
  // emitter is a delta light (point, spot, directional), whose light only strategies that
  // sample the emitter find.
  bool has_hittable_emitter() const { return hittable_emitter_; }
  // Power-proportional choice of an emitter (there must be some), and its probability for `e`.
  EmitterChoice choose_emitter(float u) const {
    const size_t i = emitter_sampler_.sample(u);
    return {&emitters_[i], emitter_sampler_.pmf(i)};
  }
  // choose_emitter(u) picks min(#{k : u >= ends[k]}, emitter_count() - 1) of these ends
  // (DiscreteDistribution::float_item_ends).
  std::vector<float> emitter_choice_ends() const { return emitter_sampler_.float_item_ends(); }
  float emitter_pmf(const Emitter& e) const { return emitter_sampler_.pmf(static_cast<size_t>(&e - emitters_.data())); }
  // p moved off its surface along n by offset_ray_origin (core/ray.h) at this scene's scale: the
  // largest side of the bounding box, capped at 1 (a power of two, so offsets stay exact).
  Vec3 spawn_origin(const Vec3& p, const Vec3& n) const { return offset_ray_origin(p, n, offset_scale_); }
  // Where a shadow ray from p0 (on a surface of normal n0) towards p1 starts: off the surface on p1's side.
  Vec3 shadow_origin(const Vec3& p0, const Vec3& n0, const Vec3& p1) const {
    return spawn_origin(p0, dot(n0, p1 - p0) > 0.f ? n0 : -n0);
  }
  // Surfaces closer to the pinhole than this (1e-6 of the scene's extent) are not seen from it,
  // by every estimator alike: rays leaving the eye start there (Ray::tmin), and connections to
  // the eye stop there (visible_point). A pinhole lying on a wall saw the wall's back at t = 0
  // in the path tracer while light tracing ignored it (issue 18).
  float eye_clearance() const { return eye_clearance_; }
  Ray eye_ray(Ray ray) const {
    ray.tmin = eye_clearance_;
    return ray;
  }
  // Triangle prim's unit normal and first vertex in one record, the only place its normal is
  // kept (the visibility filter reads both at every hit, on triangles only Embree has touched:
  // one cache miss instead of three).
  struct TrianglePlane {
    Vec3 n, p0;
  };
  const TrianglePlane& plane(uint32_t prim) const { return plane_[prim]; }
  // Signed distance of p from the plane of triangle `prim` (along its unit normal).
  float plane_offset(uint32_t prim, const Vec3& p) const {
    const TrianglePlane& plane = plane_[prim];
    return dot(plane.n, p - plane.p0);
  }
  Vec3 bounds_min() const { return bounds_min_; }
  Vec3 bounds_max() const { return bounds_max_; }
  // The sphere around the geometry that emitters at infinity use (core/bounding_sphere.h).
  const BoundingSphere& bounding_sphere() const { return sphere_; }
  // A point along unit w from p (inside the sphere) beyond the bounding sphere: where a shadow
  // ray towards a direction at infinity ends.
  Vec3 beyond(const Vec3& p, const Vec3& w) const { return p + w * reach_beyond(sphere_, p); }
  // What the scene holds (specular, closed, convex enclosure, ...), computed at construction.
  const SceneFeatures& features() const { return features_; }
  bool robust_intersections() const { return robust_intersections_; }

  bool intersect(const Ray& ray, SurfaceHit& hit) const;
  // The hit intersect() makes on triangle prim at barycentrics (u, v), distance t.
  SurfaceHit surface_hit(uint32_t prim, float u, float v, float t) const;
  // True when nothing lies between p0 (on a surface with normal n0) and p1 on triangle `target`.
  // The ray aims at p1 itself and the first hit must be the target or a triangle coplanar with it
  // at p1 (a neighbour sharing the point numerically): any other surface blocks, however close to
  // p1 it stands, so walls that meet the target's surface do not leak. `origin` is p0's own
  // triangle where it has one: it settles a p0 on the edge where its surface meets another.
  // Towards targets clear of other surfaces (emitters, surface_clearance.h) the ray stops short
  // of p1, so an unblocked ray meets no surface and calls no filter: the same answer, faster.
  static constexpr uint32_t kNoTriangle = 0xffffffffu;
  bool visible(const Vec3& p0, const Vec3& n0, const Vec3& p1, uint32_t target, uint32_t origin = kNoTriangle) const;
  // True when nothing lies between p0 (on a surface with normal n0) and p1, a point in free
  // space such as a pinhole camera.
  bool visible_point(const Vec3& p0, const Vec3& n0, const Vec3& p1) const;

  // Packets of rays traced together (EmbreeAccel's), for estimators that run paths in lanes:
  // hits as the RayHit behind intersect() for each active lane.
  void intersect(const RayPacket& rays, HitPacket& hits) const;
  // The same in place (EmbreeAccel's RayHit16), for the lanes where active[i] != 0; coherent
  // packets (camera rays through one pixel or a few) trace faster as such (EmbreeAccel).
  void intersect(const int32_t* active, RayHit16& packet, Coherence coherence = Coherence::kIncoherent) const;
  // The ends of a packet of visible() queries: lane i (where active[i] != 0) asks
  // visible(p0, n0, p1, target, origin) with o0 = shadow_origin(p0, n0, p1).
  struct ShadowPacket {
    static constexpr int kLanes = RayPacket::kLanes;
    alignas(64) float o0x[kLanes], o0y[kLanes], o0z[kLanes];
    alignas(64) float p1x[kLanes], p1y[kLanes], p1z[kLanes];
    alignas(64) uint32_t target[kLanes], origin[kLanes];
    alignas(64) int32_t active[kLanes];
  };
  // visible() of packets, for lane code that computes the segments itself: lane i of `packet`
  // (where ends.active[i] != 0) holds the ray from o0 along p1 - o0 (of `ends`) up to tmax: the
  // stop short of the target that short_stop (scene.cpp) derives from its clearance
  // (target_clearances(), per triangle), or 1 where it gives none; every hit on the way goes
  // through visible()'s filter. Where the segment is blocked, or Embree refuses the ray, tmax[i]
  // becomes negative (EmbreeAccel's RayHit16, in place).
  void occluded(RayHit16& packet, const ShadowPacket& ends) const;
  // visible_point() of packets, likewise: lane i (active[i] != 0) holds the ray from
  // shadow_origin towards p1 up to its stop short of p1, traced without a filter.
  void occluded_points(const int32_t* active, RayHit16& packet) const { accel_->occluded(active, packet); }
  const float* target_clearances() const { return clearance_.data(); }
  // The scale spawn_origin offsets at.
  float offset_scale() const { return offset_scale_; }

 private:
  // Embree's closest hit rh of `ray`, or, where rh is a wall the ray starts in the plane of, the
  // first hit past it (intersect()).
  RayHit past_start_plane(const Ray& ray, RayHit rh) const;
  std::pair<Vec3, float> normal_and_double_area(uint32_t prim) const;
  AreaEmitter area_emitter(uint32_t prim) const;
  void set_vertex_normals(const std::vector<float>& normals);
  void set_vertex_uvs(std::vector<float> uvs);
  Vec3 interpolated_normal(uint32_t prim, float u, float v) const;
  Point2 interpolated_uv(uint32_t prim, float u, float v) const;

  std::vector<float> positions_;
  std::vector<uint32_t> triangles_;
  std::vector<uint32_t> material_of_;
  std::vector<Material> materials_;
  std::vector<TrianglePlane> plane_;  // each triangle's unit normal and first vertex
  std::vector<Vec3> vertex_normal_;  // unit, per vertex; empty when every triangle is flat
  std::vector<uint8_t> smooth_;      // per triangle: 1 = interpolate vertex_normal_
  std::vector<float> uv_;            // (u, v) per vertex; empty when no mesh has any
  std::vector<uint8_t> has_uv_;      // per triangle: 1 = interpolate uv_
  std::vector<float> area_;
  static constexpr uint32_t kNoEmitter = 0xffffffffu;
  std::vector<Emitter> emitters_;           // one AreaEmitter per emissive triangle, in triangle order
  std::vector<uint32_t> emitter_of_prim_;   // index into emitters_, kNoEmitter for the others
  const Emitter* environment_ = nullptr;  // into emitters_ (fixed after construction)
  bool hittable_emitter_ = false;
  PowerEmitterSampler emitter_sampler_;
  Vec3 bounds_min_, bounds_max_;
  BoundingSphere sphere_;
  float offset_scale_ = 1.f;
  float eye_clearance_ = 0.f;
  SceneFeatures features_;
  bool robust_intersections_ = true;
  std::unique_ptr<EmbreeAccel> accel_;
  std::vector<float> clearance_;  // per triangle, emitter_clearances (0: unknown)
};

}  // namespace dualight
