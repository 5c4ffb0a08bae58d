// How the chains of an MLT method share their mutations: in rounds, each running every chain in
// parallel for its share and then merging the chains' splats in chain order, so that an image
// depends on the seed only. Rounds last about 0.25 s (the latency of Ctrl-C and progress),
// shorter near a deadline. The first round, 4 mutations per chain, measures the speed and
// always runs: a population is never missing from an image, even when its start-up (bootstrap,
// direct light) took all the time.
#pragma once
#include <algorithm>
#include <cstdint>

#include "core/render_control.h"

namespace dualight {

class ChainRounds {
 public:
  // target: mutations in all (0: until the deadline); deadline: seconds on the caller's clock
  // (0: none).
  ChainRounds(size_t chains, uint64_t target, double deadline)
      : chains_(chains), target_(target), deadline_(deadline) {}

  // Whether another round runs, starting at `now`.
  bool next(double now, const RenderControl& control) {
    if ((target_ > 0 && total_ >= target_) || control.cancelled()) return false;
    if (deadline_ > 0.0 && total_ > 0 && now >= deadline_) {
      time_limited_ = true;
      return false;
    }
    round_start_ = now;
    return true;
  }
  // Chain c's mutations in this round: what remains split evenly, the first chains take the rest.
  uint64_t share(size_t c) const {
    if (target_ == 0) return per_chain_;
    const uint64_t remaining = target_ - total_;
    return std::min<uint64_t>(per_chain_, remaining / chains_ + (c < remaining % chains_));
  }
  // Records a round of `round` mutations ending at `now`; false when rounds should stop.
  bool finish(uint64_t round, double now, const RenderControl& control) {
    total_ += round;
    if (control.cancelled() || round == 0) return false;
    const double per_mutation = std::max(now - round_start_, 1e-6) / static_cast<double>(round);
    const double round_seconds = deadline_ > 0.0 ? std::clamp(0.5 * (deadline_ - now), 0.001, 0.25) : 0.25;
    per_chain_ = static_cast<uint64_t>(std::clamp(round_seconds / per_mutation / chains_, 1.0, 1e6));
    return true;
  }
  uint64_t total() const { return total_; }
  bool time_limited() const { return time_limited_; }

 private:
  size_t chains_;
  uint64_t target_;
  double deadline_;
  uint64_t total_ = 0, per_chain_ = 4;
  double round_start_ = 0.0;
  bool time_limited_ = false;
};

}  // namespace dualight
