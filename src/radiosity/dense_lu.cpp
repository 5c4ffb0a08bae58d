#include "radiosity/dense_lu.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace dualight {

namespace {

constexpr Eigen::Index kPanel = 128;        // columns factorised together (the block size)
constexpr Eigen::Index kUpdateChunk = 512;  // trailing columns updated between cancel checks

}  // namespace

uint64_t DenseLu::panels(Eigen::Index n) { return static_cast<uint64_t>((n + kPanel - 1) / kPanel); }

bool DenseLu::compute(Eigen::MatrixXd a, RenderControl* control) {
  if (a.rows() != a.cols()) throw std::invalid_argument("DenseLu: the matrix must be square");
  lu_ = std::move(a);
  const Eigen::Index n = lu_.rows();
  pivot_.assign(static_cast<size_t>(n), 0);
  for (Eigen::Index k0 = 0; k0 < n; k0 += kPanel) {
    if (control != nullptr && control->cancelled()) return false;
    const Eigen::Index width = std::min(kPanel, n - k0);
    factor_panel(k0, width);
    if (!update_trailing(k0, width, control)) return false;
    if (control != nullptr) control->done.fetch_add(1, std::memory_order_relaxed);
  }
  return true;
}

// Unblocked LU with partial pivoting of columns [k0, k0 + width), all rows from k0 down; each
// row swap is applied to the whole row, left and right of the panel.
void DenseLu::factor_panel(Eigen::Index k0, Eigen::Index width) {
  const Eigen::Index n = lu_.rows();
  for (Eigen::Index j = k0; j < k0 + width; ++j) {
    Eigen::Index p = 0;
    lu_.col(j).tail(n - j).cwiseAbs().maxCoeff(&p);
    p += j;
    pivot_[static_cast<size_t>(j)] = p;
    if (p != j) lu_.row(j).swap(lu_.row(p));
    const double d = lu_(j, j);
    if (d == 0.0) continue;  // singular column: nothing to eliminate (solves give Inf or NaN)
    const Eigen::Index below = n - j - 1, right = k0 + width - j - 1;
    lu_.col(j).tail(below) /= d;
    lu_.block(j + 1, j + 1, below, right).noalias() -=
        lu_.col(j).tail(below) * lu_.row(j).segment(j + 1, right);
  }
}

// U12 = L11^-1 A12, then A22 -= L21 U12 a chunk of columns at a time; false if cancelled.
bool DenseLu::update_trailing(Eigen::Index k0, Eigen::Index width, const RenderControl* control) {
  const Eigen::Index n = lu_.rows(), k1 = k0 + width, rest = n - k1;
  if (rest == 0) return true;
  lu_.block(k0, k0, width, width).triangularView<Eigen::UnitLower>().solveInPlace(lu_.block(k0, k1, width, rest));
  for (Eigen::Index c0 = k1; c0 < n; c0 += kUpdateChunk) {
    if (control != nullptr && control->cancelled()) return false;
    const Eigen::Index cols = std::min(kUpdateChunk, n - c0);
    lu_.block(k1, c0, rest, cols).noalias() -= lu_.block(k1, k0, rest, width) * lu_.block(k0, c0, width, cols);
  }
  return true;
}

Eigen::VectorXd DenseLu::solve(Eigen::VectorXd b) const {
  for (size_t k = 0; k < pivot_.size(); ++k) std::swap(b(static_cast<Eigen::Index>(k)), b(pivot_[k]));
  lu_.triangularView<Eigen::UnitLower>().solveInPlace(b);
  lu_.triangularView<Eigen::Upper>().solveInPlace(b);
  return b;
}

// A^T = U^T L^T P: solve with U^T, then L^T, then undo the swaps in reverse order.
Eigen::VectorXd DenseLu::solve_transposed(Eigen::VectorXd b) const {
  lu_.transpose().triangularView<Eigen::Lower>().solveInPlace(b);
  lu_.transpose().triangularView<Eigen::UnitUpper>().solveInPlace(b);
  for (size_t k = pivot_.size(); k-- > 0;) std::swap(b(static_cast<Eigen::Index>(k)), b(pivot_[k]));
  return b;
}

}  // namespace dualight
