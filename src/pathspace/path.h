// Path vertices with densities in area measure, as bidirectional estimators need them
// [Veach 1997, ch. 10; pbrt-v3 sec. 16.3]. A subpath starts at the camera or at an emitter;
// vertex i stores
//   beta     the throughput of the subpath up to vertex i (the estimate's factor before i's own
//            scattering): 1 at the camera, 1 / pdf_a at an emitter, then times f |cos| / pdf;
//   pdf_fwd  the area density with which the subpath's own sampling generated vertex i;
//   pdf_rev  the area density with which sampling in the other direction (from i + 1, having come
//            from i + 2) would generate vertex i;
//   delta    vertex i scattered by a Dirac lobe (no connection can end there).
// Delta scattering stores 0 in the affected densities; MIS ratios read 0 as 1 (pbrt's remap0),
// skip strategies that would connect at a delta vertex, and correct the ratio across each chain
// of delta vertices (mis_weight.cpp, chain_correction).
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/frame.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "guiding/guided_sampling.h"
#include "materials/shading_normal.h"

namespace dualight {

enum class VertexType : uint8_t { Camera, Light, Surface };

struct Vertex {
  VertexType type = VertexType::Surface;
  Vec3 p;                  // position
  Vec3 n;                  // geometric normal; the view direction at the camera
  Vec3 ns;                 // shading normal, the BSDF's frame (materials/shading_normal.h); n if flat
  Point2 uv;               // surface coordinates, where textures are looked up
  Vec3 wo;                 // unit direction to the previous vertex of the subpath (0 at its start)
  uint32_t prim = 0;
  const Material* material = nullptr;
  const Emitter* emitter = nullptr;  // the emitter at p: a light subpath's start, or a surface hit on one
  Color beta;
  float pdf_fwd = 0.f, pdf_rev = 0.f;
  bool delta = false;
  bool at_point = false;  // a light vertex in free space: a point emitter's, or one at infinity
  // A light vertex on the sphere at infinity (an environment, a directional light): p and n hold
  // the unit direction from the scene towards it; densities of reaching it are solid-angle
  // densities, and those of leaving it planar densities on the distant disk (at_point too).
  bool at_infinity = false;
  // Guided BDPT (set_vertex_guides, mis_weight.cpp): the radiance and importance guides at a
  // surface vertex (VertexGuide{}: none), looked up once per subpath instead of once per
  // strategy, and the guide of the other transport direction's density of the direction to the
  // previous vertex. guides_set false: not cached, MIS looks the guides up. The walk keeps the
  // guides it looked up (*_known), so set_vertex_guides looks up only the others.
  bool guides_set = false;
  bool radiance_guide_known = false, importance_guide_known = false;
  VertexGuide radiance_guide, importance_guide;
  float reverse_guide_pdf_w = 0.f;

