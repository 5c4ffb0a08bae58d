// Multiplexed Metropolis light transport [Hachisuka, Kaplanyan and Dachsbacher 2014]: the
// primary-sample chains of PSSMLT (pssmlt.h, with PssmltOptions::multiplexed), one population
// per path length d, whose state's first number also picks one BDPT strategy (s, t) of paths
// of d segments. Each evaluation is that strategy's MIS-weighted contribution divided by its
// selection probability 1 / (number of strategies), so the chains' mutations move between
// strategies as well as paths, and spend no time on strategies that contribute little. The
// populations' chains, mutations and time are allocated in pssmlt.cpp in proportion to each
// length's bootstrap b_d. In a scene lit only by delta lights (with skip_unneeded) the
// strategies s = 0, which find nothing there, are not offered: each evaluation picks among
// the others, and paths of one segment (only (0, 2)) contribute nothing.
#pragma once
#include <cstdint>

#include "core/primary_sample_sampler.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/primary_sample_contribution.h"

namespace dualight {

// Evaluates primary samples as one strategy of the paths of `depth` segments (depth >= 1).
class StrategyEvaluator {
 public:
  StrategyEvaluator(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt, int depth)
      : scene_(scene),
        camera_(camera),
        depth_(depth),
        bdpt_(chain_bdpt(opt)),
        s_first_(opt.skip_unneeded && !scene.has_hittable_emitter() ? 1 : 0) {}

  void operator()(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters);
  uint64_t invalid() const { return invalid_; }

 private:
  const Scene& scene_;
  const PinholeCamera& camera_;
  int depth_;
  BdptOptions bdpt_;
  int s_first_;  // 1: no strategy with s = 0 (no emitter a path can hit)
  Subpaths paths_;
  uint64_t invalid_ = 0;
};

}  // namespace dualight
