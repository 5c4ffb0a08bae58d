// What BSDF sampling returns, and what a Dirac (specular) lobe is between two given
// directions, shared by every BSDF's own file.
#pragma once
#include "core/vec3.h"

namespace dualight {

enum class TransportMode { Radiance, Importance };

struct BsdfSample {
  Vec3 wi;
  Color weight;        // f * |cos(wi)| / pdf_w
  float pdf_w = 0.f;   // solid-angle density, or the lobe's probability when `delta`
  bool delta = false;  // wi is a Dirac direction: no other strategy can generate it
  // A refraction's relative index of refraction, IOR on wi's side over wo's (its Radiance weight
  // carries 1 / eta^2); 1 for a reflection. Russian roulette undoes that factor (russian_roulette.h).
  float eta = 1.f;
};

// The Dirac lobe of a BSDF that joins wo (the camera side) and wi (the light side), for
// path-space MLT (full_path.h): its coefficient in Radiance form (the BSDF is coef * delta in
// projected solid angle), the probability that sampling picks it (the same from either side),
// and the ratio of its Radiance to Importance forms (1 for reflection, (eta_eye / eta_light)^2
// for refraction). coef 0 and prob 0 when no Dirac lobe joins the two directions.
struct DeltaLobe {
  Color coef;
  float prob = 0.f;
  float importance_ratio = 1.f;
  bool refraction = false;
};

}  // namespace dualight
