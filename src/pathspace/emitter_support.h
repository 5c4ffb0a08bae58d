// Which emitters at infinity the estimators handle so far (issue 20). The path tracer, the light
// tracer and BDPT (so PSSMLT and MMLT, which run BDPT's strategies) take them all: light
// subpaths start at a direction at infinity and enter from the distant disk, camera subpaths
// end at the environment, and BDPT's MIS weights see the vertex at infinity. Path-space MLT's
// path evaluation and mutations do not know that vertex yet: it refuses such scenes by name
// before any work instead of rendering them without that light.
#pragma once
#include <stdexcept>
#include <string>

#include "geometry/scene.h"

namespace dualight {

// Throws std::invalid_argument naming `method` when the scene holds an emitter at infinity.
inline void refuse_emitters_at_infinity(const Scene& scene, const char* method) {
  for (const Emitter& e : scene.emitters()) {
    if (!is_infinite(e)) continue;
    throw std::invalid_argument(std::string("method '") + method + "' cannot render scenes lit by " +
                                (is_delta_direction(e) ? "a directional light" : "an environment (constant or envmap)") +
                                " yet; use 'path', 'light', 'bdpt', 'pssmlt' or 'mmlt'");
  }
}

}  // namespace dualight
