// The start-up of the MLT methods (direct light, pilot, bootstrap) under a time limit: each
// part gets at most a share of it, so that a short budget still leaves most of its time to the
// chains (at 0.4 s on the door, 128 spp of direct light and 100,000 bootstrap samples took it
// all). Without a time limit the parts run in full.
#pragma once
#include <algorithm>
#include <cstddef>

#include "core/parallel.h"
#include "core/render_control.h"

namespace dualight {

// Shares of the time limit.
constexpr double kDirectShare = 0.1, kPilotShare = 0.05, kBootstrapShare = 0.1;
constexpr size_t kSampleBlock = 1024, kBlocksPerWave = 8;

// Runs block(b, begin, end) over the samples [0, count) in blocks of kSampleBlock, in parallel;
// with seconds > 0, in waves of kBlocksPerWave blocks, stopping after the wave that ends past
// `seconds` from now (at least `min_count` samples). Returns the samples done: a
// prefix of the stream, so the result depends on timing only through its length.
template <class Elapsed, class Block>
size_t run_sample_blocks(int threads, size_t count, size_t min_count, double seconds, const Elapsed& elapsed,
                         const RenderControl& control, const Block& block) {
  const double deadline = elapsed() + seconds;
  const size_t blocks = (count + kSampleBlock - 1) / kSampleBlock;
  size_t done = 0;
  const size_t wave = seconds > 0.0 ? kBlocksPerWave : std::max<size_t>(blocks, 1);
  for (size_t first = 0; first < blocks && !control.cancelled(); first += wave) {
    const size_t last = std::min(blocks, first + wave);
    parallel_for_each_index(threads, last - first, [&](size_t i) {
      const size_t b = first + i;
      block(b, b * kSampleBlock, std::min(count, (b + 1) * kSampleBlock));
    });
    done = std::min(count, last * kSampleBlock);
    if (seconds > 0.0 && done >= min_count && elapsed() >= deadline) break;
  }
  return done;
}

}  // namespace dualight
