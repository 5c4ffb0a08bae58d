// Test hooks for path-space MLT's bootstrap (mlt_bootstrap.h): the complete path of every
// strategy of its BDPT samples, and their contributions recomputed from those paths alone. Not
// part of the product: dualight._testing binds check_bootstrap_paths as check_mlt_bootstrap_paths
// (bind_mlt.cpp); mlt_checks.cpp draws its start paths from bootstrap_paths.
#pragma once
#include <cstddef>
#include <vector>

#include "pathspace/mlt.h"
#include "pathspace/path.h"

namespace dualight {

// Every strategy of `count` bootstrap BDPT samples, its unweighted estimate's luminance as BDPT
// computed it, and the same recomputed from the strategy's complete path as f*(z) / p_{s,t}(z)
// with full_path.h's contribution and densities (equal without Russian roulette).
struct StrategyCheck {
  int s = 0, t = 0;
  double bdpt = 0.0, recomputed = 0.0;
};
std::vector<StrategyCheck> check_bootstrap_paths(const Scene& scene, const PinholeCamera& camera,
                                                 const MltOptions& options, size_t count);

// The complete paths of every strategy that carries light in `count` bootstrap samples (the
// chains' start candidates, not resampled).
std::vector<Path> bootstrap_paths(const Scene& scene, const PinholeCamera& camera, const MltOptions& options,
                                  size_t count);

}  // namespace dualight
