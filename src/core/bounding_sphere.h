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

}  // namespace dualight
