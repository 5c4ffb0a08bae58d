// Patch-to-patch form factors F_ij: the fraction of energy leaving patch i (uniformly, Lambertian)
// that arrives at patch j, F_ij = 1/A_i int_Ai int_Aj V cos_i cos_j / (pi r^2) dA_j dA_i
// [Sillion and Puech 1994, ch. 4; Cohen and Wallace 1993, ch. 4].
//
// The inner integral over patch j is done exactly by the point-to-polygon contour formula
// (Lambert), after clipping j to the half-space above i's tangent plane; the outer integral uses
// a symmetric quadrature rule on patch i (1, 3 or 7 points). Visibility is the fraction of
// stratified shadow rays from each quadrature point to j that arrive, so F_ij = sum_k w_k
// F(x_k -> A_j) V_k. Patches are one-sided: only the side of their normal sends and receives.
// Because quadrature points lie inside patch i, the kernel's singularity on a shared edge is
// never sampled; the contour formula integrates it exactly.
#pragma once
#include <cstdint>
#include <stdexcept>
#include <vector>

#include "core/render_control.h"
#include "core/sampling.h"
#include "geometry/scene.h"
#include "radiosity/csr_matrix.h"

namespace dualight {

struct FormFactorOptions {
  int quadrature = 3;      // points on the receiving patch: 1 (centroid), 3 (degree 2), 7 (degree 5)
  int shadow_rays = 4;     // per quadrature point and source patch; 0 = no occlusion test
  uint64_t seed = 0;
  int threads = 0;
  float min_value = 0.f;   // entries below this are dropped (0 keeps every non-zero)
  // Skip work the scene makes pointless: visibility rays in a convex enclosure (scene_features.h:
  // facing patches always see each other there); false traces them all.
  bool skip_unneeded = true;

  // The rules there are (triangle_rule); the other fields' ranges are checked where they are set
  // (bindings/options.h). Throws std::invalid_argument.
  void validate() const {
    if (quadrature != 1 && quadrature != 3 && quadrature != 7) {
      throw std::invalid_argument("quadrature must be 1, 3 or 7 points");
    }
  }
};

// Which rows of F a solve needs (the rest are left empty). Row i serves only B_i = E_i +
// rho_i sum_j F_ij B_j, so a patch that reflects nothing needs none; and for one view, only the
// patches with non-zero importance (I = R + F^T diag(rho) I) matter: those the camera sees and,
// recursively, those seen from an important patch that reflects. Their rows are computed in
// waves, each revealing the next patches through its non-zero entries, so the others' rows are
// never computed and their B and I are exact for the view: B_i on important patches, I_i = 0
// elsewhere.
struct FormFactorRows {
  std::vector<uint8_t> scatters;   // per patch: rho_i > 0
  std::vector<uint8_t> receivers;  // per patch: R_i > 0; empty when every patch is wanted
}; 

struct FormFactorStats {
  uint64_t pairs_tested = 0;   // (i, j) pairs whose kernel was evaluated
  uint64_t pairs_facing = 0;   // pairs with a non-zero unoccluded form factor
  uint64_t rays = 0;
  uint64_t rays_skipped = 0;     // visibility rays not needed (convex enclosure)
  uint64_t rows_computed = 0;    // rows of F computed; the others were not needed
  uint64_t important = 0;        // patches of non-zero importance (view-only rows), else all
  double seconds = 0.0;
  bool interrupted = false;
};

// Symmetric quadrature rules on a triangle: 1 (centroid), 3 (degree 2) or 7 points (degree 5).
struct QuadraturePoint {
  double b0, b1, b2, weight;
};
const std::vector<QuadraturePoint>& triangle_rule(int order);

// Barycentrics (b1, b2) of a uniform sample on a triangle, contracted towards the centroid by
// 1e-4 so that shadow rays never aim within rounding of the triangle's edges (see Scene::visible).
inline Point2 shadow_ray_target(Point2 u) {
  const Point2 b = square_to_uniform_triangle(u);
  constexpr float kContract = 1.f - 1e-4f, kToCentroid = (1.f - kContract) / 3.f;
  return {kContract * b.u + kToCentroid, kContract * b.v + kToCentroid};
}

// Unoccluded form factor from a differential area at x (unit normal n) to a planar polygon,
// whose front side (right-hand rule normal) must face x; 0 when x is behind or in its plane.
double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon);

// The same for a triangle, without allocating (hot in hierarchical refinement).
double point_triangle_form_factor(const Vec3& x, const Vec3& n, const Vec3 triangle[3]);

// Whether some corner of a triangle lies in front of the plane through p with normal n (any
// length) by more than float rounding (1e-6 of the largest coordinate): the facing cull of patch
// pairs, which must treat coincident and overlapping coplanar patches as coplanar.
bool some_corner_in_front(const Vec3& p, const Vec3& n, const Vec3 corners[3]);

// Rows of F for the triangles of `patches` (one patch per triangle): every row, or those `rows`
// selects.
CsrMatrix compute_form_factors(const Scene& patches, const FormFactorOptions& options, RenderControl& control,
                               FormFactorStats& stats, const FormFactorRows* rows = nullptr);

}  // namespace dualight
