// Radiosity's precondition: B = E + rho F B holds for diffuse reflectors only (outgoing
// radiance independent of direction) [Cohen and Wallace 1993, ch. 2]. Solvers that take a Scene
// check it by the BSDFs' flags and refuse anything else with a clear error, so a mirror or glass
// is never silently solved as something else.
#pragma once
#include <stdexcept>
#include <string>

#include "geometry/scene.h"

namespace dualight {

// Throws std::invalid_argument naming `who` and the emitters that are not on a surface, for
// solvers that take emission from the patches alone (a point light has no patch to emit from:
// its first shot is radiosity/direct_irradiance.h's).
inline void require_surface_emitters(const Scene& scene, const char* who) {
  const uint64_t off_surfaces = scene.emitter_count() - scene.features().emitter_triangles;
  if (off_surfaces > 0) {
    throw std::invalid_argument(std::string(who) + " solves emission from surfaces only: the scene has " +
                                std::to_string(off_surfaces) + " emitter(s) off its surfaces");
  }
}

// Throws std::invalid_argument naming `who` and the first triangle whose BSDF is not a diffuse
// reflector.
inline void require_diffuse_reflectors(const Scene& scene, const char* who) {
  if (scene.features().all_diffuse()) return;
  for (uint32_t prim = 0; prim < scene.triangle_count(); ++prim) {
    const BsdfFlags f = flags(scene.material(prim).bsdf);
    if (is_diffuse_reflector(f)) continue;
    const char* what = has_transmission(f) ? "transmits light" : (has_specular(f) ? "is specular" : "is glossy");
    throw std::invalid_argument(std::string(who) + " needs diffuse reflectors only: the BSDF of triangle " +
                                std::to_string(prim) + " " + what + " (use an image estimator for it)");
  }
}

}  // namespace dualight
