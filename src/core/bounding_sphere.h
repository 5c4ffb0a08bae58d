// A sphere around the scene's geometry: where emitters at infinity start their light subpaths
// (a disk of its radius facing the direction of travel) and what their power is measured over
// (pbrt-v4's Bounds3::BoundingSphere, Mitsuba 3's BoundingSphere).
#pragma once
#include "core/vec3.h"

namespace dualight {

struct BoundingSphere {
  Vec3 center;
  float radius = 1.f;
};

// The sphere through the corners of the box [lo, hi], widened by a relative 1e-4 so that points
// on the box lie strictly inside.
inline BoundingSphere bounding_sphere(const Vec3& lo, const Vec3& hi) {
  const Vec3 c = (lo + hi) * 0.5f;
  const float r = length(hi - c);
  return {c, r > 0.f ? r * (1.f + 1e-4f) : 1e-4f};
}

// How far along unit w from p (inside the sphere) a point lies beyond the sphere: where a
// shadow ray towards a direction at infinity ends.
inline float reach_beyond(const BoundingSphere& s, const Vec3& p) { return 2.f * s.radius + length(p - s.center); }

}  // namespace dualight
