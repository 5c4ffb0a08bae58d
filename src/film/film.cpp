#include "film/film.h"

#include <algorithm>
#include <stdexcept>

namespace dualight {

Film::Film(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("film must be at least 1x1");
  pixels_.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
}

std::vector<float> Film::mean() const {
  std::vector<float> out(pixels_.size() * 3, 0.f);
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const Accumulator& a = pixels_[i];
    if (a.count == 0) continue;
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(a.sum[c] / a.count);
  }
  return out;
}

std::vector<float> Film::variance_of_mean() const {
  std::vector<float> out(pixels_.size() * 3, 0.f);
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const Accumulator& a = pixels_[i];
    if (a.count < 2) continue;
    const double n = a.count;
    for (int c = 0; c < 3; ++c) {
      const double sample_var = std::max(0.0, (a.sum_sq[c] - a.sum[c] * a.sum[c] / n) / (n - 1.0));
      out[3 * i + c] = static_cast<float>(sample_var / n);
    }
  }
  return out;
}

std::vector<uint32_t> Film::sample_counts() const {
  std::vector<uint32_t> out(pixels_.size());
  std::transform(pixels_.begin(), pixels_.end(), out.begin(), [](const Accumulator& a) { return a.count; });
  return out;
}

}  // namespace dualight
