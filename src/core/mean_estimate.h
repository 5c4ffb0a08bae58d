// Running mean of independent samples with the variance of that mean, for normalisation
// constants (MLT's b) estimated from bootstrap samples and large steps.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

namespace dualight {

struct MeanEstimate {
  double sum = 0.0, sum_sq = 0.0;
  uint64_t n = 0;
  void add(double f) {
    sum += f;
    sum_sq += f * f;
    ++n;
  }
  MeanEstimate& operator+=(const MeanEstimate& o) {
    sum += o.sum;
    sum_sq += o.sum_sq;
    n += o.n;
    return *this;
  }
  double mean() const { return n > 0 ? sum / static_cast<double>(n) : 0.0; }
  double variance_of_mean() const {
    if (n < 2) return 0.0;
    const double k = static_cast<double>(n);
    return std::max(0.0, (sum_sq - sum * mean()) / (k - 1.0)) / k;
  }
};

inline MeanEstimate estimate_of(const std::vector<double>& f) {
  MeanEstimate e;
  for (const double x : f) e.add(x);
  return e;
}

}  // namespace dualight
