// Gauss-Legendre quadrature on [-1, 1]: n nodes and weights integrating polynomials of degree
// 2n - 1 exactly [Press et al., Numerical Recipes, sec. 4.6; Newton's method on P_n from
// Chebyshev initial guesses].
#pragma once
#include <cmath>
#include <vector>

namespace dualight {

struct Quadrature {
  std::vector<double> nodes, weights;
};

inline Quadrature gauss_legendre(int n) {
  Quadrature q;
  q.nodes.resize(static_cast<size_t>(n));
  q.weights.resize(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int iter = 0; iter < 100; ++iter) {
      double p0 = 1.0, p1 = x;  // P_0, P_1; recurrence up to P_n
      for (int k = 2; k <= n; ++k) {
        const double pk = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = pk;
      }
      dp = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-15) break;
    }
    q.nodes[static_cast<size_t>(i)] = x;
    q.weights[static_cast<size_t>(i)] = 2.0 / ((1.0 - x * x) * dp * dp);
  }
  return q;
}

}  // namespace dualight
