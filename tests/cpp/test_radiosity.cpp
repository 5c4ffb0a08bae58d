// Form-factor kernel, CSR transpose, the blocked dense LU and the solvers on a system small enough
// to solve by hand.
#include <Eigen/LU>
#include <cmath>
#include <memory>

#include "box_scene.h"
#include "check.h"
#include "core/render_control.h"
#include "core/rng.h"
#include "radiosity/dense_lu.h"
#include "radiosity/form_factors.h"
#include "radiosity/hierarchical.h"
#include "radiosity/solve_direct.h"
#include "radiosity/solve_gathering.h"
#include "radiosity/solve_shooting.h"

using namespace dualight;

TEST_CASE("point_to_square_matches_the_closed_form") {
  // A unit square centred 1 above a point facing it: F = 0.2394... (Howell, differential area
  // to a parallel rectangle: 4 quadrants of (1/2pi)(a/sqrt(1+a^2) atan(b/sqrt(1+a^2)) + ...)).
  const double a = 0.5, b = 0.5;
  const double quadrant = (1.0 / (2.0 * M_PI)) * (a / std::sqrt(1 + a * a) * std::atan(b / std::sqrt(1 + a * a)) +
                                                  b / std::sqrt(1 + b * b) * std::atan(a / std::sqrt(1 + b * b)));
  const std::vector<Vec3> square = {{-.5f, -.5f, 1.f}, {-.5f, .5f, 1.f}, {.5f, .5f, 1.f}, {.5f, -.5f, 1.f}};
  CHECK_NEAR(point_polygon_form_factor(Vec3(0, 0, 0), Vec3(0, 0, 1), square), 4 * quadrant, 1e-6);
  // Facing away (reversed order) and below the receiver's plane give 0.
  const std::vector<Vec3> reversed(square.rbegin(), square.rend());
  CHECK(point_polygon_form_factor(Vec3(0, 0, 0), Vec3(0, 0, 1), reversed) == 0.0);
  CHECK(point_polygon_form_factor(Vec3(0, 0, 2), Vec3(0, 0, 1), square) == 0.0);
}

TEST_CASE("polygon_half_below_the_receiver_plane_is_clipped") {
  // A vertical square standing on the receiver's plane through the point: only the part above
  // counts, and tilting the receiver's normal into the plane leaves nothing.
  const std::vector<Vec3> wall = {{-1.f, 1.f, -1.f}, {1.f, 1.f, -1.f}, {1.f, 1.f, 1.f}, {-1.f, 1.f, 1.f}};
  const double up = point_polygon_form_factor(Vec3(0, 0, 0), Vec3(0, 0, 1), wall);
  const double down = point_polygon_form_factor(Vec3(0, 0, 0), Vec3(0, 0, -1), wall);
  const double facing = point_polygon_form_factor(Vec3(0, 0, 0), Vec3(0, 1, 0), wall);
  CHECK((up > 0.0 && down > 0.0));
  CHECK_NEAR(up, down, 1e-9);  // symmetric halves
  CHECK(facing > up + down - 1e-9);  // the whole wall is above the plane facing it
}

TEST_CASE("csr_transpose_round_trips") {
  CsrMatrix m;
  m.n = 3;
  m.indptr = {0, 2, 3, 4};
  m.indices = {1, 2, 0, 1};
  m.values = {0.5f, 0.25f, 0.75f, 1.0f};
  const CsrMatrix t = m.transpose();
  CHECK(t.indptr == (std::vector<uint64_t>{0, 1, 3, 4}));
  CHECK(t.indices == (std::vector<uint32_t>{1, 0, 2, 0}));
  CHECK(t.values == (std::vector<float>{0.75f, 0.5f, 1.0f, 0.25f}));
  const CsrMatrix back = t.transpose();
  CHECK((back.indices == m.indices && back.values == m.values && back.indptr == m.indptr));
}

