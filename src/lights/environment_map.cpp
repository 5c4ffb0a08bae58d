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
  // sin(theta) of each row of sample points, the poles exact.
  std::vector<float> sin_theta(height_);
  for (uint32_t y = 0; y < height_; ++y) sin_theta[y] = std::sin(kPi * static_cast<float>(y) / (height_ - 1));
  sin_theta.front() = 0.f;
  sin_theta.back() = 0.f;
  density_.resize(texels_.size());
  for (size_t i = 0; i < texels_.size(); ++i) density_[i] = luminance(texels_[i]) * sin_theta[i / width_];

  std::vector<double> row_weight(height_ - 1);
  columns_.reserve(height_ - 1);
  double flux = 0.0;  // sum over cells of mean radiance (over channels) times solid angle
  // cos(theta) of each row of sample points, the poles exact.
  const auto cos_theta = [this](uint32_t y) {
    return y == 0 ? 1.f : (y + 1 == height_ ? -1.f : std::cos(kPi * static_cast<float>(y) / (height_ - 1)));
  };
  for (uint32_t y = 0; y + 1 < height_; ++y) {
    const float solid_angle = 2.f * kPi / static_cast<float>(width_) * (cos_theta(y) - cos_theta(y + 1));
    std::vector<double> cell(width_);
    for (uint32_t x = 0; x < width_; ++x) {
      const std::array<float, 4> c = corners(x, y);
      cell[x] = static_cast<double>(c[0]) + c[1] + c[2] + c[3];
      const uint32_t x1 = (x + 1) % width_;
      flux += 0.25 * average(texel(x, y) + texel(x1, y) + texel(x, y + 1) + texel(x1, y + 1)) * solid_angle;
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
  const uint32_t x0 = static_cast<uint32_t>(static_cast<int64_t>(fx0) + width_) % width_;
  return bilinear(x0, static_cast<uint32_t>(fy), px - fx0, py - fy);
}

Color EnvironmentMap::bilinear(uint32_t x0, uint32_t y0, float ax, float ay) const {
  const uint32_t x1 = (x0 + 1) % width_, y1 = y0 + 1;
  const Color top = texel(x0, y0) * (1.f - ax) + texel(x1, y0) * ax;
  const Color bottom = texel(x0, y1) * (1.f - ax) + texel(x1, y1) * ax;
  return top * (1.f - ay) + bottom * ay;
}

std::array<float, 4> EnvironmentMap::corners(uint32_t x, uint32_t y) const {
  const uint32_t x1 = (x + 1) % width_;
  const float* top = &density_[static_cast<size_t>(y) * width_];
  const float* bottom = top + width_;
  return {top[x], top[x1], bottom[x], bottom[x1]};
}

EnvironmentMap::CellPoint EnvironmentMap::cell_of(const Vec3& v) const {
  CellPoint c;
  // Columns of cells start at texel centres: u * width - 0.5 (periodic).
  float u = std::atan2(v.x, -v.z) * (0.5f * kInvPi);
  u -= std::floor(u);
  float px = u * static_cast<float>(width_) - 0.5f;
  if (px < 0.f) px += static_cast<float>(width_);
  c.x = std::min(static_cast<uint32_t>(px), width_ - 1);
  c.s = std::clamp(px - static_cast<float>(c.x), 0.f, 1.f);
  const float py = std::acos(std::clamp(v.y, -1.f, 1.f)) * kInvPi * static_cast<float>(height_ - 1);
  c.y = std::min(static_cast<uint32_t>(py), height_ - 2);
  c.t = std::clamp(py - static_cast<float>(c.y), 0.f, 1.f);
  c.sin_theta = std::sqrt(std::max(0.f, 1.f - v.y * v.y));
  return c;
}

float EnvironmentMap::pdf_in_cell(float cell_pmf, const std::array<float, 4>& c, float s, float t,
                                  float sin_theta) const {
  const float sum = c[0] + c[1] + c[2] + c[3];
  if (!(sum > 0.f) || !(sin_theta > 0.f)) return 0.f;
  const float f = (1.f - t) * ((1.f - s) * c[0] + s * c[1]) + t * ((1.f - s) * c[2] + s * c[3]);
  // Over (s, t) the patch's density is f / (sum / 4); a cell spans 1 / width by 1 / (height - 1)
  // of (u, v), and d omega = 2 pi^2 sin(theta) du dv.
  const float cells = static_cast<float>(width_) * static_cast<float>(height_ - 1);
  return cell_pmf * (4.f * f / sum) * cells / (2.f * kPi * kPi * sin_theta);
}

Vec3 EnvironmentMap::sample(Point2 u, float& pdf_w, Color* radiance) const {
  const uint32_t y = static_cast<uint32_t>(rows_.sample(u.v));
  const uint32_t x = static_cast<uint32_t>(columns_[y].sample(u.u));
  const std::array<float, 4> c = corners(x, y);
  // t by the patch's marginal, s by its conditional given t: both linear.
  const float t = sample_linear(u.v, c[0] + c[1], c[2] + c[3]);
  const float s = sample_linear(u.u, (1.f - t) * c[0] + t * c[2], (1.f - t) * c[1] + t * c[3]);
  const float phi = 2.f * kPi * (static_cast<float>(x) + 0.5f + s) / static_cast<float>(width_);
  const float theta = kPi * (static_cast<float>(y) + t) / static_cast<float>(height_ - 1);
  const float sin_theta = std::sin(theta);
  const Vec3 local(std::sin(phi) * sin_theta, std::cos(theta), -std::cos(phi) * sin_theta);
  pdf_w = pdf_in_cell(rows_.pmf(y) * columns_[y].pmf(x), c, s, t, sin_theta);
  // Cell (x, y) spans texel centres x to x + 1 and sample rows y to y + 1: eval's place there is (s, t).
  if (radiance != nullptr) *radiance = bilinear(x, y, s, t);
  return to_world_.to_world(local);
}

float EnvironmentMap::pdf_at(const CellPoint& p) const {
  return pdf_in_cell(rows_.pmf(p.y) * columns_[p.y].pmf(p.x), corners(p.x, p.y), p.s, p.t, p.sin_theta);
}

Color EnvironmentMap::eval(const Vec3& d, float& pdf_w) const {
  const CellPoint p = cell_of(to_world_.to_local(d));
  pdf_w = pdf_at(p);
  return bilinear(p.x, p.y, p.s, p.t);
}

float EnvironmentMap::pdf(const Vec3& d) const { return pdf_at(cell_of(to_world_.to_local(d))); }

}  // namespace dualight
