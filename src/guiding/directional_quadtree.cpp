#include "guiding/directional_quadtree.h"

#include <algorithm>
#include <cmath>

#include "core/bit_interleave.h"

namespace dualight {

namespace {

// atan2(y, x) in (-pi, pi] to within 2e-7 (absolute): atan on [0, 1] by a minimax polynomial in
// t^2 (the coefficients of SLEEF's atanf), the octant by symmetry. About 4x faster than libm's,
// and every direction a guide looks up goes through it.
float fast_atan2(float y, float x) {
  const float ax = std::abs(x), ay = std::abs(y);
  const float big = std::max(ax, ay), small = std::min(ax, ay);
  if (!(big > 0.f)) return 0.f;
  const float t = small / big, t2 = t * t;
  float p = 0.00282363896258175373077393f;
  p = p * t2 - 0.0159569028764963150024414f;
  p = p * t2 + 0.0425049886107444763183594f;
  p = p * t2 - 0.0748900920152664184570312f;
  p = p * t2 + 0.106347933411598205566406f;
  p = p * t2 - 0.142027363181114196777344f;
  p = p * t2 + 0.199926957488059997558594f;
  p = p * t2 - 0.333331018686294555664062f;
  float a = t + t * t2 * p;
  if (ay > ax) a = 0.5f * kPi - a;
  if (x < 0.f) a = kPi - a;
  return y < 0.f ? -a : a;
}

}  // namespace

Point2 direction_to_square(const Vec3& w) {
  const float u = std::clamp(0.5f * (w.z + 1.f), 0.f, 1.f);
  float phi = fast_atan2(w.y, w.x) * (0.5f * kInvPi);
  if (phi < 0.f) phi += 1.f;
  return {std::min(u, std::nextafter(1.f, 0.f)), std::clamp(phi, 0.f, std::nextafter(1.f, 0.f))};
}

Vec3 square_to_direction(Point2 p) {
  const float cos_theta = 2.f * p.u - 1.f;
  const float sin_theta = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  const float phi = 2.f * kPi * p.v;
  return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
}

uint32_t square_code(Point2 p) {
  const auto bits = [](float x) {
    return static_cast<uint32_t>(std::min(65535.f, std::max(0.f, x * 65536.f)));
  };
  const uint32_t u = bits(p.u), v = bits(p.v);
  static_assert(kMaxDirectionalDepth == 16, "16 bits of each coordinate");
  return (spread_bits_2(u) << 1) | spread_bits_2(v);
}

namespace {

// A quadrant is split only where enough records landed to tell its halves apart: one bright
// record alone would otherwise be followed down to max_depth, into a cell far smaller than the
// noise of its estimate (and than the float precision of a direction's round trip).
constexpr std::ptrdiff_t kMinRecordsToSplit = 16;

// The quadrant of the node at `origin` of side `size` that holds p: bit 0 the u half, bit 1 the v half.
int quadrant(Point2 p, Point2 origin, float size) {
  const float half = 0.5f * size;
  return (p.u >= origin.u + half ? 1 : 0) | (p.v >= origin.v + half ? 2 : 0);
}

Point2 quadrant_origin(Point2 origin, float size, int q) {
  const float half = 0.5f * size;
  return {origin.u + ((q & 1) ? half : 0.f), origin.v + ((q & 2) ? half : 0.f)};
}

}  // namespace

DirectionalQuadtree::DirectionalQuadtree(const GuideRecord* begin, const GuideRecord* end, float rho, int max_depth)
    : max_depth_(std::min(max_depth, kMaxDirectionalDepth)) {
  double total = 0.0;
  for (const GuideRecord* r = begin; r != end; ++r) total += r->value;
  total_ = static_cast<float>(total);
  if (empty()) return;
  rho_value_ = rho * total_;
  build(begin, end, 1);
}

// The node of the records [begin, end) (one run of a quadtree cell at `depth`, the root's 1);
// returns its index. Its quadrants are the runs of the next two code bits.
uint32_t DirectionalQuadtree::build(const GuideRecord* begin, const GuideRecord* end, int depth) {
  const uint32_t index = static_cast<uint32_t>(nodes_.size());
  nodes_.emplace_back();
  const int shift = 2 * (kMaxDirectionalDepth - depth);
  const auto digit = [shift](const GuideRecord& r) { return (square_code(r.dir) >> shift) & 3u; };
  const GuideRecord* run[5] = {begin, nullptr, nullptr, nullptr, end};
  for (uint32_t d = 1; d < 4; ++d) {
    run[d] = std::partition_point(run[d - 1], end, [&](const GuideRecord& r) { return digit(r) < d; });
  }
  // Digit (u bit, v bit) is quadrant u | v << 1.
  constexpr int kQuadrant[4] = {0, 2, 1, 3};
  double sum = 0.0;
  for (int d = 0; d < 4; ++d) {
    double s = 0.0;
    for (const GuideRecord* r = run[d]; r != run[d + 1]; ++r) s += r->value;
    nodes_[index].value[kQuadrant[d]] = static_cast<float>(s);
    sum += s;
  }
  for (int q = 0; q < 4; ++q) {
    nodes_[index].density[q] = sum > 0.0 ? static_cast<float>(4.0 * nodes_[index].value[q] / sum) : 0.f;
  }
  for (int d = 0; d < 4; ++d) {
    const int q = kQuadrant[d];
    if (depth < max_depth_ && nodes_[index].value[q] > rho_value_ && run[d + 1] - run[d] >= kMinRecordsToSplit) {
      const uint32_t child = build(run[d], run[d + 1], depth + 1);
      nodes_[index].child[q] = child;
    }
  }
  return index;
}

float DirectionalQuadtree::pdf_w(const Vec3& w) const { return empty() ? 0.f : pdf_square(direction_to_square(w)) * (0.25f * kInvPi); }

float DirectionalQuadtree::pdf_square(Point2 p) const {
  if (empty()) return 0.f;
  Point2 origin{0.f, 0.f};
  float size = 1.f;
  float density = 1.f;  // on the unit square
  uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    const int q = quadrant(p, origin, size);
    if (!(n.density[q] > 0.f)) return 0.f;
    density *= n.density[q];
    if (n.child[q] == 0) break;
    origin = quadrant_origin(origin, size, q);
    size *= 0.5f;
    node = n.child[q];
  }
  return density;
}

