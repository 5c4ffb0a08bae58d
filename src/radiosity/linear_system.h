// The radiosity system M B = E and its dual M^T I = R, with M = I - diag(rho) F per RGB channel
// [Smits, Arvo and Salesin 1992; Christensen et al. 1993]. Gathering radiosity multiplies by F;
// gathering importance multiplies by F^T, i.e. shoots along the reversed form factors.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <vector>

#include "core/parallel.h"
#include "radiosity/csr_matrix.h"

namespace dualight {

enum class SystemSide { Primal, Dual };  // M x = b (radiosity) or M^T x = b (importance)

// F and its transpose, stored once and shared by every solver of a solution.
struct FormFactorMatrices {
  CsrMatrix F, Ft;
  explicit FormFactorMatrices(CsrMatrix f) : F(std::move(f)), Ft(F.transpose()) {}

  struct Checks {
    double reciprocity_max = 0.0;   // max |A_i F_ij - A_j F_ji| / max(A_i F_ij, A_j F_ji)
    double reciprocity_mean = 0.0;  // the same, weighted by max(A_i F_ij, A_j F_ji)
    double row_sum_min = 0.0, row_sum_max = 0.0, row_sum_mean = 0.0;  // mean area-weighted
  };
  // Row i of F and row i of F^T (column i of F, i.e. F_ji) are both sorted by column: merging
  // them pairs every F_ij with F_ji without any extra memory.
  Checks checks(const std::vector<double>& area) const {
    Checks c;
    double weighted = 0.0, weight = 0.0, sum_area = 0.0;
    c.row_sum_min = F.n ? 1e300 : 0.0;
    for (uint32_t i = 0; i < F.n; ++i) {
      uint64_t a = F.indptr[i], b = Ft.indptr[i];
      const uint64_t a_end = F.indptr[i + 1], b_end = Ft.indptr[i + 1];
      while (a < a_end || b < b_end) {
        const uint32_t ja = a < a_end ? F.indices[a] : UINT32_MAX, jb = b < b_end ? Ft.indices[b] : UINT32_MAX;
        const uint32_t j = std::min(ja, jb);
        const double fij = ja == j ? F.values[a++] : 0.0, fji = jb == j ? Ft.values[b++] : 0.0;
        const double x = area[i] * fij, y = area[j] * fji, scale = std::max(x, y);
        if (scale > 0.0) {
          const double rel = std::abs(x - y) / scale;
          c.reciprocity_max = std::max(c.reciprocity_max, rel);
          weighted += rel * scale;
          weight += scale;
        }
      }
      const double s = F.row_sum(i);
      c.row_sum_min = std::min(c.row_sum_min, s);
      c.row_sum_max = std::max(c.row_sum_max, s);
      c.row_sum_mean += area[i] * s;
      sum_area += area[i];
    }
    c.reciprocity_mean = weight > 0.0 ? weighted / weight : 0.0;
    c.row_sum_mean = sum_area > 0.0 ? c.row_sum_mean / sum_area : 0.0;
    return c;
  }
};

struct RadiositySystem {
  std::shared_ptr<const FormFactorMatrices> matrices;
  std::vector<double> rho;   // n x 3 reflectance
  std::vector<double> area;  // n

  RadiositySystem(std::shared_ptr<const FormFactorMatrices> m, std::vector<double> reflectance,
                  std::vector<double> areas)
      : matrices(std::move(m)), rho(std::move(reflectance)), area(std::move(areas)) {
    if (!matrices) throw std::invalid_argument("form factors are missing");
    if (rho.size() != 3 * size() || area.size() != size()) {
      throw std::invalid_argument("reflectance must be n x 3 and areas n, for n patches");
    }
  }
  size_t size() const { return matrices->F.n; }

  // Row i of K x, where M = I - K: K = diag(rho) F (primal) or F^T diag(rho) (dual); 3 channels.
  void row_of_transport(SystemSide side, uint32_t i, const double* x, double out[3]) const {
    out[0] = out[1] = out[2] = 0.0;
    if (side == SystemSide::Primal) {
      const CsrMatrix& F = matrices->F;
      for (uint64_t k = F.indptr[i]; k < F.indptr[i + 1]; ++k) {
        const double f = F.values[k];
        const double* xj = x + 3 * F.indices[k];
        out[0] += f * xj[0];
        out[1] += f * xj[1];
        out[2] += f * xj[2];
      }
      for (int c = 0; c < 3; ++c) out[c] *= rho[3 * i + c];
    } else {
      const CsrMatrix& Ft = matrices->Ft;
      for (uint64_t k = Ft.indptr[i]; k < Ft.indptr[i + 1]; ++k) {
        const uint32_t j = Ft.indices[k];
        const double f = Ft.values[k];
        for (int c = 0; c < 3; ++c) out[c] += f * rho[3 * j + c] * x[3 * j + c];
      }
    }
  }

  // max |b - M x| / max |b|: the relative residual every solver reports. Rows in parallel; a
  // maximum does not depend on the order, so the result does not depend on the threads.
  double relative_residual(SystemSide side, const std::vector<double>& x, const std::vector<double>& b,
                           int threads = 0) const {
    constexpr uint32_t kChunk = 512;
    const uint32_t n = static_cast<uint32_t>(size());
    std::vector<double> worst((n + kChunk - 1) / kChunk, 0.0);
    parallel_for_each_index(threads, worst.size(), [&](size_t chunk) {
      double w = 0.0;
      for (uint32_t i = static_cast<uint32_t>(chunk * kChunk); i < std::min(n, static_cast<uint32_t>((chunk + 1) * kChunk)); ++i) {
        double kx[3];
        row_of_transport(side, i, x.data(), kx);
        for (int c = 0; c < 3; ++c) w = std::max(w, std::abs(b[3 * i + c] - x[3 * i + c] + kx[c]));
      }
      worst[chunk] = w;
    });
    double scale = 0.0;
    for (const double v : b) scale = std::max(scale, std::abs(v));
    const double r = worst.empty() ? 0.0 : *std::max_element(worst.begin(), worst.end());
    return scale > 0.0 ? r / scale : r;
  }
};

// What one step of any solver reports.
struct SolverStep {
  uint64_t iteration = 0;
  double residual = 0.0;  // relative, as RadiositySystem::relative_residual
  double seconds = 0.0;   // this step alone
};

}  // namespace dualight
