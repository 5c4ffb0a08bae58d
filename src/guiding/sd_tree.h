// A spatio-directional guide: the SD-tree of Müller, Gross and Novák [MGN17, sec. 3]. A binary
// tree over the scene's box, split at the middle along x, y, z in turn while a cell holds more
// than `spatial_threshold` records, with a directional quadtree (directional_quadtree.h) in each
// leaf. Unlike MGN17, which refines the previous iteration's tree and fills it while rendering,
// each iteration's tree is built at once from that iteration's stored records: sorted by Morton
// code (then contents), every node's records are one run, so the tree is found by binary search
// with no record moved, and the same records give the same tree bit for bit whatever the thread
// count; each leaf's quadtree is cut to its own records instead of the previous iteration's.
//
// An SD-tree was chosen over Vorba et al.'s parametric mixtures (2014): its density is exact to
// sample and evaluate with no fitting (no EM iterations, no failure modes from too few samples),
// it adapts to any number of lobes, and it is the published method for both of the quantities
// guided here (radiance from camera paths, importance from light paths).
#pragma once
#include <cstdint>
#include <utility>
#include <vector>

#include "core/vec3.h"
#include "guiding/directional_quadtree.h"
#include "guiding/guide_record.h"

namespace dualight {

struct SdTreeSettings {
  // Each leaf's probability of sampling the BSDF instead of the guide: learnt (the value of 0.1,
  // 0.2, ..., 1, at least `bsdf_fraction`, that minimises the second moment of the vertex's
  // one-sample estimate over the leaf's records with the previous iteration's guide,
  // importance-weighted by the density they were sampled with; 1 where fewer than 16 records
  // carried anything), or `bsdf_fraction` everywhere.
  // Below 0.5 the learnt fraction is too bold: the records miss the rare paths that BSDF
  // sampling alone finds, whose weight grows by 1 / fraction at every guided vertex (on the door,
  // unbounded depth, 512 spp: median relative variance 0.035 against 0.17 unguided, mean 11
  // against 0.58).
  bool learn_bsdf_fraction = true;
  float bsdf_fraction = 0.5f;
  uint32_t spatial_threshold = 4000;  // records a leaf may hold before it is split
  float rho = 0.01f;                  // a directional node holding more of its leaf's value is split
  int max_directional_depth = 16;  // cells of 1/65536 of the square's side: below a direction's float round trip
  int max_spatial_depth = 48;
};

class SdTree {
 public:
  struct Node {
    float split = 0.f;      // coordinate of the splitting plane
    uint8_t axis = 0;
    uint32_t child = 0;     // the lower child; the upper is child + 1; 0: a leaf
    uint32_t leaf = 0;      // the leaf's quadtree
  };

  struct Leaf {
    DirectionalQuadtree directions;
    float bsdf_fraction = 1.f;
    // The mean over the leaf's records of product / pdf_sampled: what its vertices reflected of
    // the quantity arriving along their sampled directions (scattered light, without the light
    // next-event estimation found there), the adjoint estimate of adjoint_rr.h.
    float reflected = 0.f;
  };

  SdTree() = default;
  // From records inside [lo, hi] (reordered, sorted first). The BSDF fractions are learnt by how
  // the `previous` tree's guide would have done on these records: a guide judged on the records it
  // was built from fits their noise, and always looks better than it is. Without a previous tree
  // (the first iteration) nothing can judge a guide, and every leaf samples the BSDF only.
  SdTree(GuideRecords& records, const Vec3& lo, const Vec3& hi, const SdTreeSettings& settings,
         const SdTree* previous = nullptr);

  // The leaf holding p (its distribution empty where no record had value).
  const Leaf& at(const Vec3& p) const;
  size_t spatial_nodes() const { return nodes_.size(); }
  size_t leaves() const { return leaves_.size(); }
  size_t directional_nodes() const;
  size_t records() const { return records_; }
  Vec3 lo() const { return lo_; }
  Vec3 hi() const { return hi_; }
  // For drawing: each leaf's box and quadtree.
  struct LeafBox {
    Vec3 lo, hi;
    uint32_t leaf;
  };
  std::vector<LeafBox> leaf_boxes() const;
  const Leaf& leaf(uint32_t i) const { return leaves_[i]; }
  // The leaves' BSDF fractions: their mean weighted by records, smallest and largest.
  void bsdf_fractions(double& mean, float& min, float& max) const;

 private:
  void build(uint32_t node, GuideRecord* begin, GuideRecord* end, Vec3 lo, Vec3 hi, int depth,
             const SdTreeSettings& settings, std::vector<std::pair<GuideRecord*, GuideRecord*>>& runs);
  void build_start_grid();
  // Lookups start from a grid of 2^kGridLevels cells per axis (32768 cells), each holding the
  // deepest node of the first 3 kGridLevels levels that contains it: a vertex's leaf is then a
  // few steps away instead of a dozen dependent loads.
  static constexpr int kGridLevels = 5;
  Vec3 lo_, hi_, grid_scale_;
  std::vector<uint32_t> start_;
  size_t records_ = 0;
  std::vector<Node> nodes_;
  std::vector<Leaf> leaves_;
  std::vector<size_t> leaf_records_;
};

}  // namespace dualight
