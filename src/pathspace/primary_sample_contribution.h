// Primary-sample-space chains' states (PSSMLT and MMLT): what one evaluation of the primary
// samples contributes to the film, and the BDPT settings the chains' evaluations use.
#pragma once
#include <vector>

#include "film/splat_list.h"
#include "pathspace/bdpt.h"
#include "pathspace/pssmlt.h"

namespace dualight {

// What one evaluation contributes to the film: the own pixel's value scaled by the pixel count
// (the film position is uniform over the film) and the light-tracing splats; f is their total
// luminance.
struct Contribution {
  std::vector<Splat> splats;
  float f = 0.f;
};

// BDPT as the chains evaluate it: the render's depths and heuristic, and without the paths of 1
// and 2 segments when the direct light is rendered apart.
inline BdptOptions chain_bdpt(const PssmltOptions& opt) {
  BdptOptions bdpt;
  bdpt.max_depth = opt.max_depth;
  bdpt.rr_depth = opt.rr_depth;
  bdpt.heuristic = opt.heuristic;
  bdpt.min_depth = opt.direct_spp > 0 ? 3 : 1;
  return bdpt;
}

}  // namespace dualight
