// Box-filtered film. A pixel's estimate has two independent parts:
//  * its own samples (camera paths drawn in the pixel): the sum and sum of squares of each;
//  * splats from light paths, which land wherever they project: for each light path, the sum of
//    what it added to the pixel (one value per path and pixel, see SplatList), so that the
//    variance of the splat part is known too. Splats are normalised by the number of light paths.
// The pixel's mean is own_sum / own_count + splat_sum / light_paths, and its variance of the mean
// the sum of the two parts' variances of the mean.
// Optional extra layers (BDPT's per-strategy images) hold the same two parts, means only.
//
// Sample blocks, so that a render split into tasks (render(executor=...)) is the same computation
// as one render, bit for bit. Doubles added in another order round differently, so every sum has
// one fixed shape: samples (and splats) are summed within blocks of kBlockSpp sample indices (for
// the light tracer, of kBlockSpp x pixels particles), each block from zero in a fixed order, and
// the blocks' sums are added to the totals in block order. A task renders whole blocks into a
// film of its own, whose totals are then exactly its block sums (0 + x = x); adding the tasks'
// accumulators() in block order with add_accumulators() repeats the single render's additions.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"
#include "film/splat_list.h"

namespace dualight {

// Sample indices per block (see above): also the finest split of a render into tasks.
constexpr uint32_t kBlockSpp = 16;

// A film's raw totals (blocks flushed): what a task returns and a merge adds.
struct FilmAccumulators {
  std::vector<double> sum, sum_sq;  // 3 per pixel
  std::vector<uint32_t> count;
  std::vector<double> splat_sum, splat_sum_sq;  // 3 per pixel; empty without splats
  uint64_t light_paths = 0;
};

class Film {
 public:
  Film(int width, int height);

  int width() const { return width_; }
  int height() const { return height_; }
  size_t pixel_count() const { return pixels_.size(); }

  // Not thread-safe per pixel: a pixel must be written by one task at a time.
  void add_sample(size_t pixel, const Color& value) {
    block_[pixel].add(value);
    ++pixels_[pixel].count;
  }
  // Adds the pixel's current block of samples to its totals (same threading rule).
  void end_block(size_t pixel) { pixels_[pixel].add_block(block_[pixel]); }
  // Adds light paths' splats to the current splat block (serially: splats may land on any
  // pixel) and counts the paths.
  void add_splats(const SplatList& splats, uint64_t light_paths) {
    add_splats(splats.splats().data(), splats.splats().data() + splats.splats().size(), light_paths);
  }
  void add_splats(const Splat* first, const Splat* last, uint64_t light_paths);
  // Adds the current splat block to the splat totals.
  void end_splat_block();
  // Flushes every open block (at the end of a render).
  void end_blocks();
  uint64_t light_paths() const { return light_paths_; }

  // The totals (blocks must be flushed), and their sum with another film's (layers excluded).
  FilmAccumulators accumulators() const;
  void add_accumulators(const FilmAccumulators& a);

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
    // Adds a block's sums to these and empties the block.
    void add_block(Accumulator& block) {
      for (int c = 0; c < 3; ++c) {
        sum[c] += block.sum[c];
        sum_sq[c] += block.sum_sq[c];
        block.sum[c] = block.sum_sq[c] = 0.0;
      }
    }
  };
  int width_, height_;
  std::vector<Accumulator> pixels_;  // totals and counts
  std::vector<Accumulator> block_;   // the open block of each pixel's own samples
  std::vector<Accumulator> splats_;  // allocated on the first splat; counts unused
  std::vector<Accumulator> splat_block_;  // the open splat block, allocated with splats_
  uint64_t light_paths_ = 0;
  struct LayerPixel {
    double own[3] = {0, 0, 0}, splat[3] = {0, 0, 0};
  };
  std::vector<LayerPixel> layers_;
  size_t layer_count_ = 0;
};

}  // namespace dualight
