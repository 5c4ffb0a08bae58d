// Shadow rays of path connections, skipped where the scene makes them pointless: in a convex
// enclosure without glass that holds the camera (scene_features.h) every vertex of a path lies
// on the front side of a surface or at the camera, and two such points that face each other
// cannot be separated by any triangle. Each skipped ray is counted, so a render says what it
// left out, and `skip_unneeded = false` traces them all (for benchmarks and checks).
#pragma once
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "pathspace/render_stats.h"

namespace dualight {

// Whether a render with this camera may skip its shadow rays.
// Emitters off the surfaces are path vertices too: each must be a point inside the enclosure.
inline bool connections_unoccluded(const Scene& scene, const PinholeCamera& camera, bool skip_unneeded) {
  const SceneFeatures& f = scene.features();
  if (!(skip_unneeded && f.unoccluded() && f.encloses(camera.origin()))) return false;
  for (const Emitter& e : scene.emitters()) {
    if (has_any(flags(e), EmitterFlags::Surface)) continue;
    if (!is_delta_position(e) || !f.encloses(sample_Le_position(e, 1.f, {0.5f, 0.5f}).p)) return false;
  }
  return true;
}

// Scene::visible (p0 on triangle `origin`, or Scene::kNoTriangle), or true without a ray when
// the counters say connections are unoccluded.
inline bool shadow_ray_visible(const Scene& scene, const Vec3& p0, const Vec3& n0, uint32_t origin, const Vec3& p1,
                               uint32_t target, TraceCounters& counters) {
  if (counters.unoccluded) {
    ++counters.skipped_shadow_rays;
    return true;
  }
  ++counters.rays;
  return scene.visible(p0, n0, p1, target, origin);
}

// Scene::visible_point (p1 in free space, the camera), likewise.
inline bool shadow_ray_visible_point(const Scene& scene, const Vec3& p0, const Vec3& n0, const Vec3& p1,
                                     TraceCounters& counters) {
  if (counters.unoccluded) {
    ++counters.skipped_shadow_rays;
    return true;
  }
  ++counters.rays;
  return scene.visible_point(p0, n0, p1);
}

// From p0 on triangle `origin` to p1 on triangle `target` when `on_surface`, else to p1 in
// free space (a point emitter).
inline bool shadow_ray_visible_to(const Scene& scene, const Vec3& p0, const Vec3& n0, uint32_t origin, const Vec3& p1,
                                  uint32_t target, bool on_surface, TraceCounters& counters) {
  return on_surface ? shadow_ray_visible(scene, p0, n0, origin, p1, target, counters)
                    : shadow_ray_visible_point(scene, p0, n0, p1, counters);
}

}  // namespace dualight
