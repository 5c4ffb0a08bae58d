// A piecewise-constant distribution of directions on the sphere, as in Müller, Gross and Novák's
// practical path guiding [MGN17, sec. 3.2]: a quadtree over the unit square, mapped to the sphere
// by the cylindrical map (cos theta = 2u - 1, phi = 2 pi v), which preserves area, so the density
// in solid angle is the square's density over 4 pi. Built from weighted records: a node is split
// while it holds more than `rho` of the total value (MGN17's subdivision criterion, rho = 0.01 in
// the paper) and enough records to resolve its quadrants (16), down to max_depth. Sampling descends by the children's values and is uniform within
// a leaf, so pdf() is the exact density of sample().
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/sampling.h"
#include "core/vec3.h"
#include "guiding/guide_record.h"

namespace dualight {

// The cylindrical map between unit directions and [0, 1)^2.
Point2 direction_to_square(const Vec3& w);
Vec3 square_to_direction(Point2 p);

// The finest quadtree cell holding p on the square as a Morton code: the bits of u and v at
// 1/65536 (kMaxDirectionalDepth levels), interleaved u first from the top, so that the records
// of every quadtree node sort into one run with its quadrants' runs in order (u low, v low),
// (low, high), (high, low), (high, high).
inline constexpr int kMaxDirectionalDepth = 16;
uint32_t square_code(Point2 p);

// A record (guide_record.h) of quantity L (colour, seen through throughput beta) arriving along
// unit w at p, sampled with density pdf_sampled, at a vertex whose f |cos| (colour) in w is fcos
// and whose BSDF samples w with density pdf_bsdf. False where it holds nothing finite.
inline bool make_record(const Vec3& p, const Vec3& w, const Color& L, const Color& beta, const Color& fcos,
                        float pdf_bsdf, float pdf_sampled, GuideRecord& r) {
  const float Li = incident_scalar(L, beta);
  r = {p, direction_to_square(w), Li / pdf_sampled, average(fcos) * Li, pdf_bsdf, pdf_sampled};
  return pdf_sampled > 0.f && std::isfinite(r.value) && r.value >= 0.f && std::isfinite(r.product) &&
         r.product >= 0.f && std::isfinite(r.pdf_bsdf);
}

// Sorts records as DirectionalQuadtree's constructor needs them, from a fixed order (records of
// equal codes keep theirs).
inline void sort_by_square_code(GuideRecord* begin, GuideRecord* end) {
  stable_sort_records_by(begin, end, [](const GuideRecord& r) { return square_code(r.dir); });
}

class DirectionalQuadtree {
 public:
  struct Node {
    std::array<float, 4> value{};     // the quadrants' values: (u low, v low), (high, low), (low, high), (high, high)
    std::array<float, 4> density{};   // 4 value / sum: the factor of the density on the square
    std::array<uint32_t, 4> child{};  // the quadrant's node, or 0: a leaf
  };

  DirectionalQuadtree() = default;
  // From records [begin, end) sorted by their square_code (then in any fixed order): each node's
  // records are then a contiguous run, its quadrants' runs follow in code order, and every sum
  // adds the same values in the same order.
  DirectionalQuadtree(const GuideRecord* begin, const GuideRecord* end, float rho, int max_depth);

  // No value anywhere: the distribution is undefined and must not be sampled.
  bool empty() const { return !(total_ > 0.f); }
  float total() const { return total_; }
  size_t node_count() const { return nodes_.size(); }
  const std::vector<Node>& nodes() const { return nodes_; }
  // Density in solid angle of unit direction w (0 where no record landed).
  float pdf_w(const Vec3& w) const;
  // The density on the unit square of a point of it (pdf_w times 4 pi).
  float pdf_square(Point2 p) const;
  // A unit direction with density pdf_w; *pdf_w (when given) is that density, found on the way
  // down (the same factors in the same order as pdf_square).
  Vec3 sample(Point2 u, float* pdf_w = nullptr) const;

 private:
  uint32_t build(const GuideRecord* begin, const GuideRecord* end, int depth);
  float rho_value_ = 0.f;  // rho times the total: a quadrant above it is split
  int max_depth_ = 0;
  float total_ = 0.f;
  std::vector<Node> nodes_;
};

}  // namespace dualight
