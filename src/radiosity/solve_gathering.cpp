#include "radiosity/solve_gathering.h"

#include <stdexcept>

#include "core/parallel.h"
#include "core/stopwatch.h"

namespace dualight {

namespace {
void check_rhs(const RadiositySystem& s, const std::vector<double>& b) {
  if (b.size() != 3 * s.size()) throw std::invalid_argument("right-hand side must be n x 3");
}
}  // namespace

JacobiSolver::JacobiSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side, std::vector<double> rhs,
                           int threads)
    : system_(std::move(system)), side_(side), b_(std::move(rhs)), threads_(threads) {
  check_rhs(*system_, b_);
  x_.assign(b_.size(), 0.0);
  next_.assign(b_.size(), 0.0);
}

SolverStep JacobiSolver::step() {
  const Stopwatch t0;
  const uint32_t n = static_cast<uint32_t>(system_->size());
  constexpr uint32_t kChunk = 256;
  // Rows are independent within a sweep: parallel, and the same result for any thread count.
  parallel_for_each_index(threads_, (n + kChunk - 1) / kChunk, [&](size_t chunk) {
    for (uint32_t i = static_cast<uint32_t>(chunk * kChunk); i < std::min(n, static_cast<uint32_t>((chunk + 1) * kChunk)); ++i) {
      double kx[3];
      system_->row_of_transport(side_, i, x_.data(), kx);
      for (int c = 0; c < 3; ++c) next_[3 * i + c] = b_[3 * i + c] + kx[c];
    }
  });
  x_.swap(next_);
  residual_ = system_->relative_residual(side_, x_, b_, threads_);
  return {++iteration_, residual_, t0()};
}

GaussSeidelSolver::GaussSeidelSolver(std::shared_ptr<const RadiositySystem> system, SystemSide side,
                                     std::vector<double> rhs)
    : system_(std::move(system)), side_(side), b_(std::move(rhs)) {
  check_rhs(*system_, b_);
  x_.assign(b_.size(), 0.0);
}

SolverStep GaussSeidelSolver::step() {
  const Stopwatch t0;
  const uint32_t n = static_cast<uint32_t>(system_->size());
  for (uint32_t i = 0; i < n; ++i) {
    double kx[3];
    system_->row_of_transport(side_, i, x_.data(), kx);  // uses the updated x_j for j < i
    for (int c = 0; c < 3; ++c) x_[3 * i + c] = b_[3 * i + c] + kx[c];
  }
  residual_ = system_->relative_residual(side_, x_, b_);
  return {++iteration_, residual_, t0()};
}

}  // namespace dualight
