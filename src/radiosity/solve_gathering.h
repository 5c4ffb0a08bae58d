// Gathering solvers: Jacobi and Gauss-Seidel sweeps, each patch collecting from all others
// [Cohen and Greenberg 1985; Sillion and Puech 1994, sec. 5.2]. On the dual side they gather
// importance, which is shooting importance's reverse: the same code with F^T.
#pragma once
#include <vector>

#include "radiosity/linear_system.h"

namespace dualight {

class JacobiSolver {
 public:
  JacobiSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side, std::vector<double> rhs,
               int threads = 0);
  SolverStep step();  // one sweep: x <- b + K x
  const std::vector<double>& solution() const { return x_; }
  double residual() const { return residual_; }
  uint64_t iteration() const { return iteration_; }

 private:
  std::shared_ptr<const RadiositySystem> system_;
  SystemSide side_;
  std::vector<double> b_, x_, next_;
  int threads_;
  uint64_t iteration_ = 0;
  double residual_ = 1.0;
};

class GaussSeidelSolver {
 public:
  GaussSeidelSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side, std::vector<double> rhs);
  SolverStep step();  // one in-place sweep in patch order
  const std::vector<double>& solution() const { return x_; }
  double residual() const { return residual_; }
  uint64_t iteration() const { return iteration_; }

 private:
  std::shared_ptr<const RadiositySystem> system_;
  SystemSide side_;
  std::vector<double> b_, x_;
  uint64_t iteration_ = 0;
  double residual_ = 1.0;
};

}  // namespace dualight