  // Has a surface (a normal whose cosine enters geometry terms): not the pinhole camera, not a
  // point emitter.
  bool on_surface() const { return type != VertexType::Camera && !at_point; }
  bool is_emitter() const { return emitter != nullptr; }
  // A connection (shadow ray) can end here: not at a delta BSDF, nor at an emitter whose
  // direction is a delta (only its one direction carries light).
  bool connectible() const {
    switch (type) {
      case VertexType::Surface:
        return !is_delta(material->bsdf);
      case VertexType::Light:
        // At infinity the direction to any point is the vertex's own: a directional light
        // connects (its delta is the position at infinity).
        return emitter == nullptr || at_infinity || !is_delta_direction(*emitter);
      case VertexType::Camera:
        break;
    }
    return true;
  }
};

using Path = std::vector<Vertex>;

// The surface vertex a ray along direction d found at `hit` (densities and beta left to the caller).
inline Vertex surface_vertex(const SurfaceHit& hit, const Vec3& d) {
  Vertex v;
  v.type = VertexType::Surface;
  v.p = hit.p;
  v.n = hit.n;
  v.ns = hit.ns;
  v.uv = hit.uv;
  v.wo = -d;
  v.prim = hit.prim;
  v.material = hit.material;
  v.emitter = hit.emitter;
  return v;
}

// f(surface vertex v's BSDF), its textures looked up at v.
template <class F>
[[gnu::always_inline]] inline decltype(auto) with_bsdf(const Vertex& v, F&& f) {
  return with_bsdf(*v.material, v.uv, std::forward<F>(f));
}

// The frame v's BSDF is evaluated in.
inline Frame shading_frame(const Vertex& v) { return Frame::from_normal(v.ns); }

// Solid-angle density with which surface vertex v, reached along wo (world, unit), samples w.
inline float surface_pdf_w(const Vertex& v, const Vec3& wo, const Vec3& w, TransportMode mode) {
  return with_bsdf(v, [&](const Bsdf& b) { return pdf_w_world(b, v.ns, wo, w, mode); });
}

// The start of a light subpath (or the emitter end of a connection): a point on an emitter
// the scene chose by power (u_select), sampled by the emitter (u).
inline Vertex emitter_vertex(const Scene& scene, float u_select, Point2 u) {
  const EmitterChoice choice = scene.choose_emitter(u_select);
  const EmitterPoint y = sample_Le_position(*choice.emitter, choice.pmf, u);
  Vertex v;
  v.type = VertexType::Light;
  v.p = y.p;
  v.n = y.n;
  v.ns = y.n;
  v.prim = y.prim;
  v.uv = y.uv;
  v.material = y.on_surface ? &scene.material(v.prim) : nullptr;
  v.emitter = choice.emitter;
  v.at_point = !y.on_surface;
  v.at_infinity = y.at_infinity;
  v.beta = Color(1.f / y.pdf_a);
  v.pdf_fwd = y.pdf_a;
  return v;
}

// The vertex at infinity a camera subpath reaches when its ray (unit direction d, sampled with
// solid-angle density pdf_w) leaves the scene towards its environment; beta its throughput.
inline Vertex escape_vertex(const Scene& scene, const Vec3& d, const Color& beta, float pdf_w) {
  Vertex v;
  v.type = VertexType::Light;
  v.p = d;
  v.n = d;
  v.ns = d;
  v.wo = -d;
  v.emitter = scene.environment();
  v.at_point = true;
  v.at_infinity = true;
  v.beta = beta;
  v.pdf_fwd = pdf_w;  // the sphere at infinity is measured in solid angle
  return v;
}

// Unit direction from vertex `from` to vertex `to` (either may be at infinity).
inline Vec3 direction(const Vertex& from, const Vertex& to) {
  if (to.at_infinity) return to.n;
  if (from.at_infinity) return -from.n;
  return normalize(to.p - from.p);
}

// The film position where the camera sees vertex v (a vertex at infinity: its direction).
inline bool raster_of(const PinholeCamera& camera, const Vertex& v, Point2& raster) {
  return camera.raster_position(v.at_infinity ? camera.origin() + v.n : v.p, raster);
}

// Area density at `to` of a solid-angle density at `from` towards `to`. Towards infinity the
// measure stays solid angle; from infinity pdf_w is the distant disk's planar density, which
// becomes an area density by the cosine at `to`.
inline float solid_angle_to_area(float pdf_w, const Vertex& from, const Vertex& to) {
  if (to.at_infinity) return pdf_w;
  if (from.at_infinity) return to.on_surface() ? pdf_w * std::abs(dot(to.n, from.n)) : pdf_w;
  const Vec3 d = to.p - from.p;
  const float inv_dist2 = 1.f / dot(d, d);
  float pdf = pdf_w * inv_dist2;
  if (to.on_surface()) pdf *= std::abs(dot(to.n, d)) * std::sqrt(inv_dist2);
  return pdf;
}

// |cos| between v's normal and unit w, or 1 where v has no surface (camera, point emitter).
inline float abs_cos(const Vertex& v, const Vec3& w) { return v.on_surface() ? std::abs(dot(v.n, w)) : 1.f; }

// |cos| at both ends over distance squared; no cosine where a vertex has no surface (the pinhole
// camera, a point emitter). To a vertex at infinity: the cosine at the other end alone (no
// distance, no cosine at infinity).
inline double geometry_term(const Vertex& a, const Vertex& b) {
  if (a.at_infinity || b.at_infinity) {
    const Vertex& v = a.at_infinity ? b : a;
    return v.on_surface() ? std::abs(dot(v.n, direction(a, b))) : 1.0;
  }
  const Vec3 d = b.p - a.p;
  const double dist2 = dot(d, d);
  if (!(dist2 > 0.0)) return 0.0;
  const Vec3 w = d / static_cast<float>(std::sqrt(dist2));
  double g = 1.0 / dist2;
  if (a.on_surface()) g *= std::abs(dot(a.n, w));
  if (b.on_surface()) g *= std::abs(dot(b.n, w));
  return g;
}

// Radiance vertex v emits towards `to` (0 when v is on no emitter); from infinity, along -v.n.
inline Color emitted_towards(const Vertex& v, const Vec3& to) {
  if (v.emitter == nullptr) return Color(0.f);
  return radiance(*v.emitter, v.at_infinity ? -v.n : to - v.p, v.uv);
}

// Solid-angle density of v's emitter emitting towards unit w (0 when v is on no emitter).
inline float emission_pdf_w(const Vertex& v, const Vec3& w) {
  return v.emitter != nullptr ? pdf_Le_direction(*v.emitter, w) : 0.f;
}

// The BSDF of surface vertex v from direction of `prev` (its wo) to unit direction wi, in `mode`;
// f only, the cosine belongs to the geometry term.
Color scattering_along(const Vertex& v, const Vec3& wi, TransportMode mode);

// Area density at `next` of sampling from v, which was reached from `prev` (unused at the ends of
// a subpath): the camera's direction density, an emitter's cosine lobe, or v's BSDF.
float pdf_area(const PinholeCamera& camera, const Vertex& v, const Vertex* prev, const Vertex& next);
// The same from the unit directions at v: w = direction(v, next) and, at a surface vertex,
// wo = direction(v, prev) (read only there). MIS weights pass the directions they share.
float pdf_area_along(const PinholeCamera& camera, const Vertex& v, const Vec3& wo, const Vec3& w, const Vertex& next);

// Emitter-side densities of an emitter point v as the start of a light subpath: of picking v
// (area measure), and of emitting from v towards `next` (area measure at next).
float pdf_light_origin(const Scene& scene, const Vertex& v);
float pdf_light(const Vertex& v, const Vertex& next);

// Largest relative differences between a subpath's cached quantities and their recomputation
// from its positions and materials (for tests; 0 for an exact path).
struct PathCheck {
  float pdf_fwd = 0.f, pdf_rev = 0.f, beta = 0.f;
  size_t vertices = 0;
  // Values off by more than 1e-3 relative: float rounding gets there only at grazing angles.
  size_t off = 0;
};
// `from_camera`: a camera subpath (else a light subpath). Russian roulette must be off (it
// scales beta by factors not recorded in the path).
PathCheck verify(const PinholeCamera& camera, const Path& path, bool from_camera);

}  // namespace dualight
