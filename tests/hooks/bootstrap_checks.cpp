// The bootstrap checks of bootstrap_checks.h, over mlt_bootstrap.h's samples and full_path.h's densities.
#include "hooks/bootstrap_checks.h"

#include "pathspace/full_path.h"
#include "pathspace/mlt_bootstrap.h"

namespace dualight {

namespace {

// Every strategy's complete path of the first `count` bootstrap samples: visit(s, t, unweighted
// contribution, path).
template <class Visit>
void for_each_bootstrap_path(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt, size_t count,
                             const Visit& visit) {
  const BdptOptions bdpt = chain_bdpt(opt);
  Subpaths paths;
  TraceCounters counters;
  for (size_t i = 0; i < count; ++i) {
    bootstrap_sample(scene, camera, bdpt, opt.seed, i, paths, counters,
                     [&](int s, int t, const Color& c, float, const Vertex& sampled, const Point2&) {
                       visit(s, t, c, strategy_path(paths, sampled, s, t));
                     });
  }
}

}  // namespace

std::vector<StrategyCheck> check_bootstrap_paths(const Scene& scene, const PinholeCamera& camera,
                                                 const MltOptions& opt, size_t count) {
  std::vector<StrategyCheck> checks;
  for_each_bootstrap_path(scene, camera, opt, count, [&](int s, int t, const Color& c, const Path& z) {
    Point2 raster{};
    const PathValue f = path_contribution(camera, z, raster);
    double p = 1.0;
    for (int v = 0; v < s; ++v) p *= pdf_from_light(scene, z, static_cast<size_t>(v));
    for (size_t v = static_cast<size_t>(s); v + 1 < z.size(); ++v) p *= pdf_from_eye(camera, z, v);
    checks.push_back({s, t, static_cast<double>(luminance(c)), f.f_lum / p});
  });
  return checks;
}

std::vector<Path> bootstrap_paths(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                                  size_t count) {
  std::vector<Path> out;
  for_each_bootstrap_path(scene, camera, opt, count, [&](int, int, const Color& c, const Path& z) {
    if (luminance(c) > 0.f) out.push_back(z);
  });
  return out;
}

}  // namespace dualight
