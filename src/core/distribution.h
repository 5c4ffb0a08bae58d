// Discrete distribution over weighted items, sampled by inverting its CDF.
#pragma once
#include <algorithm>
#include <cmath>
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
    const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), static_cast<double>(u));
    const size_t i = std::min<size_t>(static_cast<size_t>(it - cdf_.begin()) - 1, size() - 1);
    const double width = cdf_[i + 1] - cdf_[i];
    u = width > 0 ? static_cast<float>(std::min((u - cdf_[i]) / width, 0.99999994)) : 0.f;
    return i;
  }

 private:
  std::vector<double> cdf_;
  double total_ = 0.0;
};

}  // namespace dualight
