// Diffuse area emitter on one triangle, as Mitsuba 3's `area` emitter and pbrt-v4's
// DiffuseAreaLight: radiance leaving the front side (the right-hand-rule normal's), constant or
// a texture looked up at the point's surface coordinates (Mitsuba's `radiance` texture).
// Emission factors into a position part, uniform on the triangle, and a direction part, the
// cosine lobe around the normal [Veach 1997, sec. 8.3.2: Le = Le0 * Le1].
//
// Densities include the emitter's selection probability `pmf` (the scene's power-proportional
// choice, emitter_sampler.h): the area density is pmf / area, rounded once, so every estimator
// computes it the same way. Positions are uniform on the triangle, textured or not (as Mitsuba's
// next-event estimation); a textured triangle's power, and so its choice, is its texture's mean
// over it.
#pragma once
#include <cmath>
#include <cstdint>

#include "core/frame.h"
#include "core/sampling.h"
#include "lights/emitter_flags.h"
#include "lights/emitter_sample.h"
#include "materials/texture.h"

namespace dualight {

struct AreaEmitter {
  Vec3 p0, p1, p2;  // the triangle's corners
  Vec3 n;           // unit normal of the emitting side
  float area = 0.f;
  uint32_t prim = 0;  // the scene triangle
  Color Le;           // radiance leaving the front side; a texture's mean over the triangle
  const Texture* texture = nullptr;  // the radiance where textured (owned by the scene's material)
  Point2 uv0{0.f, 0.f}, uv1{1.f, 0.f}, uv2{0.f, 1.f};  // the corners' surface coordinates
};

// Surface coordinates at barycentrics b of corners 1 and 2.
inline Point2 surface_uv(const AreaEmitter& e, Point2 b) {
  const float b0 = 1.f - b.u - b.v;
  return {b0 * e.uv0.u + b.u * e.uv1.u + b.v * e.uv2.u, b0 * e.uv0.v + b.u * e.uv1.v + b.v * e.uv2.v};
}
// Radiance leaving the front side at surface coordinates uv (the texture's lookup out of the
// way of the untextured emitters most scenes have).
inline Color radiance_at(const AreaEmitter& e, Point2 uv) {
  if (__builtin_expect(e.texture != nullptr, 0)) return eval_rgb(*e.texture, uv);
  return e.Le;
}

constexpr EmitterFlags flags(const AreaEmitter&) { return EmitterFlags::Surface; }

// The emitter choice's weight: flux / pi (area times mean radiance here).
inline double power(const AreaEmitter& e) { return static_cast<double>(e.area) * average(e.Le); }

// Radiance leaving the emitter's point at surface coordinates uv towards w (any length):
// one-sided.
inline Color radiance(const AreaEmitter& e, const Vec3& w, Point2 uv) {
  return dot(e.n, w) > 0.f ? radiance_at(e, uv) : Color(0.f);
}

inline float pdf_Le_position(const AreaEmitter& e, float pmf, const Vec3& = {}) { return pmf / e.area; }
inline EmitterPoint sample_Le_position(const AreaEmitter& e, float pmf, Point2 u) {
  const Point2 b = square_to_uniform_triangle(u);
  EmitterPoint y{e.p0 * (1.f - b.u - b.v) + e.p1 * b.u + e.p2 * b.v, e.n, pdf_Le_position(e, pmf), e.prim};
  if (e.texture != nullptr) y.uv = surface_uv(e, b);  // only a texture reads it
  return y;
}

// Directional density of emission towards unit w.
inline float pdf_Le_direction(const AreaEmitter& e, const Vec3& w) { return cosine_hemisphere_pdf(dot(e.n, w)); }
// pdf_a: the density of the emitter point the direction leaves from, uv its surface
// coordinates. False (with w and pdf_w still set) when the direction has density 0.
inline bool sample_Le_direction(const AreaEmitter& e, float pdf_a, const Vec3&, Point2 uv, Point2 u,
                                EmitterDirection& d) {
  const Vec3 local = square_to_cosine_hemisphere(u);
  d.pdf_w = cosine_hemisphere_pdf(local.z);
  d.w = Frame::from_normal(e.n).to_world(local);
  if (!(d.pdf_w > 0.f)) return false;
  d.beta = radiance_at(e, uv) * (kPi / pdf_a);  // Le cos / (pdf_a cos / pi)
  return true;
}

// A point on the emitter that faces `ref`; false when the sampled point faces away.
inline bool sample_Li(const AreaEmitter& e, float pmf, const Vec3& ref, Point2 u, LightSample& s) {
  const EmitterPoint y = sample_Le_position(e, pmf, u);
  const Vec3 to_light = y.p - ref;
  s.dist2 = dot(to_light, to_light);
  s.wi = to_light / std::sqrt(s.dist2);
  const float cos_light = -dot(y.n, s.wi);
  if (!(cos_light > 0.f && s.dist2 > 0.f)) return false;
  s.p = y.p;
  s.n = y.n;
  s.pdf_w = y.pdf_a * s.dist2 / cos_light;
  s.Le = radiance_at(e, y.uv);
  s.prim = y.prim;
  return true;
}
// Solid-angle density of sample_Li finding the emitter point at distance `dist` whose normal
// makes cosine `cos_light` with the direction to the reference point.
inline float pdf_Li(const AreaEmitter& e, float pmf, const Vec3&, float dist, float cos_light) {
  return pdf_Le_position(e, pmf) * dist * dist / cos_light;
}

}  // namespace dualight
