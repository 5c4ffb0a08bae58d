#include "pathspace/mlt_importance.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace dualight {

PixelImportance::PixelImportance(const std::vector<double>& luminance, int width, int height, int radius,
                                 double floor_fraction) {
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  // Summed-area table: each box mean in O(1).
  std::vector<double> sum(static_cast<size_t>(width + 1) * static_cast<size_t>(height + 1), 0.0);
  const auto at = [&](int x, int y) -> double& { return sum[static_cast<size_t>(y) * (width + 1) + x]; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double v = std::max(0.0, luminance[static_cast<size_t>(y) * width + x]);
      at(x + 1, y + 1) = v + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  }
  std::vector<double> blurred(n);
  for (int y = 0; y < height; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      const double box = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
      blurred[static_cast<size_t>(y) * width + x] = box / static_cast<double>((x1 - x0) * (y1 - y0));
    }
  }
  const double mean = std::accumulate(blurred.begin(), blurred.end(), 0.0) / static_cast<double>(n);
  if (!(mean > 0.0)) return;  // nothing seen: stay with luminance
  const double floor = floor_fraction * mean;
  factor_.resize(n);
  // Scaled so that the mean pixel keeps factor 1 (only ratios matter; this keeps f* near f).
  for (size_t i = 0; i < n; ++i) factor_[i] = static_cast<float>(std::sqrt(mean / (blurred[i] + floor)));
}

}  // namespace dualight
