// A latitude-longitude environment image with Mitsuba 3's conventions (its `envmap`): in the
// map's own frame y is up, a direction d has u = atan2(d.x, -d.z) / (2 pi) (periodic) and
// v = acos(d.y) / pi; radiance is the image's bilinear interpolation, texel-centred in u and
// with rows at v = row / (height - 1) (the first row is the north pole, the last the south);
// images under 2 x 3 pixels are padded by repeating their edges, as Mitsuba does.
//
// Importance sampling, piecewise bilinear as Mitsuba 3's envmap (its Hierarchical2D warp; pbrt-v4's
// SampleBilinear within a patch): the density over (u, v) is the bilinear interpolation of each
// sample point's luminance times sin(theta) there, so that over solid angle it follows the
// interpolated radiance within each cell. The cells between sample points (width x (height - 1),
// the bilinear patches) are chosen in proportion to their corners' sum, a row by its marginal,
// then a column by its conditional; within a cell (s, t) follows the patch, t by its marginal and
// s by its conditional, both linear. The solid-angle density is that over (u, v) divided by
// 2 pi^2 sin(theta); it is positive wherever the interpolated radiance is, off the poles.
#pragma once
#include <array>
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
  // eval(d) and pdf(d) together: d turned into map coordinates once (the radiance interpolated at
  // d's place in its sampling cell, the texels and weights eval finds, to rounding).
  Color eval(const Vec3& d, float& pdf_w) const;
  // A world direction towards the environment with its solid-angle density, and, where
  // `radiance` is given, eval() there, interpolated at the sample's place in its cell (the same
  // texels and weights as eval's, without turning the direction back into coordinates).
  Vec3 sample(Point2 u, float& pdf_w, Color* radiance = nullptr) const;
  float pdf(const Vec3& d) const;
  // Mean radiance over the sphere (mean over channels), scale included.
  double mean_radiance() const { return mean_radiance_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  Color texel(uint32_t x, uint32_t y) const { return texels_[static_cast<size_t>(y) * width_ + x]; }
  // The bilinear interpolation of texels (x0, y0) to (x0 + 1, y0 + 1), x periodic, by (ax, ay).
  Color bilinear(uint32_t x0, uint32_t y0, float ax, float ay) const;
  // Where a local direction falls: its cell (column x, row y) and its place (s, t) in [0, 1]^2
  // there, and sin(theta).
  struct CellPoint {
    uint32_t x = 0, y = 0;
    float s = 0.f, t = 0.f, sin_theta = 0.f;
  };
  CellPoint cell_of(const Vec3& local) const;
  // The sampling density's corner values of cell (x, y): luminance times sin(theta) at its sample
  // points, in the order (x, y), (x + 1, y), (x, y + 1), (x + 1, y + 1).
  std::array<float, 4> corners(uint32_t x, uint32_t y) const;
  // The solid-angle density at a point of cell (x, y), given the cell's probability.
  float pdf_in_cell(float cell_pmf, const std::array<float, 4>& c, float s, float t, float sin_theta) const;
  // The solid-angle density at a direction's place in its cell.
  float pdf_at(const CellPoint& p) const;

  uint32_t width_ = 0, height_ = 0;
  std::vector<Color> texels_;       // scale included
  Frame to_world_;
  std::vector<float> density_;      // per sample point: luminance times sin(theta), corners() reads
  DiscreteDistribution rows_;       // cell rows by marginal weight
  std::vector<DiscreteDistribution> columns_;  // per cell row, its cells' conditional
  double mean_radiance_ = 0.0;
};

}  // namespace dualight
