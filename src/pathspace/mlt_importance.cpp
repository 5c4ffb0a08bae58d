#include "pathspace/mlt_importance.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "film/pixel_estimate.h"

namespace dualight {

PixelImportance::PixelImportance(const std::vector<double>& luminance, int width, int height, int radius,
                                 double floor_fraction) {
  const size_t n = static_cast<size_t>(width) * static_cast<size_t>(height);
  const std::vector<double> blurred = box_blurred(luminance, width, height, radius);
  const double mean = std::accumulate(blurred.begin(), blurred.end(), 0.0) / static_cast<double>(n);
  if (!(mean > 0.0)) return;  // nothing seen: stay with luminance
  const double floor = floor_fraction * mean;
  factor_.resize(n);
  // Scaled so that the mean pixel keeps factor 1 (only ratios matter; this keeps f* near f).
  for (size_t i = 0; i < n; ++i) factor_[i] = static_cast<float>(std::sqrt(mean / (blurred[i] + floor)));
}

}  // namespace dualight
