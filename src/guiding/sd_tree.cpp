#include "guiding/sd_tree.h"

#include <algorithm>
#include <limits>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/bit_interleave.h"

namespace dualight {

namespace {

// Records that carried something a leaf needs before its BSDF fraction is learnt.
constexpr size_t kMinEvidence = 16;

// The BSDF fraction alpha in {0.1, ..., 1}, at least `floor`, minimising the second moment of the one-sample
// estimate with density alpha pdf_bsdf + (1 - alpha) pdf_guide, sum of product^2 / (mixture
// pdf_sampled) over the records (importance sampling by the density they were drawn from), with
// pdf_guide the previous tree's (out of sample). 1 where the leaf's own guide is empty.
// Ties go to the larger fraction.
float learn_bsdf_fraction(const GuideRecord* begin, const GuideRecord* end, const DirectionalQuadtree& d,
                          const SdTree* previous, float floor) {
  if (d.empty() || previous == nullptr) return 1.f;
  constexpr int kSteps = 10;
  double moment[kSteps] = {};
  size_t evidence = 0;
  for (const GuideRecord* r = begin; r != end; ++r) {
    if (!(r->product > 0.f)) continue;
    ++evidence;
    const double pdf_guide = previous->at(r->p).directions.pdf_square(r->dir) * (0.25 / kPi);
    const double c2 = static_cast<double>(r->product) * r->product / r->pdf_sampled;
    for (int j = 0; j < kSteps; ++j) {
      const double alpha = (j + 1) / static_cast<double>(kSteps);
      const double mixture = alpha * r->pdf_bsdf + (1.0 - alpha) * pdf_guide;
      moment[j] += mixture > 0.0 ? c2 / mixture : std::numeric_limits<double>::infinity();
    }
  }
  if (evidence < kMinEvidence) return 1.f;
  int best = kSteps - 1;
  for (int j = kSteps - 2; j >= 0 && (j + 1) / static_cast<float>(kSteps) >= floor - 1e-6f; --j) {
    if (moment[j] < moment[best]) best = j;
  }
  return (best + 1) / static_cast<float>(kSteps);
}

// The cell of p at the finest level as a Morton code: 21 bits of each coordinate over the box,
// interleaved x, y, z from the top, so that every node of the tree (split at the middle, x, y,
// z in turn) holds one run of the records sorted by code.
constexpr int kMortonBits = 21;

Vec3 morton_scale(const Vec3& lo, const Vec3& hi) { return Vec3(static_cast<float>(1u << kMortonBits)) / (hi - lo); }

// The halves of the cell [lo, hi] split at `split` along `axis`: the lower one's hi, the upper one's lo.
void split_cell(const Vec3& lo, const Vec3& hi, int axis, float split, Vec3& lower_hi, Vec3& upper_lo) {
  lower_hi = hi;
  upper_lo = lo;
  (axis == 0 ? lower_hi.x : axis == 1 ? lower_hi.y : lower_hi.z) = split;
  (axis == 0 ? upper_lo.x : axis == 1 ? upper_lo.y : upper_lo.z) = split;
}

uint64_t spatial_code(const Vec3& p, const Vec3& lo, const Vec3& scale) {
  uint32_t q[3];
  for (int a = 0; a < 3; ++a) {
    const float x = (p[a] - lo[a]) * scale[a];
    q[a] = static_cast<uint32_t>(std::min(static_cast<float>((1u << kMortonBits) - 1), std::max(0.f, x)));
  }
  return (spread_bits_3(q[0]) << 2) | (spread_bits_3(q[1]) << 1) | spread_bits_3(q[2]);
}

}  // namespace

SdTree::SdTree(GuideRecords& records, const Vec3& lo, const Vec3& hi, const SdTreeSettings& settings,
               const SdTree* previous)
    : lo_(lo), hi_(hi), grid_scale_(Vec3(static_cast<float>(1 << kGridLevels)) / (hi - lo)), records_(records.size()) {
  const Vec3 scale = morton_scale(lo, hi);
  const auto code = [&](const GuideRecord& r) { return spatial_code(r.p, lo, scale); };
  sort_records_by(records.data(), records.data() + records.size(), code);
  nodes_.emplace_back();
  std::vector<std::pair<GuideRecord*, GuideRecord*>> runs;  // each leaf's records
  build(0, records.data(), records.data() + records.size(), lo, hi, 0, settings, runs);
  build_start_grid();
  leaves_.resize(runs.size());
  leaf_records_.resize(runs.size());
  // The leaves' quadtrees, each from its own run sorted by direction: independent of each other.
  tbb::parallel_for(size_t(0), runs.size(), [&](size_t i) {
    auto [begin, end] = runs[i];
    sort_by_square_code(begin, end);
    Leaf& leaf = leaves_[i];
    leaf.directions = DirectionalQuadtree(begin, end, settings.rho, settings.max_directional_depth);
    leaf.bsdf_fraction = settings.learn_bsdf_fraction
                             ? learn_bsdf_fraction(begin, end, leaf.directions, previous, settings.bsdf_fraction)
                             : settings.bsdf_fraction;
    double reflected = 0.0;
    for (const GuideRecord* r = begin; r != end; ++r) reflected += r->product / r->pdf_sampled;
    leaf.reflected = end > begin ? static_cast<float>(reflected / static_cast<double>(end - begin)) : 0.f;
    leaf_records_[i] = static_cast<size_t>(end - begin);
  });
}

// Node `node`, the cell [lo, hi] at `depth` holding the run [begin, end) of records sorted by
// spatial code: a leaf (its run kept for its quadtree) or split at the middle of axis depth % 3.
void SdTree::build(uint32_t node, GuideRecord* begin, GuideRecord* end, Vec3 lo, Vec3 hi, int depth,
                   const SdTreeSettings& settings, std::vector<std::pair<GuideRecord*, GuideRecord*>>& runs) {
  const int axis = depth % 3;
  const bool split = static_cast<size_t>(end - begin) > settings.spatial_threshold &&
                     depth < std::min(settings.max_spatial_depth, 3 * kMortonBits);
  if (!split) {
    nodes_[node].leaf = static_cast<uint32_t>(runs.size());
    runs.emplace_back(begin, end);
    return;
  }
  const float mid = 0.5f * (lo[axis] + hi[axis]);
  const Vec3 scale = morton_scale(lo_, hi_);
  const int bit = 3 * kMortonBits - 1 - depth;
  GuideRecord* middle = std::partition_point(
      begin, end, [&](const GuideRecord& r) { return ((spatial_code(r.p, lo_, scale) >> bit) & 1u) == 0; });
  const uint32_t child = static_cast<uint32_t>(nodes_.size());
  nodes_[node].axis = static_cast<uint8_t>(axis);
  nodes_[node].split = mid;
  nodes_[node].child = child;
  nodes_.emplace_back();
  nodes_.emplace_back();
  Vec3 lower_hi, upper_lo;
  split_cell(lo, hi, axis, mid, lower_hi, upper_lo);
  build(child, begin, middle, lo, lower_hi, depth + 1, settings, runs);
  build(child + 1, middle, end, upper_lo, hi, depth + 1, settings, runs);
}

// The first 3 kGridLevels levels split the box into the grid's cells exactly (middles along x, y,
// z in turn), so each cell starts its lookup at the deepest of them that holds it whole.
void SdTree::build_start_grid() {
  constexpr int n = 1 << kGridLevels;
  start_.assign(static_cast<size_t>(n) * n * n, 0);
  const Vec3 cell = (hi_ - lo_) / static_cast<float>(n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const Vec3 centre = lo_ + Vec3((i + 0.5f) * cell.x, (j + 0.5f) * cell.y, (k + 0.5f) * cell.z);
        uint32_t node = 0;
        for (int level = 0; level < 3 * kGridLevels && nodes_[node].child != 0; ++level) {
          const Node& nd = nodes_[node];
          node = nd.child + (centre[nd.axis] < nd.split ? 0u : 1u);
        }
        start_[(static_cast<size_t>(i) * n + j) * n + k] = node;
      }
    }
  }
}

