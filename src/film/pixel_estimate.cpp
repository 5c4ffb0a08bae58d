#include "film/pixel_estimate.h"

#include <algorithm>

#include "core/vec3.h"

namespace dualight {

std::vector<double> film_luminance(const Film& film) {
  const std::vector<float> mean = film.mean();
  std::vector<double> out(mean.size() / 3);
  for (size_t i = 0; i < out.size(); ++i) out[i] = luminance(Color(mean[3 * i], mean[3 * i + 1], mean[3 * i + 2]));
  return out;
}

std::vector<double> box_blurred(const std::vector<double>& image, int width, int height, int radius) {
  // Summed-area table: each box mean in O(1).
  std::vector<double> sum(static_cast<size_t>(width + 1) * static_cast<size_t>(height + 1), 0.0);
  const auto at = [&](int x, int y) -> double& { return sum[static_cast<size_t>(y) * (width + 1) + x]; };
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double v = std::max(0.0, image[static_cast<size_t>(y) * width + x]);
      at(x + 1, y + 1) = v + at(x, y + 1) + at(x + 1, y) - at(x, y);
    }
  }
  std::vector<double> blurred(static_cast<size_t>(width) * static_cast<size_t>(height));
  for (int y = 0; y < height; ++y) {
    const int y0 = std::max(0, y - radius), y1 = std::min(height, y + radius + 1);
    for (int x = 0; x < width; ++x) {
      const int x0 = std::max(0, x - radius), x1 = std::min(width, x + radius + 1);
      const double box = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
      blurred[static_cast<size_t>(y) * width + x] = box / static_cast<double>((x1 - x0) * (y1 - y0));
    }
  }
  return blurred;
}

}  // namespace dualight
