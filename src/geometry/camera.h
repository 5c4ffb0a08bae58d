// Pinhole camera with Mitsuba's conventions: `fov` is the full angle along x in degrees, row 0 is
// the top of the image, pixel (i, j) covers [i, i+1) x [j, j+1) in film coordinates.
#pragma once
#include "core/ray.h"

namespace dualight {

class PinholeCamera {
 public:
  PinholeCamera(const Vec3& origin, const Vec3& target, const Vec3& up, float fov_deg, int width,
                int height);

  int width() const { return width_; }
  int height() const { return height_; }
  Vec3 origin() const { return origin_; }
  Vec3 forward() const { return forward_; }

  // Ray through film position (x, y), both in pixels; direction normalised.
  Ray generate_ray(float x, float y) const;

 private:
  Vec3 origin_, forward_, right_, up_;
  float tan_half_x_, tan_half_y_;
  int width_, height_;
};

}  // namespace dualight
