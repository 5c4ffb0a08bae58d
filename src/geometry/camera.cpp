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
  inv_pixel_area_ = static_cast<float>(width) * static_cast<float>(height) / (4.f * tan_half_x_ * tan_half_y_);
  inv_pixel_count_ = 1.f / (static_cast<float>(width) * static_cast<float>(height));
}

Ray PinholeCamera::generate_ray(float x, float y) const {
  const float sx = (2.f * x / static_cast<float>(width_) - 1.f) * tan_half_x_;
  const float sy = (1.f - 2.f * y / static_cast<float>(height_)) * tan_half_y_;
  return {origin_, normalize(forward_ + right_ * sx + up_ * sy)};
}

}  // namespace dualight

namespace dualight {

bool PinholeCamera::raster_position(const Vec3& p, Point2& xy) const {
  const Vec3 d = p - origin_;
  const float z = dot(d, forward_);
  if (!(z > 0.f)) return false;
  const float sx = dot(d, right_) / (z * tan_half_x_), sy = dot(d, up_) / (z * tan_half_y_);
  xy = {0.5f * (sx + 1.f) * static_cast<float>(width_), 0.5f * (1.f - sy) * static_cast<float>(height_)};
  return xy.u >= 0.f && xy.u < static_cast<float>(width_) && xy.v >= 0.f && xy.v < static_cast<float>(height_);
}

float PinholeCamera::importance(const Vec3& w) const {
  const float cos_theta = dot(w, forward_);
  if (!(cos_theta > 0.f)) return 0.f;
  const float sx = dot(w, right_) / (cos_theta * tan_half_x_), sy = dot(w, up_) / (cos_theta * tan_half_y_);
  if (!(std::abs(sx) <= 1.f && std::abs(sy) <= 1.f)) return 0.f;
  return inv_pixel_area_ / (cos_theta * cos_theta * cos_theta);
}

}  // namespace dualight
