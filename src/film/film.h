// Box-filtered film: every sample lands in the one pixel it was drawn in, and each pixel keeps
// the sum and sum of squares of its samples so the variance of the pixel mean is known.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace dualight {

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }

  // Not thread-safe per pixel: a pixel must be written by one task at a time.
  void add_sample(size_t pixel, const Color& value) {
    Accumulator& a = pixels_[pixel];
    for (int c = 0; c < 3; ++c) {
      const double v = value[c];
      a.sum[c] += v;
      a.sum_sq[c] += v * v;
    }
    ++a.count;
  }

  // H x W x 3 float32, row 0 at the top.
  std::vector<float> mean() const;
  // Variance of each pixel's mean estimate, s^2 / n (0 where n < 2).
  std::vector<float> variance_of_mean() const;
  std::vector<uint32_t> sample_counts() const;

 private:
  struct Accumulator {
    double sum[3] = {0, 0, 0};
    double sum_sq[3] = {0, 0, 0};
    uint32_t count = 0;
  };
  int width_, height_;
  std::vector<Accumulator> pixels_;
};

}  // namespace dualight
