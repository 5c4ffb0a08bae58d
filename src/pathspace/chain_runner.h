// The one Markov-chain round loop of every MLT method (PSSMLT, MMLT, path-space MLT), as
// Tungsten's runSampleChain: rounds (chain_rounds.h) run every chain of a range in parallel for
// its share of mutations, each chain splatting into a list of its own; after each round the
// lists merge in chain order, so the image depends on the seed only. A method supplies what
// differs: `make_step(c, counters)` gives chain c's step for this round (its proposal and
// acceptance, with the round's workspaces), called once per mutation with the chain's splat
// list and closed by `end_round(splats)`; `merge(c, splats)` adds a chain's splats to the
// method's sums.
#pragma once
#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

#include "core/parallel.h"
#include "core/render_control.h"
#include "film/splat_list.h"
#include "pathspace/chain_rounds.h"
#include "pathspace/render_stats.h"

namespace dualight {

template <class MakeStep, class Merge>
void run_chain_rounds(int threads, size_t n_chains, ChainRounds& rounds, const std::function<double()>& elapsed,
                      RenderControl& control, SharedTraceCounters& rays, const MakeStep& make_step,
                      const Merge& merge) {
  std::vector<SplatList> splat_lists(n_chains);
  std::vector<uint64_t> done(n_chains, 0);
  while (rounds.next(elapsed(), control)) {
    parallel_for_each_index(threads, n_chains, [&](size_t c) {
      const uint64_t share = rounds.share(c);
      TraceCounters counters = rays.local();
      SplatList& splats = splat_lists[c];
      splats.clear();
      done[c] = 0;
      auto step = make_step(c, counters);
      for (uint64_t m = 0; m < share; ++m) {
        if ((m & 63u) == 0 && control.cancelled()) break;
        step(splats);
        ++done[c];
      }
      step.end_round(splats);
      rays.add(counters);
      control.done.fetch_add(done[c], std::memory_order_relaxed);
    });
    uint64_t round = 0;
    for (size_t c = 0; c < n_chains; ++c) {
      merge(c, splat_lists[c]);
      round += done[c];
    }
    if (!rounds.finish(round, elapsed(), control)) break;
  }
}

}  // namespace dualight
