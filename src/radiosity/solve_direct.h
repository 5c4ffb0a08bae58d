// Direct solution by dense LU (partial pivoting, blocked: dense_lu.h), one factorisation per
// channel serving both M B = E and M^T I = R, so the duality <R, B> = <I, E> holds to rounding.
// Dense: use it for up to a few thousand patches and as the reference the iterative solvers are
// checked against.
#pragma once
#include <vector>

#include "core/render_control.h"
#include "radiosity/linear_system.h"

namespace dualight {

inline constexpr size_t kMaxDirectPatches = 12000;  // 1.1 GiB per dense double matrix

class DirectSolver {
 public:
  // `control` (optional) counts the factorised panels and can cancel: then cancelled() is true
  // and the solver must not be used.
  explicit DirectSolver(std::shared_ptr<const RadiositySystem> system, int threads = 0,
                        RenderControl* control = nullptr);
  ~DirectSolver();
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  std::vector<double> solve(SystemSide side, const std::vector<double>& rhs) const;
  double factor_seconds() const { return factor_seconds_; }
  bool cancelled() const { return cancelled_; }

 private:
  struct Factors;
  std::shared_ptr<const RadiositySystem> system_;
  std::unique_ptr<Factors> factors_;
  double factor_seconds_ = 0.0;
  bool cancelled_ = false;
};

}  // namespace dualight