const SdTree::Leaf& SdTree::at(const Vec3& p) const {
  constexpr int n = 1 << kGridLevels;
  const auto cell = [&](int a) {
    const float x = (p[a] - lo_[a]) * grid_scale_[a];
    return static_cast<size_t>(std::min(static_cast<float>(n - 1), std::max(0.f, x)));
  };
  uint32_t node = start_[(cell(0) * n + cell(1)) * n + cell(2)];
  while (nodes_[node].child != 0) {
    const Node& n = nodes_[node];
    node = n.child + (p[n.axis] < n.split ? 0u : 1u);
  }
  return leaves_[nodes_[node].leaf];
}

size_t SdTree::directional_nodes() const {
  size_t n = 0;
  for (const Leaf& l : leaves_) n += l.directions.node_count();
  return n;
}

void SdTree::bsdf_fractions(double& mean, float& min, float& max) const {
  double sum = 0.0, weight = 0.0;
  min = 1.f;
  max = 0.f;
  for (size_t i = 0; i < leaves_.size(); ++i) {
    sum += leaves_[i].bsdf_fraction * static_cast<double>(leaf_records_[i]);
    weight += static_cast<double>(leaf_records_[i]);
    min = std::min(min, leaves_[i].bsdf_fraction);
    max = std::max(max, leaves_[i].bsdf_fraction);
  }
  mean = weight > 0.0 ? sum / weight : 1.0;
}

std::vector<SdTree::LeafBox> SdTree::leaf_boxes() const {
  std::vector<LeafBox> boxes;
  struct Item {
    uint32_t node;
    Vec3 lo, hi;
  };
  std::vector<Item> stack{{0, lo_, hi_}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    const Node& n = nodes_[it.node];
    if (n.child == 0) {
      boxes.push_back({it.lo, it.hi, n.leaf});
      continue;
    }
    Vec3 lower_hi, upper_lo;
    split_cell(it.lo, it.hi, n.axis, n.split, lower_hi, upper_lo);
    stack.push_back({n.child + 1, upper_lo, it.hi});
    stack.push_back({n.child, it.lo, lower_hi});
  }
  return boxes;
}

}  // namespace dualight
