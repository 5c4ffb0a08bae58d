// Pinhole camera with Mitsuba's conventions: `fov` is the full angle along x in degrees, row 0 is
// the top of the image, pixel (i, j) covers [i, i+1) x [j, j+1) in film coordinates.
//
// Importance [Veach 1997, sec. 8.1.2; pbrt-v3 sec. 16.1.1]: a pixel's measurement is
// I_j = integral of We_j(w) L(origin, -w) dw, and a camera ray through a uniformly jittered point of
// pixel j has direction density 1 / (A_pixel cos^3 theta) (A_pixel: the pixel's area on the image
// plane at distance 1). So We_j is that density inside pixel j: camera rays sample it exactly.
// Densities for MIS are per film instead (1 / (A_film cos^3)): each pixel's camera samples compete
// with light paths from the whole image, pixels x as many (pbrt's convention).
#pragma once
#include <algorithm>
#include <cmath>
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
  // The image plane's axes and half extents at distance 1 (generate_ray's, for code that
  // computes its rays lane-wide: pathspace/path_lanes_kernel.h).
  Vec3 right() const { return right_; }
  Vec3 up() const { return up_; }
  float tan_half_x() const { return tan_half_x_; }
  float tan_half_y() const { return tan_half_y_; }

  // Film position (in pixels) uniform over the film for u uniform in [0, 1)^2, kept below the
  // width and height, which float rounding of u * width could reach.
  Point2 film_position(Point2 u) const {
    const float w = static_cast<float>(width_), h = static_cast<float>(height_);
    return {std::min(u.u * w, std::nextafter(w, 0.f)), std::min(u.v * h, std::nextafter(h, 0.f))};
  }
  // Ray through film position (x, y), both in pixels; direction normalised.
  Ray generate_ray(float x, float y) const;

  // Film position (in pixels) where the ray from the origin to p crosses the film; false when p
  // is behind the camera or outside the field of view.
  bool raster_position(const Vec3& p, Point2& xy) const;
  // Importance We_j(w) of the pixel j that direction w (unit) falls in: the solid-angle density
  // of camera rays through uniformly jittered points of that pixel. 0 outside the view.
  float importance(const Vec3& w) const;
  // Solid-angle density of a camera ray in direction w through a uniform point of the whole film:
  // importance / pixel count. What MIS weights compare with light subpaths' densities.
  float pdf_w(const Vec3& w) const { return importance(w) * inv_pixel_count_; }

 private:
  Vec3 origin_, forward_, right_, up_;
  float tan_half_x_, tan_half_y_;
  float inv_pixel_area_;  // 1 / (area of one pixel on the image plane at distance 1)
  float inv_pixel_count_;
  int width_, height_;
};

}  // namespace dualight
