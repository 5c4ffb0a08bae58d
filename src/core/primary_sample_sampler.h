// Kelemen's primary-sample-space sampler [Kelemen et al. 2002; pbrt-v3 sec. 16.4.2]: the
// random numbers an estimator draws are the state of a Markov chain. Each iteration is a large
// step (fresh uniform numbers, with probability large_step_probability) or a small step (each
// number moved by a normal of deviation sigma, wrapped to [0, 1)). Numbers are mutated lazily,
// when first used in an iteration, so estimators that draw a varying count of numbers work
// unchanged; reject() restores the previous state. Numbers come in kStreams interleaved streams
// (camera subpath, light subpath, connections, as in pbrt-v3): a camera subpath that grows or
// shrinks does not shift the numbers the light subpath uses, so small steps stay small.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "core/sampler.h"
#include "core/sampling.h"

namespace dualight {

class PrimarySampleSampler {
 public:
  PrimarySampleSampler(uint64_t seed, uint64_t stream, float sigma, float large_step_probability)
      : rng_(seed, stream), sigma_(sigma), large_step_probability_(large_step_probability) {}

  // Draws the chain's further mutations from another stream (the state is kept): chains that
  // start from the same bootstrap sample then still move independently.
  void reseed(uint64_t seed, uint64_t stream) { rng_ = Pcg32(seed, stream); }

  void start_iteration() {
    ++iteration_;
    large_step_ = rng_.next_float() < large_step_probability_;
    start_stream(kCameraStream);
  }
  // The first iteration after construction is always a large step (an independent sample).
  void start_large_step() {
    ++iteration_;
    large_step_ = true;
    start_stream(kCameraStream);
  }
  static constexpr int kStreams = 3;
  void start_stream(int stream) {
    stream_ = stream;
    index_ = 0;
  }
  bool large_step() const { return large_step_; }

  void accept() {
    if (large_step_) last_large_step_ = iteration_;
  }
  void reject() {
    for (PrimarySample& x : samples_) {
      if (x.modified == iteration_) x.restore();
    }
    --iteration_;
  }

  float next_1d() { return value(stream_ + kStreams * index_++); }
  Point2 next_2d() {
    const float u = next_1d();
    return {u, next_1d()};
  }

 private:
  struct PrimarySample {
    float x = 0.f, backup = 0.f;
    int64_t modified = 0, modified_backup = 0;
    void save() {
      backup = x;
      modified_backup = modified;
    }
    void restore() {
      x = backup;
      modified = modified_backup;
    }
  };

  float value(size_t i) {
    if (i >= samples_.size()) samples_.resize(i + 1);
    PrimarySample& s = samples_[i];
    // A number untouched since before the last accepted large step takes that step's value.
    if (s.modified < last_large_step_) {
      s.x = rng_.next_float();
      s.modified = last_large_step_;
    }
    s.save();
    if (large_step_) {
      s.x = rng_.next_float();
    } else {
      // The small steps it missed, at once: their sum is normal with variance n sigma^2.
      const int64_t n = iteration_ - s.modified;
      const float deviation = sigma_ * std::sqrt(static_cast<float>(n));
      s.x += deviation * normal();
      s.x -= std::floor(s.x);
      if (s.x >= 1.f) s.x = 0.f;  // rounding of x - floor(x) for tiny negative x
    }
    s.modified = iteration_;
    return s.x;
  }

  // Standard normal by Box-Muller (one of the pair).
  float normal() {
    const float u1 = 1.f - rng_.next_float();  // (0, 1]
    const float u2 = rng_.next_float();
    return std::sqrt(-2.f * std::log(u1)) * std::cos(2.f * kPi * u2);
  }

  Pcg32 rng_;
  float sigma_, large_step_probability_;
  std::vector<PrimarySample> samples_;
  int64_t iteration_ = 0, last_large_step_ = 0;
  bool large_step_ = true;
  size_t index_ = 0;
  int stream_ = 0;
};

}  // namespace dualight
