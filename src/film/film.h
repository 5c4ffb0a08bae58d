// Box-filtered film. A pixel's estimate has two independent parts:
//  * its own samples (camera paths drawn in the pixel): the sum and sum of squares of each;
//  * splats from light paths, which land wherever they project: for each light path, the sum of
//    what it added to the pixel (one value per path and pixel, see SplatList), so that the
//    variance of the splat part is known too. Splats are normalised by the number of light paths.
// The pixel's mean is own_sum / own_count + splat_sum / light_paths, and its variance of the mean
// the sum of the two parts' variances of the mean.
// Optional extra layers (BDPT's per-strategy images) hold the same two parts, means only.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "film/splat_list.h"

namespace dualight {

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return pixels_.size(); }

  // Not thread-safe per pixel: a pixel must be written by one task at a time.
  void add_sample(size_t pixel, const Color& value) {
    Accumulator& a = pixels_[pixel];
    a.add(value);
    ++a.count;
  }
  // Adds light paths' splats (serially: splats may land on any pixel) and counts the paths.
  void add_splats(const SplatList& splats, uint64_t light_paths);
  uint64_t light_paths() const { return light_paths_; }

  void add_layers(size_t count) { layers_.resize(count * pixels_.size()); layer_count_ = count; }
  size_t layer_count() const { return layer_count_; }
  // A pixel's own sample's share in layer k (same threading rule as add_sample; the sample
  // itself is counted by add_sample).
  void add_layer_sample(size_t layer, size_t pixel, const Color& value) {
    double* own = layers_[layer * pixels_.size() + pixel].own;
    for (int c = 0; c < 3; ++c) own[c] += value[c];
  }
  std::vector<float> layer_mean(size_t layer) const;

  // H x W x 3 float32, row 0 at the top.
  std::vector<float> mean() const;
  // Variance of each pixel's mean estimate, s^2 / n per part (0 for a part with n < 2).
  std::vector<float> variance_of_mean() const;
  std::vector<uint32_t> sample_counts() const;

 private:
  struct Accumulator {
    double sum[3] = {0, 0, 0};
    double sum_sq[3] = {0, 0, 0};
    uint32_t count = 0;
    void add(const Color& value) {
      for (int c = 0; c < 3; ++c) {
        const double v = value[c];
        sum[c] += v;
        sum_sq[c] += v * v;
      }
    }
  };
  int width_, height_;
  std::vector<Accumulator> pixels_;
  std::vector<Accumulator> splats_;  // allocated on the first splat; counts unused
  uint64_t light_paths_ = 0;
  struct LayerPixel {
    double own[3] = {0, 0, 0}, splat[3] = {0, 0, 0};
  };
  std::vector<LayerPixel> layers_;
  size_t layer_count_ = 0;
};

}  // namespace dualight
