// Pinhole camera with Mitsuba's conventions: `fov` is the full angle along x in degrees, row 0 is
// the top of the image, pixel (i, j) covers [i, i+1) x [j, j+1) in film coordinates.
//
// Importance [Veach 1997, sec. 8.1.2; pbrt-v3 sec. 16.1.1]: a pixel's measurement is
// I_j = integral of We_j(w) L(origin, -w) dw, and a camera ray through a uniformly jittered point of
// pixel j has direction density p(w) = 1 / (A_pixel cos^3 theta) (A_pixel: the pixel's area on the
// image plane at distance 1). So We_j = p inside pixel j: camera rays sample importance exactly.
#pragma once
#include "core/ray.h"
#include "core/sampling.h"

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

  // Film position (in pixels) where the ray from the origin to p crosses the film; false when p
  // is behind the camera or outside the field of view.
  bool raster_position(const Vec3& p, Point2& xy) const;
  // Solid-angle density of generate_ray's direction w (unit) for a uniformly jittered film position
  // in w's pixel; also the pixel's importance We_j(w). 0 outside the field of view.
  float pdf_w(const Vec3& w) const;

 private:
  Vec3 origin_, forward_, right_, up_;
  float tan_half_x_, tan_half_y_;
  float inv_pixel_area_;  // 1 / (area of one pixel on the image plane at distance 1)
  int width_, height_;
};

}  // namespace dualight
