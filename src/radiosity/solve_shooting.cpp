#include "radiosity/solve_shooting.h"

#include <stdexcept>

#include "core/stopwatch.h"

namespace dualight {

SouthwellSolver::SouthwellSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side,
                                 std::vector<double> rhs, uint32_t shots_per_step)
    : system_(std::move(system)), side_(side), b_(std::move(rhs)), shots_per_step_(shots_per_step) {
  if (b_.size() != 3 * system_->size()) throw std::invalid_argument("right-hand side must be n x 3");
  x_.assign(b_.size(), 0.0);
  r_ = b_;  // x = 0: everything is unshot
  for (const double v : b_) b_scale_ = std::max(b_scale_, std::abs(v));
  if (shots_per_step_ == 0) shots_per_step_ = static_cast<uint32_t>(std::max<size_t>(1, system_->size()));
}

double SouthwellSolver::priority(uint32_t i) const {
  const double unshot = std::abs(r_[3 * i]) + std::abs(r_[3 * i + 1]) + std::abs(r_[3 * i + 2]);
  return side_ == SystemSide::Primal ? system_->area[i] * unshot : unshot;
}

SolverStep SouthwellSolver::step() {
  const Stopwatch t0;
  const uint32_t n = static_cast<uint32_t>(system_->size());
  const CsrMatrix& F = system_->matrices->F;
  const CsrMatrix& Ft = system_->matrices->Ft;
  const std::vector<double>& rho = system_->rho;
  for (uint32_t shot = 0; shot < shots_per_step_; ++shot) {
    uint32_t best = 0;
    double best_priority = -1.0;
    for (uint32_t i = 0; i < n; ++i) {
      const double p = priority(i);
      if (p > best_priority) {
        best_priority = p;
        best = i;
      }
    }
    if (!(best_priority > 0.0)) break;  // nothing left to shoot: exact solution
    const double dr[3] = {r_[3 * best], r_[3 * best + 1], r_[3 * best + 2]};
    for (int c = 0; c < 3; ++c) {
      x_[3 * best + c] += dr[c];
      r_[3 * best + c] = 0.0;
    }
    // r <- r + K e_best dr: column `best` of K.
    if (side_ == SystemSide::Primal) {  // K = diag(rho) F: column best of F is row best of F^T
      for (uint64_t k = Ft.indptr[best]; k < Ft.indptr[best + 1]; ++k) {
        const uint32_t j = Ft.indices[k];
        const double f = Ft.values[k];
        for (int c = 0; c < 3; ++c) r_[3 * j + c] += rho[3 * j + c] * f * dr[c];
      }
    } else {  // K = F^T diag(rho): column best is rho_best times row best of F
      for (uint64_t k = F.indptr[best]; k < F.indptr[best + 1]; ++k) {
        const uint32_t j = F.indices[k];
        const double f = F.values[k];
        for (int c = 0; c < 3; ++c) r_[3 * j + c] += f * rho[3 * best + c] * dr[c];
      }
    }
    ++shots_;
  }
  return {++iteration_, residual(), t0()};
}

double SouthwellSolver::residual() const {
  double worst = 0.0;
  for (const double v : r_) worst = std::max(worst, std::abs(v));
  return b_scale_ > 0.0 ? worst / b_scale_ : worst;
}

std::vector<double> SouthwellSolver::ambient() const {
  // Area weights on the primal side (radiosity is per area), uniform ones on the dual side.
  double weight_sum = 0.0;
  double unshot[3] = {0, 0, 0}, rho_avg[3] = {0, 0, 0};
  for (uint32_t i = 0; i < system_->size(); ++i) {
    const double w = side_ == SystemSide::Primal ? system_->area[i] : 1.0;
    weight_sum += w;
    for (int c = 0; c < 3; ++c) {
      unshot[c] += w * r_[3 * i + c];
      rho_avg[c] += w * system_->rho[3 * i + c];
    }
  }
  std::vector<double> out(3, 0.0);
  for (int c = 0; c < 3; ++c) {
    const double avg = rho_avg[c] / weight_sum;
    out[c] = avg < 1.0 ? (unshot[c] / weight_sum) / (1.0 - avg) : 0.0;
  }
  return out;
}

}  // namespace dualight
