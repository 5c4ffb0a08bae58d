// Which emitters at infinity the estimators built on light subpaths handle so far (issue 20).
// The light tracer starts subpaths from a directional light's disk (lights/directional_emitter.h);
// subpaths from environments (constant, envmap) and BDPT's vertex at infinity, which its MIS
// weights need for every emitter there, are not built yet: those estimators refuse the scene by
// name before any work instead of rendering it without that light.
#pragma once
#include <stdexcept>
#include <string>

#include "geometry/scene.h"

namespace dualight {

// Throws std::invalid_argument naming `method` when it cannot render the scene's emitters;
// `directional`: whether it takes directional lights.
inline void require_light_subpaths(const Scene& scene, const char* method, bool directional) {
  for (const Emitter& e : scene.emitters()) {
    if (!is_infinite(e) || (directional && is_delta_direction(e))) continue;
    throw std::invalid_argument(std::string("method '") + method + "' cannot render scenes lit by " +
                                (is_delta_direction(e) ? "a directional light" : "an environment (constant or envmap)") +
                                " yet; use method='path'" + (directional ? "" : " (or 'light' for directional lights)"));
  }
}

}  // namespace dualight
