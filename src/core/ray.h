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
};

// Moves p off its surface along n by a few ulps of p's magnitude (integer steps on the float bits),
// which is scale-invariant, unlike a fixed epsilon [Waechter and Binder, Ray Tracing Gems ch. 6].
inline Vec3 offset_ray_origin(const Vec3& p, const Vec3& n) {
  constexpr float kOrigin = 1.f / 32.f, kFloatScale = 1.f / 65536.f, kIntScale = 256.f;
  auto shift = [](float v, float nv) {
    const int32_t of = static_cast<int32_t>(kIntScale * nv);
    int32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    bits += (v < 0.f) ? -of : of;
    float shifted;
    std::memcpy(&shifted, &bits, sizeof shifted);
    return std::abs(v) < kOrigin ? v + kFloatScale * nv : shifted;
  };
  return {shift(p.x, n.x), shift(p.y, n.y), shift(p.z, n.z)};
}

}  // namespace dualight
