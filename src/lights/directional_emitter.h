// Directional light, as Mitsuba 3's `directional` and pbrt-v4's DistantLight: irradiance E
// (W/m^2, on a plane facing it) arriving along one direction from infinitely far away, the sun's
// idealisation. Its direction is a Dirac delta: no path can hit it, only next-event estimation
// (towards -w, unoccluded to infinity) and light subpaths reach it. Light subpaths start on the
// distant disk (lights/distant_disk.h) [pbrt-v4 sec. 12.4]: uniform on it, then along w.
//
// Flux through the scene: E pi r^2, so power() (flux / pi) is E r^2 for the sphere's radius r.
#pragma once
#include <cmath>

#include "core/bounding_sphere.h"
#include "core/frame.h"
#include "core/sampling.h"
#include "lights/distant_disk.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"

namespace dualight {

struct DirectionalEmitter {
  Frame frame;   // n: unit direction the light travels in
  Color E;       // irradiance on a plane perpendicular to it, per channel
  BoundingSphere scene;  // set by the scene (attach_scene)
};

inline DirectionalEmitter make_directional(const Vec3& direction, const Color& E) {
  return {Frame::from_normal(normalize(direction)), E, {}};
}

inline void attach_scene(DirectionalEmitter& e, const BoundingSphere& s) { e.scene = s; }

constexpr EmitterFlags flags(const DirectionalEmitter&) {
  return static_cast<EmitterFlags>(static_cast<uint8_t>(EmitterFlags::DeltaDirection) |
                                   static_cast<uint8_t>(EmitterFlags::Infinite));
}

inline double power(const DirectionalEmitter& e) {
  return static_cast<double>(e.scene.radius) * e.scene.radius * average(e.E);
}

// What reaches a plane facing it per unit area: its irradiance (in the measure of its disk).
inline Color radiance(const DirectionalEmitter& e, const Vec3&, Point2) { return e.E; }

// Light subpaths: its direction at infinity, with the choice's probability (a delta: the
// position of a point at infinity [Veach 1997, sec. 8.1.1]), then a point on the distant disk
// (lights/distant_disk.h) from which the ray travels along w.
inline float pdf_Le_position(const DirectionalEmitter&, float pmf, const Vec3& = {}) { return pmf; }
inline EmitterPoint sample_Le_position(const DirectionalEmitter& e, float pmf, Point2) {
  return point_at_infinity(-e.frame.n, pmf);
}
inline float pdf_Le_direction(const DirectionalEmitter& e, const Vec3&) { return distant_disk_pdf(e.scene); }
// beta = E / (pdf_a pdf_disk): the flux through the disk over the choice's probability.
inline bool sample_Le_direction(const DirectionalEmitter& e, float pdf_a, const Vec3&, Point2, Point2 u,
                                EmitterDirection& d) {
  return ray_from_infinity(e.scene, -e.frame.n, e.E, pdf_a, u, d);
}

// Seen from `ref`: towards -w, to a point beyond the bounding sphere (the shadow ray's end);
// pdf_w is the choice's probability, Le the irradiance.
inline bool sample_Li(const DirectionalEmitter& e, float pmf, const Vec3& ref, Point2, LightSample& s) {
  light_sample_at_infinity(e.scene, ref, -e.frame.n, pmf, e.E, s);
  return true;
}
// No path finds one direction by chance.
inline float pdf_Li(const DirectionalEmitter&, float, const Vec3&, float, float) { return 0.f; }

}  // namespace dualight
