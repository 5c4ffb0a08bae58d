// PCG32 random numbers [O'Neill 2014] with seeding by hashing, so every (pixel, sample) pair
// owns an independent stream and images do not depend on the thread count or schedule.
#pragma once
#include <cstdint>

namespace dualight {

// SplitMix64 finaliser: a cheap, well-mixed hash for deriving stream seeds.
constexpr uint64_t mix64(uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
constexpr uint64_t hash_combine(uint64_t a, uint64_t b) { return mix64(a ^ mix64(b)); }

class Pcg32 {
 public:
  // The state is hashed from (seed, stream), not only the increment: PCG streams that start
  // from one state and differ in the increment are correlated (the sequences are affine images
  // of one another). Seeded as pbrt-v4 and O'Neill's reference code do (state = seed + inc,
  // stream in the increment), the samples of a pixel, which differ only in the stream, were
  // correlated by about 3e-5 per pair: at 8192 spp on the Cornell box the reported variance
  // of a pixel was 25 % short of its true error (issue 18).
  Pcg32(uint64_t seed, uint64_t stream) : state_(hash_combine(seed, stream)), inc_((stream << 1u) | 1u) {
    next_uint();
  }

  uint32_t next_uint() {
    const uint64_t old = state_;
    state_ = old * 6364136223846793005ull + inc_;
    const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rot = static_cast<uint32_t>(old >> 59u);
    return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
  }

  // The generator's state and increment (for lanes that step many generators at once, core/lanes.h).
  uint64_t state() const { return state_; }
  uint64_t increment() const { return inc_; }

  // Uniform in [0, 1): 24 random mantissa bits, so 1.0 is never returned.
  float next_float() { return static_cast<float>(next_uint() >> 8) * 0x1p-24f; }

 private:
  uint64_t state_;
  uint64_t inc_;
};

}  // namespace dualight
