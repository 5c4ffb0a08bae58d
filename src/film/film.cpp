#include "film/film.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace dualight {

Film::Film(int width, int height) : width_(width), height_(height) {
  if (width < 1 || height < 1) throw std::invalid_argument("film must be at least 1x1");
  pixels_.resize(static_cast<size_t>(width) * static_cast<size_t>(height));
  block_.resize(pixels_.size());
}

void Film::add_splats(const Splat* first, const Splat* last, uint64_t light_paths) {
  if (splats_.empty()) {
    splats_.resize(pixels_.size());
    splat_block_.resize(pixels_.size());
  }
  for (const Splat* it = first; it != last; ++it) {
    const Splat& s = *it;
    if (s.layer == 0) {
      splat_block_[s.pixel].add(s.value);
    } else {
      double* splat = layers_[(s.layer - 1) * pixels_.size() + s.pixel].splat;
      for (int c = 0; c < 3; ++c) splat[c] += s.value[c];
    }
  }
  light_paths_ += light_paths;
}

void Film::end_splat_block() {
  for (size_t i = 0; i < splats_.size(); ++i) splats_[i].add_block(splat_block_[i]);
}

void Film::end_blocks() {
  for (size_t i = 0; i < pixels_.size(); ++i) end_block(i);
  end_splat_block();
}

FilmAccumulators Film::accumulators() const {
  FilmAccumulators a;
  const size_t n = pixels_.size();
  a.sum.resize(3 * n);
  a.sum_sq.resize(3 * n);
  a.count.resize(n);
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      a.sum[3 * i + c] = pixels_[i].sum[c];
      a.sum_sq[3 * i + c] = pixels_[i].sum_sq[c];
    }
    a.count[i] = pixels_[i].count;
  }
  if (!splats_.empty()) {
    a.splat_sum.resize(3 * n);
    a.splat_sum_sq.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        a.splat_sum[3 * i + c] = splats_[i].sum[c];
        a.splat_sum_sq[3 * i + c] = splats_[i].sum_sq[c];
      }
    }
  }
  a.light_paths = light_paths_;
  return a;
}

void Film::add_accumulators(const FilmAccumulators& a) {
  const size_t n = pixels_.size();
  if (a.sum.size() != 3 * n || a.sum_sq.size() != 3 * n || a.count.size() != n) {
    throw std::invalid_argument("accumulators do not match the film's size");
  }
  const bool splats = !a.splat_sum.empty();
  if (splats && (a.splat_sum.size() != 3 * n || a.splat_sum_sq.size() != 3 * n)) {
    throw std::invalid_argument("splat accumulators do not match the film's size");
  }
  // They may come from another process (executor tasks): radiance sums are finite and
  // non-negative, and no count may wrap around.
  const auto sane = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x) && x >= 0.0; });
  };
  if (!sane(a.sum) || !sane(a.sum_sq) || !sane(a.splat_sum) || !sane(a.splat_sum_sq)) {
    throw std::invalid_argument("accumulators hold negative or non-finite sums");
  }
  for (size_t i = 0; i < n; ++i) {
    if (a.count[i] > std::numeric_limits<uint32_t>::max() - pixels_[i].count) {
      throw std::invalid_argument("accumulators overflow a pixel's sample count");
    }
    for (int c = 0; c < 3 && a.count[i] == 0; ++c) {
      if (a.sum[3 * i + c] != 0.0 || a.sum_sq[3 * i + c] != 0.0) {
        throw std::invalid_argument("accumulators hold sums for a pixel without samples");
      }
    }
  }
  if (a.light_paths > std::numeric_limits<uint64_t>::max() - light_paths_) {
    throw std::invalid_argument("accumulators overflow the light path count");
  }
  // The same additions as Film::end_block / end_splat_block: a block's sums onto the totals.
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) {
      pixels_[i].sum[c] += a.sum[3 * i + c];
      pixels_[i].sum_sq[c] += a.sum_sq[3 * i + c];
    }
    pixels_[i].count += a.count[i];
  }
  if (splats) {
    if (splats_.empty()) {
      splats_.resize(n);
      splat_block_.resize(n);
    }
    for (size_t i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) {
        splats_[i].sum[c] += a.splat_sum[3 * i + c];
        splats_[i].sum_sq[c] += a.splat_sum_sq[3 * i + c];
      }
    }
  }
  light_paths_ += a.light_paths;
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
