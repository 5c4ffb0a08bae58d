// Where light subpaths from emitters at infinity enter the scene [pbrt-v4 sec. 12.4-12.5;
// Mitsuba 3's directional and envmap sample_ray]: a direction at infinity is a vertex on the
// sphere at infinity, and the ray that brings its light starts on the disk of the scene's
// bounding-sphere radius, perpendicular to the direction and behind the scene, uniformly (the
// planar density 1 / (pi r^2), which at a surface point becomes an area density times the
// cosine there).
#pragma once
#include "core/bounding_sphere.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace dualight {

inline float distant_disk_pdf(const BoundingSphere& s) { return 1.f / (kPi * s.radius * s.radius); }

// A point on the disk facing unit `towards_light` (from the scene towards the emitter), from u.
inline Vec3 distant_disk_point(const BoundingSphere& s, const Vec3& towards_light, Point2 u) {
  const Point2 d = square_to_uniform_disk(u);
  return s.center + Frame::from_normal(towards_light).to_world(Vec3(d.u, d.v, 1.f)) * s.radius;
}

}  // namespace dualight
