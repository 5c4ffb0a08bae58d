// Hierarchical radiosity with links between elements of per-triangle subdivision trees
// [Hanrahan, Salzman and Aupperle 1991], refined by the BF oracle or by the importance-driven
// oracle of [Smits, Arvo and Salesin 1992], which solves radiosity and importance together and
// refines a link only where its energy transfer matters for the view.
//
// A gather link (i <- j) carries F_ij, the form factor from receiver i to source j (exact contour
// integral at 3 points of i times a visibility fraction from stratified rays). Radiosity flows
// along it, B_i += rho_i F_ij B_j; importance density flows back, W_j += rho_i F_ji W_i with
// F_ji = A_i F_ij / A_j, which makes the importance system the exact adjoint (area inner
// product) of the radiosity system on any hierarchy: <R, B>_A = <W, E>_A to rounding.
// Push-pull moves gathered quantities down to leaves and averages them up [HSA91 sec. 4].
// A link whose source has children carries their radiosity weighted by what the receiver sees
// of each (source_view), not the source's average; importance flows back to those children.
// Above the per-link oracle, an a-posteriori check per element pushes links down where what the
// element gathers varies across it by more than the oracle's threshold (flag_links).
// Emitted radiosity is each element's own: pi times its emitter's mean radiance over it (a
// radiance texture's mean over the element), plus the first shot of the emitters without a
// surface, rho times their mean irradiance over it [Cohen and Wallace 1993, sec. 2.3]
// (radiosity/direct_irradiance.h), taken again for every element refinement creates.
#pragma once
#include <array>
#include <atomic>
#include <cstdint>
#include <vector>

#include "core/render_control.h"
#include "geometry/scene.h"
#include "radiosity/direct_irradiance.h"

namespace dualight {

enum class RefinementOracle { BF, Importance };

struct HierarchicalOptions {
  RefinementOracle oracle = RefinementOracle::Importance;
  double epsilon = 1e-3;    // relative: of the brightest emission (BF) or of the measurement (importance)
  double min_area = 0.0;    // elements are not split below this area (0: 1e-4 of the largest input)
  int shadow_rays = 1;      // per receiver quadrature point (7 per link) and per estimate (2)
  int sweeps = 30;          // Gauss-Seidel sweeps per step at most
  double tolerance = 1e-6;  // relative change per sweep that ends a step's sweeps
  uint64_t seed = 0;
  int threads = 0;
  uint64_t max_links = 20000000;  // refinement stops before exceeding this (64 bytes each: about 1.3 GiB)
  bool skip_unneeded = true;      // no visibility rays in a convex enclosure (scene_features.h)
  int first_shot_points = 4;      // per axis: the first shot's points per element (FirstShot)
  int env_strata = 8;             // per axis: the environment's direction pairs per point
};

struct HierarchicalStep {
  uint64_t iteration = 0;
  uint64_t elements = 0, leaves = 0, links = 0, links_refined = 0, rays = 0;
  uint64_t rays_skipped = 0;  // visibility rays not needed (convex enclosure)
  uint64_t memory_bytes = 0;
  double residual = 0.0;  // largest relative change of B or W in the last sweep
  double seconds = 0.0;
  bool converged = false;  // nothing was refined
  bool link_limit = false;  // refinement was cut short by max_links
};

// Camera samples for the receiver: root triangle, barycentrics, weight (front-facing hits only).
struct ReceiverSamples {
  std::vector<uint32_t> prim;
  std::vector<float> b1, b2;
  double weight = 0.0;  // each sample's share of the measurement (1 / (count * pi))
};

class HierarchicalSolver {
 public:
  // `scene` provides the input triangles (the roots) and their materials. `albedo`, empty or one
  // colour in [0, 1] per input triangle, replaces the materials' albedo (a textured material's
  // mean over each triangle: every element of a root keeps its root's). The initial linking
  // is O(triangles^2): `control` (optional) counts its rows and can cancel it, which leaves the
  // solver unusable (cancelled() true): the caller discards it. The roots' first shot comes
  // before it, cancellable and counted too (total: 2 x triangles when there is one).
  HierarchicalSolver(const Scene& scene, ReceiverSamples receiver, HierarchicalOptions options,
                     RenderControl* control = nullptr, const std::vector<Color>& albedo = {});

  // One refine-and-solve iteration: refine every link the oracle flags (none on the first call),
  // then Gauss-Seidel sweeps with push-pull for radiosity and for importance.
  HierarchicalStep step(RenderControl* control = nullptr);

