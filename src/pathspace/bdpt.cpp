#include "pathspace/bdpt.h"

#include <tbb/enumerable_thread_specific.h>

#include <stdexcept>

#include "pathspace/bdpt_sample.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/shadow_ray.h"

namespace dualight {

std::vector<std::pair<int, int>> bdpt_strategies(int max_depth) {
  std::vector<std::pair<int, int>> out;
  for (int d = 1; d <= max_depth; ++d) {
    for (int t = 1; t <= d + 1; ++t) out.emplace_back(d + 1 - t, t);
  }
  return out;
}

RenderResult render_bdpt(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                         RenderControl& control) {
  if (options.strategy_images && options.max_depth < 0) {
    throw std::invalid_argument("strategy images need a bounded max_depth");
  }
  RenderResult result{Film(camera.width(), camera.height()), {}};
  if (options.strategy_images) result.film.add_layers(bdpt_strategies(options.max_depth).size());
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, true,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  tbb::enumerable_thread_specific<Subpaths> workspaces;
  const auto estimate = [&](float x, float y, auto& sampler, TraceCounters& counters, SplatList& splats) {
    return bdpt_sample(scene, camera, options, x, y, sampler, workspaces.local(), counters, splats, &result.film);
  };
  result.stats = with_sampler(options.sampler, [&](auto tag) {
    return drive_pixels<typename decltype(tag)::type>(result.film, driver, control, estimate);
  });
  return result;
}

}  // namespace dualight
