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
#include "lights/emitter_sample.h"

namespace dualight {

inline float distant_disk_pdf(const BoundingSphere& s) { return 1.f / (kPi * s.radius * s.radius); }

// A point on the disk facing unit `towards_light` (from the scene towards the emitter), from u.
inline Vec3 distant_disk_point(const BoundingSphere& s, const Vec3& towards_light, Point2 u) {
  const Point2 d = square_to_uniform_disk(u);
  return s.center + Frame::from_normal(towards_light).to_world(Vec3(d.u, d.v, 1.f)) * s.radius;
}

// A light subpath's start at unit direction `towards_light` with density pdf_a (solid angle,
// or a direction's probability).
inline EmitterPoint point_at_infinity(const Vec3& towards_light, float pdf_a) {
  EmitterPoint y{towards_light, towards_light, pdf_a, 0, false};
  y.at_infinity = true;
  return y;
}

// The ray that brings radiance Le from `towards_light` (sampled with density pdf_a) into the
// scene: from the distant disk, along -towards_light; beta = Le / (pdf_a pdf_disk).
inline bool ray_from_infinity(const BoundingSphere& s, const Vec3& towards_light, const Color& Le, float pdf_a,
                              Point2 u, EmitterDirection& d) {
  d.w = -towards_light;
  d.origin = distant_disk_point(s, towards_light, u);
  d.pdf_w = distant_disk_pdf(s);
  if (!(pdf_a > 0.f)) return false;
  d.beta = Le / (pdf_a * d.pdf_w);
  return true;
}

// Next-event estimation towards unit direction wi at infinity from `ref` (inside the sphere):
// the shadow ray ends beyond the sphere; pdf_w includes the emitter's choice.
inline void light_sample_at_infinity(const BoundingSphere& s, const Vec3& ref, const Vec3& wi, float pdf_w,
                                     const Color& Le, LightSample& ls) {
  const float reach = reach_beyond(s, ref);
  ls.wi = wi;
  ls.p = ref + wi * reach;
  ls.n = Vec3(0.f);
  ls.dist2 = reach * reach;
  ls.pdf_w = pdf_w;
  ls.Le = Le;
  ls.prim = 0;
  ls.on_surface = false;
}

}  // namespace dualight
