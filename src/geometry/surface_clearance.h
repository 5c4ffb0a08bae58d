// How far a triangle stands from the surfaces that could hide a point on it: a lower bound on
// the distance from the triangle to every other triangle of the scene, leaving out those
// coplanar with it (its neighbours in one flat light, say). Scene::visible uses it to trace a
// shadow ray without a per-hit callback: short of its end by less than this, no surface but the
// target's own can lie on the rest of the segment.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace dualight {

class Scene;

// Triangles `parallel` (the normals' |cos| test of Scene::visible's filter, in float, as it) and
// within this of the target's plane, relative to max(1, the target's smallest coordinate
// magnitude), count as coplanar: a tenth of the filter's tolerance, so the filter surely ignores
// every hit on them near the target.
inline constexpr double kCoplanarSlack = 1e-6;

// Per triangle: 0 (unknown, or touching another surface) or a lower bound on its distance to
// every triangle not coplanar with it (kCoplanarSlack), for the emitters' triangles, which
// shadow rays aim at. A scene with more than `max_pairs` (emitter triangle, triangle) pairs gets
// zeros: the bound is then not worth its O(pairs) cost at construction.
std::vector<float> emitter_clearances(const Scene& scene, uint64_t max_pairs = uint64_t{1} << 24);

}  // namespace dualight
