#include "film/film.h"

#include <algorithm>
#include <stdexcept>

namespace dualight {

Film::Film(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("film must be at least 1x1");
  pixels_.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
}

void Film::add_splats(const SplatList& splats, uint64_t light_paths) {
  if (splats_.empty()) splats_.resize(pixels_.size());
  for (const Splat& s : splats.splats()) {
    if (s.layer == 0) {
      splats_[s.pixel].add(s.value);
    } else {
      double* splat = layers_[(s.layer - 1) * pixels_.size() + s.pixel].splat;
      for (int c = 0; c < 3; ++c) splat[c] += s.value[c];
    }
  }
  light_paths_ += light_paths;
}

std::vector<float> Film::layer_mean(size_t layer) const {
  std::vector<float> out(pixels_.size() * 3, 0.f);
  const double inv_paths = light_paths_ > 0 ? 1.0 / static_cast<double>(light_paths_) : 0.0;
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const LayerPixel& l = layers_[layer * pixels_.size() + i];
    const double inv_count = pixels_[i].count > 0 ? 1.0 / pixels_[i].count : 0.0;
    for (int c = 0; c < 3; ++c) out[3 * i + c] = static_cast<float>(l.own[c] * inv_count + l.splat[c] * inv_paths);
  }
  return out;
}

std::vector<float> Film::mean() const {
  std::vector<float> out(pixels_.size() * 3, 0.f);
  const double inv_paths = light_paths_ > 0 ? 1.0 / static_cast<double>(light_paths_) : 0.0;
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const Accumulator& a = pixels_[i];
    for (int c = 0; c < 3; ++c) {
      double m = a.count > 0 ? a.sum[c] / a.count : 0.0;
      if (!splats_.empty()) m += splats_[i].sum[c] * inv_paths;
      out[3 * i + c] = static_cast<float>(m);
    }
  }
  return out;
}

namespace {

// s^2 / n of n samples with the given sum and sum of squares (samples that are 0 included).
double variance_of_mean_of(double sum, double sum_sq, double n) {
  if (n < 2.0) return 0.0;
  return std::max(0.0, (sum_sq - sum * sum / n) / (n - 1.0)) / n;
}

}  // namespace

std::vector<float> Film::variance_of_mean() const {
  std::vector<float> out(pixels_.size() * 3, 0.f);
  const double paths = static_cast<double>(light_paths_);
  for (size_t i = 0; i < pixels_.size(); ++i) {
    const Accumulator& a = pixels_[i];
    for (int c = 0; c < 3; ++c) {
      double v = variance_of_mean_of(a.sum[c], a.sum_sq[c], a.count);
      if (!splats_.empty()) v += variance_of_mean_of(splats_[i].sum[c], splats_[i].sum_sq[c], paths);
      out[3 * i + c] = static_cast<float>(v);
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