// Picks the u half by the marginal, then the v half given it, rescaling each coordinate so the
// leaf is reached with one 2D sample (in double: twenty levels halve a float's precision away).
Vec3 DirectionalQuadtree::sample(Point2 u_in, float* pdf_w) const {
  double u = u_in.u, v = u_in.v;
  double origin_u = 0.0, origin_v = 0.0, size = 1.0;
  float density = 1.f;  // on the unit square
  uint32_t node = 0;
  for (;;) {
    const Node& n = nodes_[node];
    const double low_u = double(n.value[0]) + n.value[2], high_u = double(n.value[1]) + n.value[3];
    const double p_low_u = low_u / (low_u + high_u);
    int q = 0;
    if (u < p_low_u) {
      u /= p_low_u;
    } else {
      u = (u - p_low_u) / (1.0 - p_low_u);
      q |= 1;
    }
    const double low_v = n.value[q], high_v = n.value[q | 2];
    const double p_low_v = low_v / (low_v + high_v);
    if (v < p_low_v) {
      v /= p_low_v;
    } else {
      v = (v - p_low_v) / (1.0 - p_low_v);
      q |= 2;
    }
    size *= 0.5;
    origin_u += (q & 1) ? size : 0.0;
    origin_v += (q & 2) ? size : 0.0;
    density *= n.density[q];
    if (n.child[q] == 0) break;
    node = n.child[q];
  }
  const auto inside = [](double x) { return std::clamp(x, 0.0, std::nextafter(1.0, 0.0)); };
  const Point2 p{static_cast<float>(origin_u + size * inside(u)), static_cast<float>(origin_v + size * inside(v))};
  if (pdf_w != nullptr) *pdf_w = density * (0.25f * kInvPi);
  return square_to_direction({std::min(p.u, std::nextafter(1.f, 0.f)), std::min(p.v, std::nextafter(1.f, 0.f))});
}

}  // namespace dualight
