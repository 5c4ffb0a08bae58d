// Multiple importance sampling weight of one BDPT strategy [Veach 1997, sec. 10.2.1-10.3.4;
// pbrt-v3 sec. 16.3.4]. For the path made of light[0..s-1] and camera[0..t-1] (with `sampled`
// standing in for light[0] when s = 1, or for camera[0] when t = 1), each other strategy's density
// relative to this one's is a product of ratios pdf_rev / pdf_fwd along the path; the weight is
// 1 / (1 + sum of h(ratio)) with h the power (squared) or balance (identity) heuristic. Only the
// four vertices at the connection need densities for this strategy; the rest are cached. With one
// strategy alone (strategies.h), the weight is 1 for the most preferred strategy that can sample
// the path and 0 for the others.
#pragma once
#include "pathspace/path.h"
#include "pathspace/strategies.h"

namespace dualight {

enum class MisHeuristic { Power, Balance };

float mis_weight(const Scene& scene, const PinholeCamera& camera, const Path& light, const Path& cam,
                 const Vertex& sampled, int s, int t, MisHeuristic heuristic,
                 Strategies strategies = Strategies::Mis);

}  // namespace dualight
