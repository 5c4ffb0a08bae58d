// Spot light, as Mitsuba 3's `spot`: a point light whose intensity I, along its axis, falls off
// linearly in angle from the beam width to the cutoff angle and is zero beyond (Mitsuba 3's
// falloff_curve; pbrt-v4's SpotLight uses a smoothstep in cosine instead). Light subpaths leave
// it uniformly in the cutoff cone. A Dirac position like PointEmitter (point_emitter.h).
#pragma once
#include <cmath>

#include "core/frame.h"
#include "core/sampling.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"

namespace dualight {

struct SpotEmitter {
  Vec3 p;            // position
  Frame frame;       // z along the axis of the beam
  Color I;           // intensity on the axis, W/sr per channel
  float cutoff = 0.f;        // half-angles in radians, 0 <= beam_width <= cutoff <= pi / 2
  float beam_width = 0.f;
  float cos_cutoff = 1.f, cos_beam_width = 1.f;
};

inline SpotEmitter make_spot(const Vec3& p, const Vec3& axis, const Color& I, float cutoff, float beam_width) {
  return {p, Frame::from_normal(normalize(axis)), I, cutoff, beam_width, std::cos(cutoff), std::cos(beam_width)};
}

constexpr EmitterFlags flags(const SpotEmitter&) { return EmitterFlags::DeltaPosition; }

// Intensity towards w over the on-axis intensity (Mitsuba 3's falloff_curve).
inline float spot_falloff(const SpotEmitter& e, const Vec3& w) {
  const float cos_theta = dot(normalize(w), e.frame.n);
  if (!(cos_theta > e.cos_cutoff)) return 0.f;
  if (cos_theta >= e.cos_beam_width) return 1.f;
  return (e.cutoff - std::acos(std::min(cos_theta, 1.f))) / (e.cutoff - e.beam_width);
}

// flux / pi, bounded above by the full cone's: 2 (1 - cos cutoff) I (a selection weight only).
inline double power(const SpotEmitter& e) { return 2.0 * (1.0 - double(e.cos_cutoff)) * average(e.I); }

inline Color radiance(const SpotEmitter& e, const Vec3& w, Point2) { return e.I * spot_falloff(e, w); }

inline float pdf_Le_position(const SpotEmitter&, float pmf, const Vec3& = {}) { return pmf; }
inline EmitterPoint sample_Le_position(const SpotEmitter& e, float pmf, Point2) {
  return {e.p, Vec3(0.f), pmf, 0, false};
}

inline float pdf_Le_direction(const SpotEmitter& e, const Vec3& w) {
  return dot(w, e.frame.n) > e.cos_cutoff ? uniform_cone_pdf(e.cos_cutoff) : 0.f;
}
inline bool sample_Le_direction(const SpotEmitter& e, float pdf_a, const Vec3&, Point2, Point2 u, EmitterDirection& d) {
  d.w = e.frame.to_world(square_to_uniform_cone(u, e.cos_cutoff));
  d.pdf_w = uniform_cone_pdf(e.cos_cutoff);
  d.beta = radiance(e, d.w, {}) / (pdf_a * d.pdf_w);
  return !is_black(d.beta);
}

inline bool sample_Li(const SpotEmitter& e, float pmf, const Vec3& ref, Point2, LightSample& s) {
  const Vec3 to_light = e.p - ref;
  s.dist2 = dot(to_light, to_light);
  if (!(s.dist2 > 0.f)) return false;
  s.wi = to_light / std::sqrt(s.dist2);
  s.Le = radiance(e, -s.wi, {}) / s.dist2;
  if (is_black(s.Le)) return false;
  s.p = e.p;
  s.n = Vec3(0.f);
  s.pdf_w = pmf;
  s.prim = 0;
  s.on_surface = false;
  return true;
}
inline float pdf_Li(const SpotEmitter&, float, const Vec3&, float, float) { return 0.f; }

}  // namespace dualight
