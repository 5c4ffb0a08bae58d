#include "geometry/camera.h"

#include <cmath>
#include <stdexcept>

#include "core/sampling.h"

namespace dualight {

PinholeCamera::PinholeCamera(const Vec3& origin, const Vec3& target, const Vec3& up, float fov_deg,
                             int width, int height)
    : origin_(origin), width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("camera resolution must be at least 1x1");
  if (!(fov_deg > 0.f && fov_deg < 180.f)) throw std::invalid_argument("fov must be in (0, 180) degrees");
  const Vec3 d = target - origin;
  if (!(length(d) > 0.f)) throw std::invalid_argument("camera target equals its origin");
  forward_ = normalize(d);
  const Vec3 r = cross(forward_, up);
  if (!(length(r) > 1e-6f * length(up))) throw std::invalid_argument("camera up is parallel to the view");
  right_ = normalize(r);
  up_ = cross(right_, forward_);
  tan_half_x_ = std::tan(0.5f * fov_deg * kPi / 180.f);
  tan_half_y_ = tan_half_x_ * static_cast<float>(height) / static_cast<float>(width);
}

Ray PinholeCamera::generate_ray(float x, float y) const {
  const float sx = (2.f * x / static_cast<float>(width_) - 1.f) * tan_half_x_;
  const float sy = (1.f - 2.f * y / static_cast<float>(height_)) * tan_half_y_;
  return {origin_, normalize(forward_ + right_ * sx + up_ * sy)};
}

}  // namespace dualight
