// Isotropic point light, as Mitsuba 3's `point` and pbrt-v4's PointLight: intensity I (W/sr)
// in every direction from one point in free space. Its position is a Dirac delta: no path can
// hit it, only next-event estimation and light subpaths reach it, and its "area density" is the
// discrete probability of choosing it [Veach 1997, sec. 8.1.1 and 10.3.5].
//
// Irradiance at distance r on a surface facing it: I / r^2. Flux: 4 pi I.
#pragma once
#include <cmath>

#include "core/sampling.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"

namespace dualight {

struct PointEmitter {
  Vec3 p;     // position
  Color I;    // intensity, W/sr per channel
};

constexpr EmitterFlags flags(const PointEmitter&) { return EmitterFlags::DeltaPosition; }

// flux / pi = 4 I (mean over channels).
inline double power(const PointEmitter& e) { return 4.0 * average(e.I); }

// What leaves the point towards w: its intensity.
inline Color radiance(const PointEmitter& e, const Vec3&, Point2) { return e.I; }

inline float pdf_Le_position(const PointEmitter&, float pmf, const Vec3& = {}) { return pmf; }
inline EmitterPoint sample_Le_position(const PointEmitter& e, float pmf, Point2) {
  return {e.p, Vec3(0.f), pmf, 0, false};
}

inline float pdf_Le_direction(const PointEmitter&, const Vec3&) { return kUniformSpherePdf; }
inline bool sample_Le_direction(const PointEmitter& e, float pdf_a, const Vec3&, Point2, Point2 u, EmitterDirection& d) {
  d.w = square_to_uniform_sphere(u);
  d.pdf_w = kUniformSpherePdf;
  d.beta = e.I / (pdf_a * kUniformSpherePdf);  // no cosine at a point
  return true;
}

// The point seen from `ref`: Le carries the 1 / r^2 (pdf_w is the choice's probability).
inline bool sample_Li(const PointEmitter& e, float pmf, const Vec3& ref, Point2, LightSample& s) {
  const Vec3 to_light = e.p - ref;
  s.dist2 = dot(to_light, to_light);
  if (!(s.dist2 > 0.f)) return false;
  s.wi = to_light / std::sqrt(s.dist2);
  s.p = e.p;
  s.n = Vec3(0.f);
  s.pdf_w = pmf;
  s.Le = e.I / s.dist2;
  s.prim = 0;
  s.on_surface = false;
  return true;
}
// No path finds a point by chance.
inline float pdf_Li(const PointEmitter&, float, const Vec3&, float, float) { return 0.f; }

}  // namespace dualight
