// Primary-sample-space chains' states (PSSMLT and MMLT): what one evaluation of the primary
// samples contributes to the film.
#pragma once
#include <vector>

#include "film/splat_list.h"
#include "pathspace/direct_light.h"
#include "pathspace/pssmlt.h"

namespace dualight {

// What one evaluation contributes to the film: the own pixel's value scaled by the pixel count
// (the film position is uniform over the film) and the light-tracing splats; f is their total
// luminance.
struct Contribution {
  std::vector<Splat> splats;
  float f = 0.f;
};

}  // namespace dualight
