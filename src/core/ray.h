// Rays and the offset that keeps a spawned ray from re-hitting the surface it leaves.
#pragma once
#include <cstdint>
#include <cstring>
#include <limits>

#include "core/vec3.h"

namespace dualight {

struct Ray {
  Vec3 o, d;
  float tmax = std::numeric_limits<float>::infinity();
  float tmin = 0.f;  // hits closer than this are ignored (rays from the eye: Scene::eye_clearance)
};

// Moves p off its surface along n by a few ulps of p's magnitude (integer steps on the float bits),
// which is scale-invariant, unlike a fixed epsilon [Waechter and Binder, Ray Tracing Gems ch. 6].
// Components near 0 (below 1/32) move by a fixed 1/65536 instead: their ulps are far below the
// rounding of a hit point, which follows the point's other components. Both constants assume a
// scene about a unit across or larger; `scene_scale` (the scene's extent, capped at 1: see
// Scene::offset_scale) shrinks them with a smaller scene, whose points would otherwise all move
// by 1/65536 (a quarter of a scene 6e-5 across: issue 18). At scale 1 nothing changes.
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& n, float scene_scale) {
  constexpr float kOrigin = 1.f / 32.f, kFloatScale = 1.f / 65536.f, kIntScale = 256.f;
  const float origin = kOrigin * scene_scale, float_scale = kFloatScale * scene_scale;
  auto shift = [origin, float_scale](float v, float nv) {
    const int32_t of = static_cast<int32_t>(kIntScale * nv);
    int32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits += (v < 0.f) ? -of : of;
    float shifted;
    std::memcpy(&shifted, &bits, sizeof shifted);
    return std::abs(v) < origin ? v + float_scale * nv : shifted;
  };
  return {shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z)};
}

}  // namespace dualight
