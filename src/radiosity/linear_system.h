// The radiosity system M B = E and its dual M^T I = R, with M = I - diag(rho) F per RGB channel
// [Smits, Arvo and Salesin 1992; Christensen et al. 1993]. Gathering radiosity multiplies by F;
// gathering importance multiplies by F^T, i.e. shoots along the reversed form factors.
#pragma once
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "radiosity/csr_matrix.h"

namespace dualight {

enum class SystemSide { Primal, Dual };  // M x = b (radiosity) or M^T x = b (importance)

// F and its transpose, stored once and shared by every solver of a solution.
struct FormFactorMatrices {
  CsrMatrix F, Ft;
  explicit FormFactorMatrices(CsrMatrix f) : F(std::move(f)), Ft(F.transpose()) {}
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

  // max |b - M x| / max |b|: the relative residual every solver reports.
  double relative_residual(SystemSide side, const std::vector<double>& x, const std::vector<double>& b) const {
    double worst = 0.0, scale = 0.0;
    for (uint32_t i = 0; i < size(); ++i) {
      double kx[3];
      row_of_transport(side, i, x.data(), kx);
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(b[3 * i + c] - x[3 * i + c] + kx[c]));
        scale = std::max(scale, std::abs(b[3 * i + c]));
      }
    }
    return scale > 0.0 ? worst / scale : worst;
  }
};

// What one step of any solver reports.
struct SolverStep {
  uint64_t iteration = 0;
  double residual = 0.0;  // relative, as RadiositySystem::relative_residual
  double seconds = 0.0;   // this step alone
};

}  // namespace dualight
