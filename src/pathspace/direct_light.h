// Emitters seen directly and direct light (paths of 1 and 2 segments) by BDPT, for the MLT
// methods that leave them out of their chains (Veach's thesis sec. 11.4.2; Mitsuba's
// `directSamples`): BDPT renders them well, and in a chain they would take most mutations.
#pragma once
#include <algorithm>

#include "pathspace/bdpt.h"

namespace dualight {

// BDPT as the MLT methods' chains and bootstraps evaluate it (PssmltOptions or MltOptions): the
// render's depths and heuristic, without the paths of 1 and 2 segments when render_direct_light
// renders them apart (direct_spp > 0).
template <class ChainOptions>
BdptOptions chain_bdpt(const ChainOptions& opt) {
  BdptOptions bdpt;
  bdpt.max_depth = opt.max_depth;
  bdpt.rr_depth = opt.rr_depth;
  bdpt.heuristic = opt.heuristic;
  bdpt.min_depth = opt.direct_spp > 0 ? 3 : 1;
  bdpt.light_pool = 1;  // a chain's sample is its own subpaths' strategies
  return bdpt;
}

// At most `spp` samples per pixel; with time_limit > 0 (seconds), fewer if that runs out first.
inline RenderResult render_direct_light(const Scene& scene, const PinholeCamera& camera, const EstimatorOptions& base,
                                        uint32_t spp, MisHeuristic heuristic, RenderControl& control,
                                        double time_limit = 0.0) {
  BdptOptions direct;
  static_cast<EstimatorOptions&>(direct) = base;
  direct.spp = spp;
  direct.time_limit = time_limit;
  direct.max_depth = base.max_depth < 0 ? 2 : std::min(base.max_depth, 2);
  direct.heuristic = heuristic;
  direct.seed = hash_combine(base.seed, 0xd1ec7ull);
  direct.light_pool = 1;  // paths of 2 segments join no light vertex to a camera vertex (s, t >= 2)
  RenderResult result = render_bdpt(scene, camera, direct, control);
  control.done.store(0);
  return result;
}

}  // namespace dualight
