// How the chains of an MLT method share their mutations: in rounds, each running every chain in
// parallel for its share and then merging the chains' splats (exact sums: the image depends on
// the seed only, not on the rounds). Rounds last about 0.25 s (the latency of Ctrl-C and progress),
// shorter near a deadline. The first round, 4 mutations per chain, measures the speed and
// always runs: a population is never missing from an image, even when its start-up (bootstrap,
// direct light) took all the time.
#pragma once
#include <algorithm>
#include <cstdint>

#include "core/render_control.h"

namespace dualight {

// Chain c's mutations in all, of a population's target: split evenly, the first chains take the
// rest. Fixed by the chain's index, so any range of chains run apart does the same work.
inline uint64_t chain_quota(uint64_t target, uint64_t chains, uint64_t c) {
  return target / chains + (c < target % chains ? 1 : 0);
}

class ChainRounds {
 public:
  // Chains [first, first + count) of a population of `chains` that share `target` mutations
  // (0: until the deadline); deadline: seconds on the caller's clock (0: none). Chain c's
  // mutations in all are its chain_quota whichever range runs it.
  ChainRounds(uint64_t chains, uint64_t first, uint64_t count, uint64_t target, double deadline)
      : chains_(chains), first_(first), count_(count), target_(target), deadline_(deadline) {}

  // Whether another round runs, starting at `now`.
  bool next(double now, const RenderControl& control) {
    if (count_ == 0 || (target_ > 0 && given_ >= chain_quota(target_, chains_, first_)) || control.cancelled()) {
      return false;
    }
    if (deadline_ > 0.0 && total_ > 0 && now >= deadline_) {
      time_limited_ = true;
      return false;
    }
    round_start_ = now;
    return true;
  }
  // The mutations of the range's chain i in this round: per_chain_, less at the end of its quota.
  uint64_t share(size_t i) const {
    if (target_ == 0) return per_chain_;
    const uint64_t quota = chain_quota(target_, chains_, first_ + i);
    return std::min(quota, given_ + per_chain_) - std::min(quota, given_);
  }
  // The range's mutations in all (0: until the deadline).
  uint64_t range_target() const {
    uint64_t sum = 0;
    for (uint64_t i = 0; i < count_ && target_ > 0; ++i) sum += chain_quota(target_, chains_, first_ + i);
    return sum;
  }
  // Records a round of `round` mutations ending at `now`; false when rounds should stop.
  bool finish(uint64_t round, double now, const RenderControl& control) {
    total_ += round;
    given_ += per_chain_;
    if (control.cancelled() || round == 0) return false;
    const double per_mutation = std::max(now - round_start_, 1e-6) / static_cast<double>(round);
    const double round_seconds = deadline_ > 0.0 ? std::clamp(0.5 * (deadline_ - now), 0.001, 0.25) : 0.25;
    per_chain_ = static_cast<uint64_t>(
        std::clamp(round_seconds / per_mutation / static_cast<double>(count_), 1.0, 1e6));
    return true;
  }
  uint64_t total() const { return total_; }
  bool time_limited() const { return time_limited_; }

 private:
  uint64_t chains_, first_, count_, target_;
  double deadline_;
  uint64_t total_ = 0, given_ = 0, per_chain_ = 4;
  double round_start_ = 0.0;
  bool time_limited_ = false;
};

}  // namespace dualight
