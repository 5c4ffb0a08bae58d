// Emitters: a closed set held in a std::variant, evaluated by free functions (pbrt-v4's
// base/light.h). Each member lives in its own file with its flags and maths: emission
// (radiance, sample_Le_* / pdf_Le_* for light subpaths) and next-event estimation (sample_Li /
// pdf_Li), with the types of emitter_sample.h. Estimators ask through the dispatchers here and
// decide by flags (emitter_flags.h); none writes an emitter's density itself. The scene chooses
// among emitters in proportion to power (emitter_sampler.h) and passes that choice's
// probability in.
//
// Conventions every member keeps: power() is flux / pi (the choice's weight; an area emitter's
// area times mean radiance, a point's 4 times its mean intensity); radiance(e, w, uv) is what
// leaves the emitter's point (of surface coordinates uv, which members without a surface
// ignore) towards w, in the measure its position density uses (a point emitter: its
// intensity, its position's density a discrete probability); a member without a surface samples
// positions with on_surface = false and a zero normal, and paths never hit it. Members at
// infinity (flag Infinite) learn the scene's bounding sphere from attach_scene; those whose
// direction is not a delta are what rays leaving the scene see (radiance towards -ray.d,
// pdf_Li at the ray's direction). Their light subpaths start at a direction at infinity
// (EmitterPoint::at_infinity) and enter the scene from the distant disk (distant_disk.h).
#pragma once
#include <variant>

#include "lights/area_emitter.h"
#include "lights/constant_emitter.h"
#include "lights/directional_emitter.h"
#include "lights/envmap_emitter.h"
#include "lights/point_emitter.h"
#include "lights/spot_emitter.h"

namespace dualight {

using Emitter =
    std::variant<AreaEmitter, PointEmitter, SpotEmitter, DirectionalEmitter, ConstantEmitter, EnvmapEmitter>;

// Members away from infinity ignore the scene's bounds.
template <class E>
void attach_scene(E&, const BoundingSphere&) {}

// f(the member e holds). Area emitters, the only kind in most scenes and the one paths hit,
// are tested first and inlined ahead of the std::visit over the other members (the light
// tracer's render took 0.5 % fewer instructions; the path tracer's +1.6 % over the one-member
// variant stayed: issue 20's note).
template <class F>
[[gnu::always_inline]] inline decltype(auto) with_emitter(const Emitter& e, F&& f) {
  if (const auto* a = std::get_if<AreaEmitter>(&e)) return f(*a);
  return std::visit(f, e);
}

inline EmitterFlags flags(const Emitter& e) {
  return with_emitter(e, [](const auto& x) { return flags(x); });
}
inline bool is_delta_position(const Emitter& e) { return is_delta_position(flags(e)); }
inline bool is_delta_direction(const Emitter& e) { return is_delta_direction(flags(e)); }
// No path finds it by chance (a delta position or direction): only sampling the emitter does.
inline bool is_delta_light(const Emitter& e) { return is_delta_light(flags(e)); }
inline bool is_infinite(const Emitter& e) { return has_any(flags(e), EmitterFlags::Infinite); }
inline void attach_scene(Emitter& e, const BoundingSphere& s) {
  std::visit([&](auto& x) { attach_scene(x, s); }, e);
}
inline double power(const Emitter& e) {
  return with_emitter(e, [](const auto& x) { return power(x); });
}
inline Color radiance(const Emitter& e, const Vec3& w, Point2 uv) {
  return with_emitter(e, [&](const auto& x) { return radiance(x, w, uv); });
}
// The density of the emitter point (or direction at infinity) `at` as a light subpath's start.
inline float pdf_Le_position(const Emitter& e, float pmf, const Vec3& at) {
  return with_emitter(e, [&](const auto& x) { return pdf_Le_position(x, pmf, at); });
}
inline EmitterPoint sample_Le_position(const Emitter& e, float pmf, Point2 u) {
  return with_emitter(e, [&](const auto& x) { return sample_Le_position(x, pmf, u); });
}
inline float pdf_Le_direction(const Emitter& e, const Vec3& w) {
  return with_emitter(e, [&](const auto& x) { return pdf_Le_direction(x, w); });
}
// A direction of emission from the emitter point `at` (surface coordinates uv) sampled with
// density pdf_a.
inline bool sample_Le_direction(const Emitter& e, float pdf_a, const Vec3& at, Point2 uv, Point2 u,
                                EmitterDirection& d) {
  return with_emitter(e, [&](const auto& x) { return sample_Le_direction(x, pdf_a, at, uv, u, d); });
}
inline bool sample_Li(const Emitter& e, float pmf, const Vec3& ref, Point2 u, LightSample& s) {
  return with_emitter(e, [&](const auto& x) { return sample_Li(x, pmf, ref, u, s); });
}
// Solid-angle density of sample_Li finding, along unit wi, the emitter point at distance `dist`
// whose normal makes cosine `cos_light` with -wi (members at infinity read wi only).
inline float pdf_Li(const Emitter& e, float pmf, const Vec3& wi, float dist, float cos_light) {
  return with_emitter(e, [&](const auto& x) { return pdf_Li(x, pmf, wi, dist, cos_light); });
}

// What a ray leaving the scene along unit d sees of an environment: the radiance arriving along
// -d, and in pdf_light_w pdf_Li's density of finding d. A member may compute both at once
// (envmap_emitter.h); this is the two calls.
template <class E>
Color radiance_seen(const E& e, float pmf, const Vec3& d, float& pdf_light_w) {
  pdf_light_w = pdf_Li(e, pmf, d, 0.f, 1.f);
  return radiance(e, -d, {});
}
inline Color radiance_seen(const Emitter& e, float pmf, const Vec3& d, float& pdf_light_w) {
  return with_emitter(e, [&](const auto& x) { return radiance_seen(x, pmf, d, pdf_light_w); });
}

}  // namespace dualight
