// Image-based environment, as Mitsuba 3's `envmap` and pbrt-v4's ImageInfiniteLight: radiance
// from every direction at infinity, read from a latitude-longitude image (environment_map.h,
// which also importance-samples it). Rays that leave the scene see it; next-event estimation
// samples directions in proportion to its luminance.
//
// Flux through the scene's bounding sphere of radius r: 4 pi * pi r^2 times the mean radiance,
// so power() (flux / pi) is 4 pi r^2 times it.
//
// Light subpaths: a direction at infinity sampled as next-event estimation samples it, then a
// point on the distant disk facing it (lights/distant_disk.h).
#pragma once
#include <memory>

#include "core/bounding_sphere.h"
#include "lights/distant_disk.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"
#include "lights/environment_map.h"

namespace dualight {

struct EnvmapEmitter {
  std::shared_ptr<const EnvironmentMap> map;  // shared by the copies of one emitter
  BoundingSphere scene;                       // set by the scene (attach_scene)
};

inline void attach_scene(EnvmapEmitter& e, const BoundingSphere& s) { e.scene = s; }

constexpr EmitterFlags flags(const EnvmapEmitter&) { return EmitterFlags::Infinite; }

inline double power(const EnvmapEmitter& e) {
  return 4.0 * kPi * static_cast<double>(e.scene.radius) * e.scene.radius * e.map->mean_radiance();
}

// Radiance travelling along w (from infinity into the scene): the map seen towards -w.
inline Color radiance(const EnvmapEmitter& e, const Vec3& w, Point2) { return e.map->eval(-normalize(w)); }

inline float pdf_Le_position(const EnvmapEmitter& e, float pmf, const Vec3& at) { return pmf * e.map->pdf(at); }
inline EmitterPoint sample_Le_position(const EnvmapEmitter& e, float pmf, Point2 u) {
  float pdf = 0.f;
  const Vec3 w = e.map->sample(u, pdf);
  return point_at_infinity(w, pmf * pdf);
}
inline float pdf_Le_direction(const EnvmapEmitter& e, const Vec3&) { return distant_disk_pdf(e.scene); }
// From direction `at` (towards the emitter): a ray along -at from the distant disk.
inline bool sample_Le_direction(const EnvmapEmitter& e, float pdf_a, const Vec3& at, Point2, Point2 u, EmitterDirection& d) {
  return ray_from_infinity(e.scene, at, e.map->eval(at), pdf_a, u, d);
}

// A direction sampled by the map's luminance, to a point beyond the bounding sphere.
inline bool sample_Li(const EnvmapEmitter& e, float pmf, const Vec3& ref, Point2 u, LightSample& s) {
  float pdf = 0.f;
  Color Le;
  const Vec3 wi = e.map->sample(u, pdf, &Le);
  if (!(pdf > 0.f)) return false;
  light_sample_at_infinity(e.scene, ref, wi, pmf * pdf, Le, s);
  return true;
}
// Solid-angle density of sample_Li finding unit direction wi (an escaping ray's).
inline float pdf_Li(const EnvmapEmitter& e, float pmf, const Vec3& wi, float, float) { return pmf * e.map->pdf(wi); }

// radiance() towards -d and pdf_Li at d (emitter.h), from one look-up of d's place in the map.
inline Color radiance_seen(const EnvmapEmitter& e, float pmf, const Vec3& d, float& pdf_light_w) {
  float pdf = 0.f;
  const Color L = e.map->eval(d, pdf);
  pdf_light_w = pmf * pdf;
  return L;
}

}  // namespace dualight
