// Discrete distribution over weighted items, sampled by inverting its CDF. The search starts from
// a guide table (the cutpoint method of Chen and Asau 1974; Devroye 1986, sec. III.2.4): for each
// of G equal slices of [0, 1), where the search's answer for the slice's start lies, so a sample
// searches only between its slice's two entries (about one item on average) and finds what a
// search of the whole CDF would.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace dualight {

class DiscreteDistribution {
 public:
  DiscreteDistribution() = default;
  explicit DiscreteDistribution(const std::vector<double>& weights) {
    cdf_.reserve(weights.size() + 1);
    cdf_.push_back(0.0);
    for (const double w : weights) {
      if (!(w >= 0.0)) throw std::invalid_argument("distribution weight must be >= 0");
      cdf_.push_back(cdf_.back() + w);
    }
    total_ = cdf_.back();
    if (!(total_ > 0.0)) throw std::invalid_argument("distribution has zero total weight");
    for (double& c : cdf_) c /= total_;
    build_guide();
  }

  size_t size() const { return cdf_.empty() ? 0 : cdf_.size() - 1; }
  double total() const { return total_; }
  float pmf(size_t i) const { return static_cast<float>(cdf_[i + 1] - cdf_[i]); }

  // The floats sample() compares u against: the smallest float at or past each item's end
  // (cdf_[1..size()], rounded up), so that sample(u) picks min(#{k : u >= ends[k]}, size() - 1)
  // (for lanes: the same choice in float comparisons, without a search).
  std::vector<float> float_item_ends() const {
    std::vector<float> ends;
    for (size_t k = 1; k < cdf_.size(); ++k) {
      float f = static_cast<float>(cdf_[k]);
      if (static_cast<double>(f) < cdf_[k]) f = std::nextafter(f, 2.f);
      ends.push_back(f);
    }
    return ends;
  }

  // Returns the item index and rescales u to [0, 1) within the chosen item for reuse.
  size_t sample(float& u) const {
    const size_t i = std::min<size_t>(static_cast<size_t>(search(static_cast<double>(u)) - cdf_.begin()) - 1,
                                      size() - 1);
    const double width = cdf_[i + 1] - cdf_[i];
    u = width > 0 ? static_cast<float>(std::min((u - cdf_[i]) / width, 0.99999994)) : 0.f;
    return i;
  }

 private:
  using Position = std::vector<double>::const_iterator;

  // The first CDF entry past the start (cdf_[1..]) above u, as std::upper_bound finds it: within
  // the guide's bracket of u's slice where u is in [0, 1) (the answer grows with u, and slice j
  // starts at j / G exactly, G being a power of two), else over the whole CDF.
  Position search(double u) const {
    const double x = u * static_cast<double>(guide_slices_);
    if (!(u >= 0.0) || !(x < static_cast<double>(guide_slices_))) {
      return std::upper_bound(cdf_.begin() + 1, cdf_.end(), u);
    }
    const auto j = static_cast<size_t>(x);
    return std::upper_bound(cdf_.begin() + guide_[j], cdf_.begin() + guide_[j + 1], u);
  }

  // guide_[j] = search's answer (an index into cdf_) for u = j / G, j = 0 .. G, G the power of two
  // at or above the item count (at most 2^16): under twice as many 4-byte entries as items, so
  // at most the CDF's own memory. Half as many slices cost the environment-map box 2 % of its
  // samples per second.
  void build_guide() {
    guide_slices_ = 1;
    while (guide_slices_ < size() && guide_slices_ < (size_t{1} << 16)) guide_slices_ *= 2;
    guide_.resize(guide_slices_ + 1);
    size_t k = 1;
    for (size_t j = 0; j <= guide_slices_; ++j) {
      const double start = static_cast<double>(j) / static_cast<double>(guide_slices_);
      while (k < cdf_.size() && !(start < cdf_[k])) ++k;
      guide_[j] = static_cast<uint32_t>(k);
    }
  }

  std::vector<double> cdf_;
  double total_ = 0.0;
  size_t guide_slices_ = 0;
  std::vector<uint32_t> guide_;
};

}  // namespace dualight
