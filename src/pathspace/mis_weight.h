// Multiple importance sampling weight of one BDPT strategy [Veach 1997, sec. 10.2.1-10.3.4;
// pbrt-v3 sec. 16.3.4]. For the path made of light[0..s-1] and camera[0..t-1] (with `sampled`
// standing in for light[0] when s = 1, or for camera[0] when t = 1), each other strategy's density
// relative to this one's is a product of ratios pdf_rev / pdf_fwd along the path; the weight is
// 1 / (1 + sum of h(ratio)) with h the power (squared) or balance (identity) heuristic. Only the
// four vertices at the connection need densities for this strategy; the rest are cached. Across
// a chain of delta vertices the ratio is that of the chain's true end densities (mis_weight.cpp,
// chain_correction). With one strategy alone (strategies.h), the weight is 1 for the most
// preferred strategy that can sample the path and 0 for the others. With guides (guided BDPT),
// a surface vertex's density of continuing a subpath is its guide's mixture (guided_sampling.h):
// the radiance guide's where a camera subpath continues, the importance guide's where a light
// subpath does.
#pragma once
#include "pathspace/path.h"
#include "pathspace/strategies.h"
#include "pathspace/subpath.h"

namespace dualight {

enum class MisHeuristic { Power, Balance };

// pdf_area (path.h) where a surface vertex v samples from `guide` (null: none) mixed with its
// BSDF, as a guided walk there does (subpath.h): the leaf at v.p, its BSDF fraction.
float pdf_area(const PinholeCamera& camera, const Vertex& v, const Vertex* prev, const Vertex& next,
               const SdTree* guide);

// Caches on every surface vertex of a subpath walked with `guides` both guides at it and the
// reverse direction's guide's density towards the previous vertex (Vertex::guides_set), as
// mis_weight would compute them: the weights are the same, bit for bit, with fewer tree lookups.
// `mode`: the subpath's (Radiance: a camera subpath).
void set_vertex_guides(Path& path, const SubpathGuides& guides, TransportMode mode);

float mis_weight(const Scene& scene, const PinholeCamera& camera, const Path& light, const Path& cam,
                 const Vertex& sampled, int s, int t, MisHeuristic heuristic,
                 Strategies strategies = Strategies::Mis, const SubpathGuides* guides = nullptr);

}  // namespace dualight
