// A latitude-longitude environment image with Mitsuba 3's conventions (its `envmap`): in the
// map's own frame y is up, a direction d has u = atan2(d.x, -d.z) / (2 pi) (periodic) and
// v = acos(d.y) / pi; radiance is the image's bilinear interpolation, texel-centred in u and
// with rows at v = row / (height - 1) (the first row is the north pole, the last the south);
// images under 2 x 3 pixels are padded by repeating their edges, as Mitsuba does.
//
// Importance sampling [pbrt-v4 sec. 12.5.2; Pharr and Humphreys' piecewise-constant 2D
// distribution]: the map's cells between sample points (width x (height - 1), the bilinear
// patches) are chosen in proportion to their mean corner luminance times their solid angle
// (the sin(theta) Jacobian integrated: 2 pi / width * (cos theta_0 - cos theta_1)), a row by its
// marginal, then a column by its conditional; within a cell directions are uniform in solid
// angle. The density is positive wherever the interpolated radiance is.
#pragma once
#include <cstdint>
#include <vector>

#include "core/distribution.h"
#include "core/frame.h"
#include "core/sampling.h"

namespace dualight {

class EnvironmentMap {
 public:
  // rgb: height x width x 3 linear values, row-major from the top row; to_world: a rotation
  // (the map's frame in the world: its columns s, t, n are the map's x, y, z); scale multiplies
  // the radiance. Throws std::invalid_argument for an empty, negative, non-finite or black image.
  EnvironmentMap(uint32_t width, uint32_t height, const std::vector<float>& rgb, float scale, const Frame& to_world);

  // Radiance arriving from world direction d (unit, pointing away from the scene).
  Color eval(const Vec3& d) const;
  // A world direction towards the environment with its solid-angle density.
  Vec3 sample(Point2 u, float& pdf_w) const;
  float pdf(const Vec3& d) const;
  // Mean radiance over the sphere (mean over channels), scale included.
  double mean_radiance() const { return mean_radiance_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  Color texel(uint32_t x, uint32_t y) const { return texels_[static_cast<size_t>(y) * width_ + x]; }
  // The cell (column, row) a local direction falls in.
  std::pair<uint32_t, uint32_t> cell_of(const Vec3& local) const;
  float cell_solid_angle(uint32_t row) const { return kTwoPiOverWidth() * (cos_theta_[row] - cos_theta_[row + 1]); }
  float kTwoPiOverWidth() const { return 2.f * kPi / static_cast<float>(width_); }

  uint32_t width_ = 0, height_ = 0;
  std::vector<Color> texels_;       // scale included
  Frame to_world_;
  std::vector<float> cos_theta_;    // per row of sample points
  DiscreteDistribution rows_;       // cell rows by marginal weight
  std::vector<DiscreteDistribution> columns_;  // per cell row, its cells' conditional
  double mean_radiance_ = 0.0;
};

}  // namespace dualight