TEST_CASE("solvers_agree_on_a_two_patch_enclosure") {
  // Two patches seeing only each other: F = [[0, 1], [1, 0]], rho = 0.5, E = (1, 0):
  // B1 = 1 + 0.5 B2, B2 = 0.5 B1  =>  B1 = 4/3, B2 = 2/3. Dual with R = (0, 1): I = (2/3, 4/3).
  CsrMatrix F;
  F.n = 2;
  F.indptr = {0, 1, 2};
  F.indices = {1, 0};
  F.values = {1.f, 1.f};
  auto system = std::make_shared<RadiositySystem>(std::make_shared<FormFactorMatrices>(F),
                                                  std::vector<double>(6, 0.5), std::vector<double>{1.0, 2.0});
  const std::vector<double> E = {1, 1, 1, 0, 0, 0}, R = {0, 0, 0, 1, 1, 1};
  const DirectSolver direct(system);
  const std::vector<double> B = direct.solve(SystemSide::Primal, E), I = direct.solve(SystemSide::Dual, R);
  CHECK_NEAR(B[0], 4.0 / 3.0, 1e-12);
  CHECK_NEAR(B[3], 2.0 / 3.0, 1e-12);
  CHECK_NEAR(I[0], 2.0 / 3.0, 1e-12);
  CHECK_NEAR(I[3], 4.0 / 3.0, 1e-12);
  // <R, B> = <I, E>
  CHECK_NEAR(B[3], I[0] * 1.0, 1e-12);

  JacobiSolver jacobi(system, SystemSide::Primal, E);
  GaussSeidelSolver gs(system, SystemSide::Dual, R);
  SouthwellSolver sw(system, SystemSide::Primal, E, 1);
  for (int k = 0; k < 60; ++k) {
    jacobi.step();
    gs.step();
    sw.step();
  }
  CHECK_NEAR(jacobi.solution()[0], 4.0 / 3.0, 1e-12);
  CHECK_NEAR(gs.solution()[0], 2.0 / 3.0, 1e-12);
  CHECK_NEAR(sw.solution()[3], 2.0 / 3.0, 1e-12);
  CHECK((jacobi.residual() < 1e-12 && gs.residual() < 1e-12 && sw.residual() < 1e-12));
}

TEST_CASE("dense_lu_solves_both_sides_like_eigens_lu_and_stops_when_cancelled") {
  // A random non-symmetric matrix needing row swaps (its diagonal is small), 300 x 300: three
  // panels of 128, the last one narrower.
  constexpr int n = 300;
  Pcg32 rng(11, 0);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) a(i, j) = rng.next_float() - 0.5 + (i == j ? 1e-3 : 0.0);
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b(i) = rng.next_float();
  DenseLu lu;
  RenderControl control;
  REQUIRE(lu.compute(a, &control));
  CHECK(control.done.load() == DenseLu::panels(n));
  const Eigen::PartialPivLU<Eigen::MatrixXd> reference(a);
  CHECK((lu.solve(b) - reference.solve(b)).norm() < 1e-9 * reference.solve(b).norm());
  const Eigen::VectorXd xt = lu.solve_transposed(b);
  CHECK((a.transpose() * xt - b).norm() < 1e-10 * b.norm() * a.norm() * xt.norm());
  // The control: a wrong transposition (solve instead of solve_transposed) fails that check.
  const Eigen::VectorXd wrong = lu.solve(b);
  CHECK((a.transpose() * wrong - b).norm() > 1e-3 * b.norm());
  control.cancel = true;
  CHECK_FALSE(DenseLu().compute(a, &control));
}

namespace {

// Leaves `value` in the stack memory the next call at this depth will use.
[[gnu::noinline]] double fill_stack(double value) {
  volatile double junk[8192];
  for (auto& j : junk) j = value;
  return junk[17];
}

// Links the second BF step refines, the solver built right after the stack held `value`.
[[gnu::noinline]] uint64_t refined_after_stack_held(const Scene& scene, double value) {
  fill_stack(value);
  HierarchicalOptions options;
  options.oracle = RefinementOracle::BF;
  options.epsilon = 1e-2;
  options.threads = 1;
  HierarchicalSolver solver(scene, ReceiverSamples{}, options);
  solver.step();
  return solver.step().links_refined;
}

}  // namespace

TEST_CASE("hierarchical_bf_threshold_reads_only_the_emission_it_set") {
  // The constructor took the brightest emission from channels it had not set yet: with large
  // values left on the stack, BF's threshold was garbage and it refined nothing.
  const Scene scene = closed_box();
  const uint64_t clean = refined_after_stack_held(scene, 0.0);
  CHECK(clean > 0);
  CHECK(refined_after_stack_held(scene, 1e300) == clean);
}