  struct Leaf {
    Vec3 v[3];
    uint32_t root;
    double area;
    double B[3], W[3], E[3], R;  // W, R: importance and receiver per unit area
    double link_density;         // links gathered by this leaf or its ancestors, per unit area
  };
  std::vector<Leaf> leaves() const;
  struct LinkView {
    uint32_t receiver_root, source_root;
    Vec3 receiver_centroid, source_centroid;
    float F;
  };
  std::vector<LinkView> links() const;
  // <R, B>_A and <W, E>_A per channel.
  void measurements(double primal[3], double dual[3]) const;
  uint64_t total_rays() const { return rays_; }
  uint64_t total_rays_skipped() const { return rays_skipped_; }
  // For tests: over all leaves and all other roots, the largest |covered area / root area - 1|,
  // where "covered" sums the areas of that root's elements linked (before visibility culling) to
  // the leaf or its ancestors. 0 means every source is seen exactly once from every leaf.
  double link_coverage_error(bool only_facing_roots) const;

 private:
  struct Element {
    Vec3 v[3];
    Vec3 normal;
    double area;
    uint32_t root;
    int32_t first_child = -1;  // four children, contiguous
    int32_t parent = -1;
    double rho[3] = {0, 0, 0}, E[3] = {0, 0, 0};
    double B[3] = {0, 0, 0}, Bg[3] = {0, 0, 0};  // radiosity, gathered at this level
    double W[3] = {0, 0, 0}, Wg[3] = {0, 0, 0};  // importance density, gathered at this level
    double R = 0.0;                               // receiver density (leaves)
  };
  // How a link's receiver sees its source's four children: each child's share of the link's form
  // factor. share[0] = kNotSeen until the source has children, kNone if it sees none of them.
  static constexpr float kNotSeen = -2.f, kNone = -1.f;
  struct SourceView {
    float share[4] = {kNotSeen, 0.f, 0.f, 0.f};
  };
  // Two independent visibility estimates: one for the transport, one for the refinement
  // decisions. With a single one, links whose rays happened to be blocked would never be
  // refined and keep their underestimate while lucky ones get re-sampled: a bias towards too
  // little light that grows with refinement.
  struct Link {
    uint32_t receiver, source;
    float F;         // receiver -> source form factor with the transport visibility estimate
    float F_oracle;  // the same with an independent visibility estimate, for the oracle only
    float F_unoccluded;
    float F_point[7];  // point-to-source form factors at the receiver's 7 rule points, each times
                       // the oracle's visible fraction from that point
    SourceView view;   // how the receiver sees the source's children (computed once they exist)
  };

  // A link the oracle flags, and which of its ends to split.
  struct Refinement {
    uint32_t link;
    bool split_receiver;
  };

  Link make_link(uint32_t receiver, uint32_t source, uint64_t& rays, uint64_t& rays_skipped) const;
  bool facing(const Element& a, const Element& b) const;
  void subdivide(uint32_t e);
  // Emitted radiosity of elements [first, end) (the roots, or those a refinement created);
  // `done` (optional) counts them.
  void set_emission(size_t first, const RenderControl* control, std::atomic<uint64_t>* done = nullptr);
  Color mean_emitted_radiance(const Element& e) const;
  // The three parts of a step: the oracle's flags, the refinement, the solve of both systems.
  std::vector<Refinement> flag_links(const RenderControl* control) const;
  std::vector<char> links_to_push_down(double measurement, const RenderControl* control) const;
  void gathered_deviations(uint32_t receiver, const uint32_t* links, size_t count,
                           std::vector<std::array<double, 7>>& deviation) const;
  static std::vector<size_t> strays_to_push_down(const std::vector<std::array<double, 7>>& deviation,
                                                 double threshold);
  void refine_links(std::vector<Refinement> to_refine, HierarchicalStep& st, const RenderControl* control);
  SourceView source_view(const Link& link, uint64_t& rays) const;
  void update_source_views(const RenderControl* control);
  void seen_radiosity(const Link& link, double seen[3]) const;
  void link_roots(RenderControl* control);
  double solve_links(RenderControl* control);
  void push_pull_radiosity(uint32_t e, const double down[3]);
  void push_pull_importance(uint32_t e, const double down[3]);
  double leaf_change(const std::vector<double>& before) const;
  void assign_receiver();
  uint32_t leaf_at(uint32_t root, float b1, float b2) const;

  const Scene& scene_;
  ReceiverSamples receiver_;
  HierarchicalOptions options_;
  FirstShot first_shot_;
  bool emission_varies_ = false;  // textured emitters or a first shot: elements differ from their parents
  std::vector<Element> elements_;
  std::vector<Link> links_;
  uint32_t roots_;
  uint64_t iteration_ = 0, rays_ = 0, rays_skipped_ = 0;
  double emitted_radiosity_max_ = 0.0;  // luminance of the brightest emitter's radiosity
};

}  // namespace dualight
