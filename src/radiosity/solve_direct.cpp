#include "radiosity/solve_direct.h"

#include <Eigen/Core>
#include <string>

#include "core/parallel.h"
#include "core/stopwatch.h"
#include "radiosity/dense_lu.h"

namespace dualight {

struct DirectSolver::Factors {
  DenseLu lu[3];
};

DirectSolver::DirectSolver(std::shared_ptr<const RadiositySystem> system, int threads, RenderControl* control)
    : system_(std::move(system)), factors_(std::make_unique<Factors>()) {
  const size_t n = system_->size();
  if (n > kMaxDirectPatches) {
    throw std::invalid_argument("the direct solver holds a dense n x n matrix: " + std::to_string(n) +
                                " patches is more than " + std::to_string(kMaxDirectPatches) +
                                "; use an iterative method");
  }
  if (threads > 0) Eigen::setNbThreads(worker_count(threads));
  const Stopwatch t0;
  const CsrMatrix& F = system_->matrices->F;
  if (control != nullptr) control->total.store(3 * DenseLu::panels(static_cast<Eigen::Index>(n)));
  for (int c = 0; c < 3 && !cancelled_; ++c) {
    Eigen::MatrixXd M = Eigen::MatrixXd::Identity(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
    for (uint32_t i = 0; i < n; ++i) {
      const double rho = system_->rho[3 * i + c];
      for (uint64_t k = F.indptr[i]; k < F.indptr[i + 1]; ++k) M(i, F.indices[k]) -= rho * F.values[k];
    }
    cancelled_ = !factors_->lu[c].compute(std::move(M), control);
  }
  factor_seconds_ = t0();
}

DirectSolver::~DirectSolver() = default;

std::vector<double> DirectSolver::solve(SystemSide side, const std::vector<double>& rhs) const {
  const auto n = static_cast<Eigen::Index>(system_->size());
  if (rhs.size() != 3 * system_->size()) throw std::invalid_argument("right-hand side must be n x 3");
  if (cancelled_) throw std::logic_error("the direct solver's factorisation was cancelled");
  std::vector<double> out(rhs.size());
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) b(i) = rhs[3 * i + c];
    const Eigen::VectorXd x =
        side == SystemSide::Primal ? factors_->lu[c].solve(std::move(b)) : factors_->lu[c].solve_transposed(std::move(b));
    for (Eigen::Index i = 0; i < n; ++i) out[3 * i + c] = x(i);
  }
  return out;
}

}  // namespace dualight
