// Southwell iteration = progressive refinement: repeatedly shoot the patch with the most unshot
// quantity [Cohen, Chen, Wallace and Greenberg 1988; Gortler, Cohen and Slusallek 1994]. The
// unshot quantity is the residual r = b - M x, kept exactly. Primal side: unshot power A_i |r_i|,
// shot along column i of F (needs F^T). Dual side: unshot importance |r_i|, shot along row i of F.
#pragma once
#include <vector>

#include "radiosity/linear_system.h"

namespace dualight {

class SouthwellSolver {
 public:
  // shots_per_step = 0 means one shot per patch (a step costs about one gathering sweep).
  SouthwellSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side, std::vector<double> rhs,
                  uint32_t shots_per_step = 0);
  SolverStep step();
  const std::vector<double>& solution() const { return x_; }
  const std::vector<double>& unshot() const { return r_; }  // the residual, n x 3
  // Cohen's ambient term per channel: the unshot quantity spread by an average reflectance,
  // so x_i + rho_i * ambient is a better picture of the converged solution early on.
  std::vector<double> ambient() const;
  double residual() const;
  uint64_t iteration() const { return iteration_; }
  uint64_t shots() const { return shots_; }

 private:
  double priority(uint32_t i) const;

  std::shared_ptr<const RadiositySystem> system_;
  SystemSide side_;
  std::vector<double> b_, x_, r_;
  uint32_t shots_per_step_;
  uint64_t iteration_ = 0, shots_ = 0;
  double b_scale_ = 0.0;
};

}  // namespace dualight
