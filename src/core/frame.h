// Orthonormal frame around a normal; directions in local coordinates have z = cos(theta).
#pragma once
#include "core/vec3.h"

namespace dualight {

struct Frame {
  Vec3 s, t, n;

  // Branchless basis [Duff et al. 2017, "Building an Orthonormal Basis, Revisited"].
  static Frame from_normal(const Vec3& n) {
    const float sign = std::copysign(1.f, n.z);
    const float a = -1.f / (sign + n.z);
    const float b = n.x * n.y * a;
    return {Vec3(1.f + sign * n.x * n.x * a, sign * b, -sign * n.x), Vec3(b, sign + n.y * n.y * a, -n.y),
            n};
  }
  Vec3 to_local(const Vec3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  Vec3 to_world(const Vec3& v) const { return s * v.x + t * v.y + n * v.z; }
};

}  // namespace dualight
