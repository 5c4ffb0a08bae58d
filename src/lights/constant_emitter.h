// Constant environment, as Mitsuba 3's `constant` and pbrt-v4's UniformInfiniteLight: radiance
// L arriving from every direction at infinity. Rays that leave the scene see it; next-event
// estimation samples directions uniformly on the sphere (as Mitsuba; the choice's density
// pmf / (4 pi)).
//
// Flux through the scene's bounding sphere of radius r: 4 pi * pi r^2 * L, so power()
// (flux / pi) is 4 pi r^2 L.
//
// Light subpaths: a direction at infinity, uniform on the sphere, then a point on the distant
// disk facing it (lights/distant_disk.h).
#pragma once
#include "core/bounding_sphere.h"
#include "core/sampling.h"
#include "lights/distant_disk.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"

namespace dualight {

struct ConstantEmitter {
  Color L;                // radiance, per channel
  BoundingSphere scene;   // set by the scene (attach_scene)
};

inline void attach_scene(ConstantEmitter& e, const BoundingSphere& s) { e.scene = s; }

constexpr EmitterFlags flags(const ConstantEmitter&) { return EmitterFlags::Infinite; }

inline double power(const ConstantEmitter& e) {
  return 4.0 * kPi * static_cast<double>(e.scene.radius) * e.scene.radius * average(e.L);
}

// Radiance travelling along w (from infinity into the scene): L.
inline Color radiance(const ConstantEmitter& e, const Vec3&, Point2) { return e.L; }

inline float pdf_Le_position(const ConstantEmitter&, float pmf, const Vec3& = {}) { return pmf * kUniformSpherePdf; }
inline EmitterPoint sample_Le_position(const ConstantEmitter&, float pmf, Point2 u) {
  return point_at_infinity(square_to_uniform_sphere(u), pmf * kUniformSpherePdf);
}
inline float pdf_Le_direction(const ConstantEmitter& e, const Vec3&) { return distant_disk_pdf(e.scene); }
// From direction `at` (towards the emitter): a ray along -at from the distant disk.
inline bool sample_Le_direction(const ConstantEmitter& e, float pdf_a, const Vec3& at, Point2, Point2 u, EmitterDirection& d) {
  return ray_from_infinity(e.scene, at, e.L, pdf_a, u, d);
}

// A uniform direction on the sphere, to a point beyond the bounding sphere (the shadow ray's end).
inline bool sample_Li(const ConstantEmitter& e, float pmf, const Vec3& ref, Point2 u, LightSample& s) {
  light_sample_at_infinity(e.scene, ref, square_to_uniform_sphere(u), pmf * kUniformSpherePdf, e.L, s);
  return true;
}
// Solid-angle density of sample_Li finding direction wi (an escaping ray's).
inline float pdf_Li(const ConstantEmitter&, float pmf, const Vec3&, float, float) { return pmf * kUniformSpherePdf; }

}  // namespace dualight
