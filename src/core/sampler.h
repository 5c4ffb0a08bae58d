// Samplers: every random number an estimator uses comes from one of these, one sampler per
// (pixel, sample index), so images do not depend on threads and a sampler swap changes the
// sampling strategy without touching the estimator (later: primary-sample-space MLT).
//
// IndependentSampler: uniform random numbers (PCG32), what Mitsuba's `independent` does. Its
//   samples are independent, so a pixel's sample variance estimates its error honestly.
// SobolSampler: each 2D (and 1D) dimension draws from the first two Sobol dimensions with a
//   hash-based Owen scramble and an Owen-shuffled index of its own ("padded" Sobol) [Burley
//   2020, "Practical Hash-based Owen Scrambling", JCGT 9(4)]. Stratified in every pair, so it
//   converges faster on smooth integrands; its samples are not independent, so per-pixel sample
//   variances overestimate the error (tests use the independent sampler).
#pragma once
#include <cstdint>

#include "core/rng.h"
#include "core/sampling.h"

namespace dualight {

enum class SamplerType { Independent, Sobol };

// The named streams of a BDPT sample's numbers (pbrt-v4's cameraStreamIndex, ...): the camera
// subpath, the light subpath and the connections each draw from their own, so that a
// primary-sample mutation that lengthens one leaves the others' numbers where they were.
// Samplers with a single stream ignore them.
enum SampleStream : int { kCameraStream = 0, kLightStream = 1, kConnectStream = 2 };

class IndependentSampler {
 public:
  IndependentSampler(uint64_t seed, uint64_t pixel, uint32_t sample_index)
      : rng_(hash_combine(seed, pixel), sample_index) {}
  float next_1d() { return rng_.next_float(); }
  Point2 next_2d() {
    const float u = rng_.next_float();
    return {u, rng_.next_float()};
  }
  void start_stream(int) {}  // see PrimarySampleSampler
  const Pcg32& rng() const { return rng_; }

 private:
  Pcg32 rng_;
};

namespace sobol_detail {

constexpr uint32_t reverse_bits(uint32_t x) {
  x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
  x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
  x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
  return (x >> 16) | (x << 16);
}

// Owen scramble of a value in bit-reversed order [Burley 2020, listing 2, improved constants]:
// each output bit depends on the same and lower input bits only.
constexpr uint32_t laine_karras_permutation(uint32_t x, uint32_t seed) {
  x ^= x * 0x3d20adeau;
  x += seed;
  x *= (seed >> 16) | 1u;
  x ^= x * 0x05526c56u;
  x ^= x * 0x53a22864u;
  return x;
}

// Sobol dimension 1 (dimension 0 is bit reversal): XOR of direction numbers v_k for the set
// bits k of the index, v_0 = 2^31, v_k = v_{k-1} ^ (v_{k-1} >> 1). Looked up a byte at a time,
// since shuffled indices use all 32 bits.
struct Dimension1Table {
  uint32_t by_byte[4][256] = {};
  constexpr Dimension1Table() {
    uint32_t v[32] = {};
    v[0] = 0x80000000u;
    for (int k = 1; k < 32; ++k) v[k] = v[k - 1] ^ (v[k - 1] >> 1);
    for (int byte = 0; byte < 4; ++byte) {
      for (uint32_t value = 0; value < 256; ++value) {
        uint32_t x = 0;
        for (int bit = 0; bit < 8; ++bit) {
          if (value & (1u << bit)) x ^= v[8 * byte + bit];
        }
        by_byte[byte][value] = x;
      }
    }
  }
};
inline constexpr Dimension1Table kDimension1{};

inline uint32_t sobol_dimension1(uint32_t index) {
  return kDimension1.by_byte[0][index & 0xffu] ^ kDimension1.by_byte[1][(index >> 8) & 0xffu] ^
         kDimension1.by_byte[2][(index >> 16) & 0xffu] ^ kDimension1.by_byte[3][index >> 24];
}

constexpr float to_unit_float(uint32_t x) { return static_cast<float>(x >> 8) * 0x1p-24f; }

}  // namespace sobol_detail

class SobolSampler {
 public:
  SobolSampler(uint64_t seed, uint64_t pixel, uint32_t sample_index)
      : pixel_seed_(hash_combine(seed, pixel)), reversed_index_(sobol_detail::reverse_bits(sample_index)) {}

  float next_1d() {
    using namespace sobol_detail;
    const Seeds s = next_seeds();
    // Dimension 0 of the shuffled index, Owen-scrambled. With NUS(x) = rev(LK(rev(x))) and
    // dimension 0 = rev(index), the scrambled value is rev(LK(shuffled index)).
    return to_unit_float(reverse_bits(laine_karras_permutation(shuffled_index(s.shuffle), s.x)));
  }
  Point2 next_2d() {
    using namespace sobol_detail;
    const Seeds s = next_seeds();
    const uint32_t index = shuffled_index(s.shuffle);
    const uint32_t x = reverse_bits(laine_karras_permutation(index, s.x));
    const uint32_t y = reverse_bits(laine_karras_permutation(reverse_bits(sobol_dimension1(index)), s.y));
    return {to_unit_float(x), to_unit_float(y)};
  }
  void start_stream(int) {}  // see PrimarySampleSampler
  // The state, for lanes that step samplers together (core/lanes.h, LaneSobol).
  uint64_t pixel_seed() const { return pixel_seed_; }
  uint32_t reversed_index() const { return reversed_index_; }
  uint32_t dimension() const { return dimension_; }

 private:
  struct Seeds {
    uint32_t shuffle, x, y;
  };
  // Each dimension gets its own index shuffle (decorrelating dimensions: "padding") and scrambles.
  Seeds next_seeds() {
    const uint64_t a = mix64(pixel_seed_ + 0x9e3779b97f4a7c15ull * ++dimension_);
    const uint64_t b = mix64(a);
    return {static_cast<uint32_t>(a), static_cast<uint32_t>(a >> 32), static_cast<uint32_t>(b)};
  }
  // Owen scramble of the index itself: a permutation within every aligned block of 2^k indices,
  // so any power-of-two count of samples is still a (0, m, 2)-net.
  uint32_t shuffled_index(uint32_t seed) const {
    return sobol_detail::reverse_bits(sobol_detail::laine_karras_permutation(reversed_index_, seed));
  }

  uint64_t pixel_seed_;
  uint32_t reversed_index_;
  uint32_t dimension_ = 0;
};

// Calls f(SamplerTag<S>{}) with the sampler class S that `type` names, so that estimators are
// compiled once per sampler and chosen at run time in one place.
template <class S>
struct SamplerTag {
  using type = S;
};
template <class F>
auto with_sampler(SamplerType type, F&& f) {
  return type == SamplerType::Sobol ? f(SamplerTag<SobolSampler>{}) : f(SamplerTag<IndependentSampler>{});
}

}  // namespace dualight
