// Hamilton's largest-remainder apportionment: `total` whole units (chains, mutations) split in
// proportion to non-negative weights so that the parts sum to `total` exactly. Each positive
// weight gets at least `minimum` units (a population with light needs a chain); only when the
// minimums alone exceed `total` do the parts sum to more. Rounding each share on its own
// (llround) gave multiplexed MLT 39 chains when 40 were asked for (issue 18).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace dualight {

inline std::vector<uint64_t> apportion(uint64_t total, const std::vector<double>& weights, uint64_t minimum) {
  double sum = 0.0;
  for (const double w : weights) sum += w > 0.0 ? w : 0.0;
  std::vector<double> quota(weights.size(), 0.0);
  std::vector<uint64_t> part(weights.size(), 0);
  uint64_t given = 0;
  for (size_t i = 0; i < weights.size(); ++i) {
    if (!(weights[i] > 0.0)) continue;
    quota[i] = static_cast<double>(total) * (weights[i] / sum);
    part[i] = std::max<uint64_t>(minimum, static_cast<uint64_t>(std::floor(quota[i])));
    given += part[i];
  }
  // Units left over go to the largest remainders; units over (from the minimums) come back from
  // the parts most above their quota. Each loop runs at most once per weight.
  const auto pick = [&](bool give) {
    size_t best = weights.size();
    for (size_t i = 0; i < weights.size(); ++i) {
      if (!(weights[i] > 0.0) || (!give && part[i] <= minimum)) continue;
      const double rest = quota[i] - static_cast<double>(part[i]);
      if (best == weights.size() || (give ? rest > quota[best] - static_cast<double>(part[best])
                                          : rest < quota[best] - static_cast<double>(part[best]))) {
        best = i;
      }
    }
    return best;
  };
  while (given < total) {
    const size_t i = pick(true);
    if (i == weights.size()) break;
    ++part[i];
    ++given;
  }
  while (given > total) {
    const size_t i = pick(false);
    if (i == weights.size()) break;
    --part[i];
    --given;
  }
  return part;
}

}  // namespace dualight
