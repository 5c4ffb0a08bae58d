#include "lights/environment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace dualight {

namespace {

// The image padded to at least 2 x 3 pixels by repeating its last column and row (Mitsuba 3's
// Bitmap::pad_to), as colours.
std::vector<Color> padded(uint32_t& width, uint32_t& height, const std::vector<float>& rgb, float scale) {
  const uint32_t w = std::max(width, 2u), h = std::max(height, 3u);
  std::vector<Color> out(static_cast<size_t>(w) * h);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = 3 * (static_cast<size_t>(std::min(y, height - 1)) * width + std::min(x, width - 1));
      out[static_cast<size_t>(y) * w + x] = Color(rgb[i], rgb[i + 1], rgb[i + 2]) * scale;
    }
  }
  width = w;
  height = h;
  return out;
}

}  // namespace

EnvironmentMap::EnvironmentMap(uint32_t width, uint32_t height, const std::vector<float>& rgb, float scale,
                               const Frame& to_world)
    : to_world_(to_world) {
  if (width == 0 || height == 0 || rgb.size() != 3ull * width * height) {
    throw std::invalid_argument("environment map needs width x height x 3 values");
  }
  for (const float x : rgb) {
    if (!(x >= 0.f) || !std::isfinite(x)) throw std::invalid_argument("environment map values must be finite and >= 0");
  }
  if (!(scale >= 0.f) || !std::isfinite(scale)) throw std::invalid_argument("environment map scale must be finite and >= 0");
  texels_ = padded(width, height, rgb, scale);
  width_ = width;
  height_ = height;
  cos_theta_.resize(height_);
  for (uint32_t y = 0; y < height_; ++y) cos_theta_[y] = std::cos(kPi * static_cast<float>(y) / (height_ - 1));
  cos_theta_.front() = 1.f;
  cos_theta_.back() = -1.f;

  std::vector<double> row_weight(height_ - 1);
  columns_.reserve(height_ - 1);
  double flux = 0.0;  // sum over cells of mean radiance (over channels) times solid angle
  for (uint32_t y = 0; y + 1 < height_; ++y) {
    std::vector<double> cell(width_);
    for (uint32_t x = 0; x < width_; ++x) {
      const uint32_t x1 = (x + 1) % width_;
      const Color corners = texel(x, y) + texel(x1, y) + texel(x, y + 1) + texel(x1, y + 1);
      cell[x] = 0.25 * luminance(corners) * cell_solid_angle(y);
      flux += 0.25 * average(corners) * cell_solid_angle(y);
    }
    double sum = 0.0;
    for (const double c : cell) sum += c;
    row_weight[y] = sum;
    if (!(sum > 0.0)) std::fill(cell.begin(), cell.end(), 1.0);  // never chosen: its row has pmf 0
    columns_.emplace_back(cell);
  }
  double total = 0.0;
  for (const double r : row_weight) total += r;
  if (!(total > 0.0)) throw std::invalid_argument("environment map is black: it has no positive pixel");
  rows_ = DiscreteDistribution(row_weight);
  mean_radiance_ = flux / (4.0 * kPi);
}

Color EnvironmentMap::eval(const Vec3& d) const {
  const Vec3 v = to_world_.to_local(d);
  float u = std::atan2(v.x, -v.z) * (0.5f * kInvPi);
  u -= std::floor(u);
  const float t = std::acos(std::clamp(v.y, -1.f, 1.f)) * kInvPi;
  // Texel-centred in u (periodic), sample rows at v = row / (height - 1).
  const float px = u * static_cast<float>(width_) - 0.5f, py = t * static_cast<float>(height_ - 1);
  const float fx0 = std::floor(px);
  const float fy = std::min(std::floor(py), static_cast<float>(height_ - 2));
  const float ax = px - fx0, ay = py - fy;
  const uint32_t x0 = static_cast<uint32_t>(static_cast<int64_t>(fx0) + width_) % width_;
  const uint32_t x1 = (x0 + 1) % width_, y0 = static_cast<uint32_t>(fy), y1 = y0 + 1;
  const Color top = texel(x0, y0) * (1.f - ax) + texel(x1, y0) * ax;
  const Color bottom = texel(x0, y1) * (1.f - ax) + texel(x1, y1) * ax;
  return top * (1.f - ay) + bottom * ay;
}

std::pair<uint32_t, uint32_t> EnvironmentMap::cell_of(const Vec3& v) const {
  float u = std::atan2(v.x, -v.z) * (0.5f * kInvPi) - 0.5f / static_cast<float>(width_);
  u -= std::floor(u);
  const uint32_t x = std::min(static_cast<uint32_t>(u * static_cast<float>(width_)), width_ - 1);
  // The row whose band [cos theta_{y+1}, cos theta_y] holds v.y.
  const auto it = std::upper_bound(cos_theta_.begin(), cos_theta_.end(), v.y, std::greater<float>());
  const uint32_t y = static_cast<uint32_t>(std::clamp<std::ptrdiff_t>(it - cos_theta_.begin() - 1, 0, height_ - 2));
  return {x, y};
}

Vec3 EnvironmentMap::sample(Point2 u, float& pdf_w) const {
  const uint32_t y = static_cast<uint32_t>(rows_.sample(u.v));
  const uint32_t x = static_cast<uint32_t>(columns_[y].sample(u.u));
  pdf_w = rows_.pmf(y) * columns_[y].pmf(x) / cell_solid_angle(y);
  const float phi = kTwoPiOverWidth() * (static_cast<float>(x) + 0.5f + u.u);
  const float cos_theta = cos_theta_[y] + (cos_theta_[y + 1] - cos_theta_[y]) * u.v;
  const float sin_theta = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  return to_world_.to_world(Vec3(std::sin(phi) * sin_theta, cos_theta, -std::cos(phi) * sin_theta));
}

float EnvironmentMap::pdf(const Vec3& d) const {
  const auto [x, y] = cell_of(to_world_.to_local(d));
  return rows_.pmf(y) * columns_[y].pmf(x) / cell_solid_angle(y);
}

}  // namespace dualight
