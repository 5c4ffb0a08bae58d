// Sums of many floats that do not depend on the order of the additions. The Metropolis methods
// splat into them, so that their image is the same bit for bit whether the chains run in one
// process, in rounds whose length follows the clock, or as tasks on other machines merged in any
// order (python/dualight/executor.py). Each value is rounded once to a fixed-point grid and the
// grid counts are summed in 128-bit two's complement integers (two 64-bit words), where
// addition is exact and associative. The grid is 2^-64 of a power of two at or above `scale`
// (the values' typical size: MLT's b), so values down to about 1e-19 scale keep their float
// precision, and a single value must stay below 2^62 scale (larger ones are rejected: they are
// numerical blow-ups, not light).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <utility>
#include <vector>

namespace dualight {

class ExactSums {
 public:
  ExactSums() = default;
  ExactSums(size_t count, double scale)
      : ExactSums(std::vector<uint64_t>(2 * count, 0),
                  scale > 0.0 && std::isfinite(scale) ? std::clamp(std::ilogb(scale) + 1, -900, 900) : 0) {}
  // From raw words (2 per value: low, high) and the grid exponent, as words() and exponent() give.
  ExactSums(std::vector<uint64_t> words, int exponent)
      : exponent_(exponent),
        to_grid_(std::ldexp(1.0, 64 - exponent)),
        from_grid_(std::ldexp(1.0, exponent - 64)),
        words_(std::move(words)) {
    if (words_.size() % 2 != 0 || exponent < -900 || exponent > 900) {
      throw std::invalid_argument("exact sums need two words per value and a grid exponent in [-900, 900]");
    }
  }

  size_t size() const { return words_.size() / 2; }
  bool empty() const { return words_.empty(); }
  int exponent() const { return exponent_; }
  const std::vector<uint64_t>& words() const { return words_; }

  // Adds v to value i; false (nothing added) when v is not finite or too large for the grid.
  bool add(size_t i, float v) {
    if (v == 0.f) return true;
    // Exact: a float is exactly a double, and scaling by a power of two is exact.
    const double x = static_cast<double>(v) * to_grid_;
    double a = std::fabs(x);
    if (!(a < kLimit)) return false;
    // Round to the nearest grid point, ties to even (above 2^52 a double is an integer already);
    // plain arithmetic, not a libm call: this runs for every splat.
    if (a < 0x1p52) a = (a + 0x1p52) - 0x1p52;
    // The magnitude in two words, exactly: split at 2^63 (both pieces are bits of a's 53-bit
    // significand and convert as signed integers, one instruction each), then shifted into place.
    const auto top = static_cast<int64_t>(a * 0x1p-63);
    const auto rest = static_cast<uint64_t>(static_cast<int64_t>(a - static_cast<double>(top) * 0x1p63));
    const uint64_t low = (static_cast<uint64_t>(top) << 63) | rest;
    const uint64_t high = static_cast<uint64_t>(top) >> 1;
    if (x < 0.0) {
      add_words(i, ~low + 1, ~high + (low == 0 ? 1 : 0));  // two's complement of the magnitude
    } else {
      add_words(i, low, high);
    }
    return true;
  }

  // Adds another set of sums on the same grid.
  void add(const ExactSums& o) {
    if (o.empty()) return;
    if (empty()) {
      *this = o;
      return;
    }
    if (o.size() != size() || o.exponent_ != exponent_) {
      throw std::invalid_argument("exact sums of different sizes or grids cannot be added");
    }
    for (size_t i = 0; i < size(); ++i) add_words(i, o.words_[2 * i], o.words_[2 * i + 1]);
  }

  // Value i (rounded to double; the same integer always gives the same double).
  // Whether every value is >= 0 (sums of splats of light are).
  bool non_negative() const {
    for (size_t i = 1; i < words_.size(); i += 2) {
      if ((words_[i] >> 63) != 0) return false;
    }
    return true;
  }

  double value(size_t i) const {
    uint64_t low = words_[2 * i], high = words_[2 * i + 1];
    const bool negative = (high >> 63) != 0;
    if (negative) {
      high = ~high + (low == 0 ? 1 : 0);
      low = ~low + 1;
    }
    const double magnitude = static_cast<double>(high) * 0x1p64 + static_cast<double>(low);
    return (negative ? -magnitude : magnitude) * from_grid_;
  }

 private:
  // A value's bound in grid units (2^62 scale or more). Sums of values near scale reach it only
  // after some 2^62 additions, so they never wrap in practice.
  static constexpr double kLimit = 0x1p126;

  void add_words(size_t i, uint64_t low, uint64_t high) {
    uint64_t& l = words_[2 * i];
    l += low;
    words_[2 * i + 1] += high + (l < low ? 1u : 0u);  // unsigned: wraps like two's complement
  }

  int exponent_ = 0;
  double to_grid_ = 1.0, from_grid_ = 1.0;
  std::vector<uint64_t> words_;
};

}  // namespace dualight
