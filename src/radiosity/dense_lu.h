// Blocked right-looking LU factorisation with partial pivoting, P A = L U in place [Golub and
// Van Loan, Matrix Computations, 4th ed., sec. 3.4.7 (block LU with pivoting); the order of
// LAPACK's dgetrf]: a panel of columns is factorised with row swaps, the block row to its right
// solved with the panel's unit lower triangle, and the trailing matrix updated by one matrix
// product per chunk of columns. The cancel flag is checked between chunks, so a factorisation
// of thousands of unknowns (seconds) stops within a few hundredths of a second.
//
// Solves A x = b and A^T x = b with the same factors (the radiosity and importance systems).
#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/render_control.h"

namespace dualight {

class DenseLu {
 public:
  // Factorises the square matrix `a`; false if `control` cancelled it (then nothing is usable).
  // `control->done` counts the panels factorised (panels(n) in all).
  bool compute(Eigen::MatrixXd a, RenderControl* control = nullptr);
  static uint64_t panels(Eigen::Index n);

  Eigen::VectorXd solve(Eigen::VectorXd b) const;             // A x = b
  Eigen::VectorXd solve_transposed(Eigen::VectorXd b) const;  // A^T x = b

 private:
  void factor_panel(Eigen::Index k0, Eigen::Index width);
  bool update_trailing(Eigen::Index k0, Eigen::Index width, const RenderControl* control);

  Eigen::MatrixXd lu_;                // L below the diagonal (unit diagonal implied), U on and above
  std::vector<Eigen::Index> pivot_;  // step k swapped rows k and pivot_[k] (LAPACK's ipiv)
};

}  // namespace dualight
