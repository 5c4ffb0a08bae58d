// The unweighted contribution of one BDPT strategy (s light vertices, t camera vertices)
// [Veach 1997, eq. 10.8; pbrt-v3 sec. 16.3.3]:
//   s = 0   the camera subpath's last vertex is on an emitter;
//   t = 1   the light subpath's last vertex is connected to the camera and lands on the film at
//           `raster` (light tracing);
//   s = 1   the camera subpath's last vertex is connected to a freshly sampled emitter point
//           (next-event estimation), which is returned in `sampled`;
//   else    the two last vertices are connected by a shadow ray.
// The value is beta_light * f(q_s) * G(q_s, p_t) * f(p_t) * beta_camera; at the camera, f is the
// importance We and G has no camera cosine (pinhole).
#pragma once
#include <limits>

#include "pathspace/path.h"
#include "pathspace/render_stats.h"
#include "pathspace/shadow_ray.h"

namespace dualight {

// A segment made by connecting a and b (neither specular): visibility, one shadow ray, aimed at
// the vertex itself where it has no surface (the camera, a point emitter), or past the scene
// towards b's direction when b is at infinity.
inline bool connect_visible(const Scene& scene, const Vertex& a, const Vertex& b, TraceCounters& counters) {
  if (b.at_infinity) return shadow_ray_visible_point(scene, a.p, a.n, scene.beyond(a.p, b.n), counters);
  if (a.at_infinity) return shadow_ray_visible_point(scene, b.p, b.n, scene.beyond(b.p, a.n), counters);
  if (b.on_surface() && !a.on_surface()) return shadow_ray_visible_point(scene, b.p, b.n, a.p, counters);
  return shadow_ray_visible_to(scene, a.p, a.n, a.on_surface() ? a.prim : Scene::kNoTriangle, b.p, b.prim,
                               b.on_surface(), counters);
}

// The rounding of hit points at a connection between points a and b: a few ulps of their largest
// coordinate (the same for both ends).
inline float rounding_band(const Vec3& a, const Vec3& b) {
  return 16.f * std::numeric_limits<float>::epsilon() * max_component(vmax(vmax(a, -a), vmax(b, -b)));
}

// Whether the connection's segment d lies in surface vertex v's tangent plane within the
// rounding `band` of its end points (rounding_band). Such a connection has G = 0 exactly;
// in floats its cosine's sign, and so the side of the surface it runs on, is decided by
// rounding: a light vertex on a closed wall's outside reached a camera vertex on its inside
// through a connection along the wall (a leak of 1e-10, issue 18).
inline bool along_surface(const Vertex& v, const Vec3& d, float band) {
  return v.on_surface() && std::abs(dot(v.n, d)) <= band;
}

// Vertex standing for the pinhole camera in t = 1 connections.
inline Vertex camera_vertex(const PinholeCamera& camera) {
  Vertex c;
  c.type = VertexType::Camera;
  c.p = camera.origin();
  c.n = camera.forward();
  c.ns = c.n;
  c.beta = Color(1.f);
  return c;
}

// t = 1 from a vertex at infinity: the environment seen straight through the pinhole towards
// qs.n (G = 1: no distance, no cosine at either end). A directional light is not seen (a delta
// direction through a delta position).
inline Color connect_camera_to_infinity(const Scene& scene, const PinholeCamera& camera, const Vertex& qs,
                                        Point2& raster, TraceCounters& counters) {
  if (is_delta_direction(*qs.emitter) || !raster_of(camera, qs, raster)) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  const Color L = qs.beta * emitted_towards(qs, camera.origin()) * camera.importance(qs.n);
  if (is_black(L)) {
    ++counters.skipped_connections;
    return L;
  }
  const Vec3 eye = camera.origin();
  return shadow_ray_visible_point(scene, scene.beyond(eye, qs.n), -qs.n, eye, counters) ? L : Color(0.f);
}

// t = 1: the light subpath vertex qs seen by the camera.
inline Color connect_to_camera(const Scene& scene, const PinholeCamera& camera, const Vertex& qs, Point2& raster,
                               TraceCounters& counters) {
  if (qs.at_infinity) return connect_camera_to_infinity(scene, camera, qs, raster, counters);
  // A point emitter is not seen through a pinhole (two delta positions never meet).
  if (!qs.connectible() || qs.at_point || !camera.raster_position(qs.p, raster)) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  const Vec3 d = camera.origin() - qs.p;
  const float dist2 = dot(d, d);
  const Vec3 w = d / std::sqrt(dist2);
  const Color f = qs.type == VertexType::Light ? emitted_towards(qs, camera.origin())
                                               : scattering_along(qs, w, TransportMode::Importance);
  const Color L = qs.beta * f * (camera.importance(-w) * abs_cos(qs, w) / dist2);
  if (is_black(L)) {
    ++counters.skipped_connections;
    return L;
  }
  return shadow_ray_visible_point(scene, qs.p, qs.n, camera.origin(), counters) ? L : Color(0.f);
}

// s = 1 with the emitter vertex at infinity: towards its direction, G = |cos| at pt alone.
inline Color connect_to_infinity(const Scene& scene, const Vertex& pt, const Vertex& qs, TraceCounters& counters) {
  const Vec3 w = qs.n;
  const float band = 16.f * std::numeric_limits<float>::epsilon();
  const float G = std::abs(dot(pt.n, w));
  if (!(G > band)) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  const Color L = qs.beta * emitted_towards(qs, pt.p) * pt.beta * scattering_along(pt, w, TransportMode::Radiance) * G;
  if (is_black(L)) {
    ++counters.skipped_connections;
    return L;
  }
  return connect_visible(scene, pt, qs, counters) ? L : Color(0.f);
}

template <class Sampler>
Color connect(const Scene& scene, const PinholeCamera& camera, const Path& light, const Path& cam, int s, int t,
              Sampler& sampler, Vertex& sampled, Point2& raster, TraceCounters& counters) {
  if (s == 0) {
    const Vertex& pt = cam[t - 1];
    return pt.is_emitter() ? pt.beta * emitted_towards(pt, cam[t - 2].p) : Color(0.f);
  }
  if (t == 1) {
    sampled = camera_vertex(camera);
    return connect_to_camera(scene, camera, light[s - 1], raster, counters);
  }
  const Vertex& pt = cam[t - 1];
  // A camera subpath's vertex at infinity (its ray left the scene) takes s = 0 only.
  if (!pt.connectible() || pt.at_infinity) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  if (s == 1) {
    const float u_select = sampler.next_1d();
    sampled = emitter_vertex(scene, u_select, sampler.next_2d());
  }
  const Vertex& qs = s == 1 ? sampled : light[s - 1];
  if (!qs.connectible()) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  if (qs.at_infinity) return connect_to_infinity(scene, pt, qs, counters);
  const Vec3 d = qs.p - pt.p;
  const float dist2 = dot(d, d);
  if (!(dist2 > 0.f)) return Color(0.f);
  const float band = rounding_band(pt.p, qs.p);
  if (along_surface(pt, d, band) || along_surface(qs, d, band)) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  const Vec3 w = d / std::sqrt(dist2);
  const float G = std::abs(dot(pt.n, w)) * abs_cos(qs, w) / dist2;
  // w is normalize(qs.p - pt.p) to the bit, and -w normalize(pt.p - qs.p): both ends scatter along them.
  const Color fq = s == 1 ? emitted_towards(qs, pt.p) : scattering_along(qs, -w, TransportMode::Importance);
  const Color L = qs.beta * fq * pt.beta * scattering_along(pt, w, TransportMode::Radiance) * G;
  if (is_black(L)) {
    ++counters.skipped_connections;
    return L;
  }
  return connect_visible(scene, pt, qs, counters) ? L : Color(0.f);
}

}  // namespace dualight
