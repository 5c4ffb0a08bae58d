// Bit interleaving for Morton codes: spreads an integer's low bits apart so that two or three
// coordinates can be merged bit by bit with shifts and ors ("magic numbers" of Raman and Wise,
// "Converting to and from dilated integers", IEEE Trans. Computers 2008).
#pragma once
#include <cstdint>

namespace dualight {

// Bit i of the low 21 bits of x moved to bit 3 i.
constexpr uint64_t spread_bits_3(uint32_t x) {
  uint64_t v = x & 0x1fffffu;
  v = (v | (v << 32)) & 0x1f00000000ffffull;
  v = (v | (v << 16)) & 0x1f0000ff0000ffull;
  v = (v | (v << 8)) & 0x100f00f00f00f00full;
  v = (v | (v << 4)) & 0x10c30c30c30c30c3ull;
  v = (v | (v << 2)) & 0x1249249249249249ull;
  return v;
}

// Bit i of the low 16 bits of x moved to bit 2 i.
constexpr uint32_t spread_bits_2(uint32_t x) {
  uint32_t v = x & 0xffffu;
  v = (v | (v << 8)) & 0x00ff00ffu;
  v = (v | (v << 4)) & 0x0f0f0f0fu;
  v = (v | (v << 2)) & 0x33333333u;
  v = (v | (v << 1)) & 0x55555555u;
  return v;
}

static_assert(spread_bits_3(0x1fffffu) == 0x1249249249249249ull && spread_bits_3(0b101u) == 0b1000001ull);
static_assert(spread_bits_2(0xffffu) == 0x55555555u && spread_bits_2(0b11u) == 0b101u);

}  // namespace dualight
