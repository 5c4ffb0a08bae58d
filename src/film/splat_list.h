// Contributions of light paths to arbitrary pixels, collected by one task and added to the film
// later in a fixed order, so images do not depend on the schedule. Between begin_path() and
// end_path() one light path adds its splats; end_path() merges the ones that hit the same pixel,
// since the film's variance needs each path's total per pixel, not its pieces.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace dualight {

struct Splat {
  uint32_t pixel;
  uint32_t layer;  // 0: the image; k > 0: the film's extra layer k - 1 (e.g. a BDPT strategy)
  Color value;
};

class SplatList {
 public:
  void begin_path() { path_begin_ = splats_.size(); }
  // Non-finite values are dropped and counted (as the pixel driver does with samples).
  void add(uint32_t pixel, const Color& value, uint32_t layer = 0) {
    if (is_finite(value)) {
      splats_.push_back({pixel, layer, value});
    } else {
      ++invalid_;
    }
  }
  uint64_t invalid() const { return invalid_; }
  void end_path() {
    const auto first = splats_.begin() + static_cast<std::ptrdiff_t>(path_begin_);
    if (splats_.end() - first < 2) return;
    const auto key = [](const Splat& s) { return (static_cast<uint64_t>(s.layer) << 32) | s.pixel; };
    std::sort(first, splats_.end(), [&](const Splat& a, const Splat& b) { return key(a) < key(b); });
    auto out = first;
    for (auto it = first + 1; it != splats_.end(); ++it) {
      if (key(*it) == key(*out)) {
        out->value += it->value;
      } else {
        *++out = *it;
      }
    }
    splats_.erase(out + 1, splats_.end());
  }
  void clear() {
    splats_.clear();
    path_begin_ = 0;
    invalid_ = 0;
  }
  const std::vector<Splat>& splats() const { return splats_; }

 private:
  std::vector<Splat> splats_;
  size_t path_begin_ = 0;
  uint64_t invalid_ = 0;
};

}  // namespace dualight
