// Path-space MLT's bootstrap samples [Veach 1997, sec. 11.3.1]: BDPT samples at uniform film
// positions whose strategies' MIS-weighted contributions estimate b = the integral of f* and from
// whose complete paths the chains start. Shared by the renderer (mlt.cpp) and the checks that
// recompute the strategies' paths (tests/hooks).
#pragma once
#include <cstdint>

#include "core/sampler.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/direct_light.h"
#include "pathspace/mis_weight.h"
#include "pathspace/mlt.h"
#include "pathspace/subpath.h"

namespace dualight {

// One BDPT sample of the bootstrap (a uniform film position, every strategy); calls
// visit(s, t, unweighted, mis weight, sampled, raster) for each strategy that carries light.
// Values of strategies with t >= 2 are scaled by the pixel count: they estimate the whole
// film's integral.
template <class Visit>
void bootstrap_sample(const Scene& scene, const PinholeCamera& camera, const BdptOptions& bdpt, uint64_t seed,
                      uint64_t index, Subpaths& paths, TraceCounters& counters, const Visit& visit) {
  IndependentSampler sampler(seed, index, 0);
  const Point2 film = camera.film_position(sampler.next_2d());
  const WalkLimits limits{bdpt.max_depth, bdpt.rr_depth};
  camera_subpath(scene, camera, film.u, film.v, sampler, limits, paths.camera, counters);
  light_subpath(scene, sampler, limits, paths.light, counters);
  const float pixels = static_cast<float>(camera.width()) * static_cast<float>(camera.height());
  for_each_strategy(scene, camera, bdpt, paths, sampler, counters,
                    [&](int s, int t, Color c, const Vertex& sampled, const Point2& raster) {
                      if (t >= 2) c *= pixels;
                      visit(s, t, c, mis_weight(scene, camera, paths.light, paths.camera, sampled, s, t, bdpt.heuristic),
                            sampled, t == 1 ? raster : film);
                    });
}

// The complete path (emitter first) that strategy (s, t) made.
inline Path strategy_path(const Subpaths& paths, const Vertex& sampled, int s, int t) {
  Path z;
  if (s == 1) {
    z.push_back(sampled);
  } else {
    z.assign(paths.light.begin(), paths.light.begin() + s);
  }
  if (t == 1) {
    z.push_back(sampled);  // the camera vertex
  } else {
    for (int i = t - 1; i >= 0; --i) z.push_back(paths.camera[i]);
  }
  z.front().type = VertexType::Light;
  return z;
}

}  // namespace dualight
