// Russian roulette [Arvo and Kirk 1990; pbrt-v4, sec. 14.2]: a path goes on with probability
// q = min(max channel of its throughput, 0.95) and its throughput is divided by q, so the estimate
// stays unbiased and a path's weight stays near 1. The throughput it plays on is the path's times
// a roulette scale that takes out two factors which say nothing about what the path will carry:
// - Refraction (BsdfSample::eta): a camera path's throughput carries 1 / eta^2 across each
//   refraction, which its exit undoes; the roulette plays on it times eta^2, as Mitsuba 3's and
//   pbrt-v4's do. Caustic box, 64x64, max_depth 8, 256 spp, 4 seeds, relMSE x spp with
//   independent samplers against the reference: 10.6 without the factor, Mitsuba 3's path 6.9;
//   without any roulette 5.7 and 5.2.
// - Guiding (guided_sampling.h, sample_guided's bsdf_ratio): a direction the guide favours has a
//   high density, so a low weight; a roulette on it would stop such paths in proportion to their
//   density, undoing the guide past rr_depth. It plays on the throughput BSDF sampling alone would
//   have had. On Veach's door (guided path tracing without adjoint roulette, 1024 spp after 511 of
//   training, relMSE x spp over 3 seeds) this took the guided render from 178 to 146, unguided 226.
#pragma once
#include <algorithm>

#include "core/vec3.h"
#include "materials/bsdf_sample.h"

namespace dualight {

// The factor a sampled direction adds to a path's roulette scale: its refraction's eta^2 where the
// path carries radiance, times the guide's bsdf_ratio (1 unguided).
inline float roulette_scale(const BsdfSample& bs, TransportMode mode, float bsdf_ratio) {
  return mode == TransportMode::Radiance ? bs.eta * bs.eta * bsdf_ratio : bsdf_ratio;
}

// The probability of going on for a path of throughput `beta` and roulette scale `scale`.
inline float roulette_survival(const Color& beta, float scale = 1.f) {
  return std::min(max_component(beta) * scale, 0.95f);
}

}  // namespace dualight
