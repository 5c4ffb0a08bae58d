#include "pathspace/bdpt.h"

#include <tbb/enumerable_thread_specific.h>

#include <stdexcept>

#include "pathspace/connect.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/subpath.h"

namespace dualight {

namespace {

// Layer of strategy (s, t): depth d = s + t - 1 has d + 1 strategies (t = 1 .. d + 1).
size_t strategy_layer(int s, int t) {
  const int d = s + t - 1;
  return static_cast<size_t>((d - 1) * (d + 2) / 2 + (t - 1));
}

struct Subpaths {
  Path camera, light;
};

template <class Sampler>
Color bdpt_sample(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt, float x, float y,
                  Sampler& sampler, Subpaths& paths, TraceCounters& counters, SplatList& splats, Film& film) {
  const WalkLimits limits{opt.max_depth, opt.rr_depth};
  camera_subpath(scene, camera, x, y, sampler, limits, paths.camera, counters);
  light_subpath(scene, sampler, limits, paths.light, counters);
  const Path& cam = paths.camera;
  const Path& light = paths.light;
  const size_t pixel = static_cast<size_t>(y) * camera.width() + static_cast<size_t>(x);

  Color L(0.f);
  for (int t = 1; t <= static_cast<int>(cam.size()); ++t) {
    for (int s = 0; s <= static_cast<int>(light.size()); ++s) {
      const int depth = s + t - 1;
      if (depth < 1 || (opt.max_depth >= 0 && depth > opt.max_depth)) continue;
      if (s == 1 && t == 1) continue;  // the same paths as (0, 2), which keeps them all
      Vertex sampled;
      Point2 raster{};
      Color c = connect(scene, camera, light, cam, s, t, sampler, sampled, raster, counters);
      if (is_black(c)) continue;
      c *= mis_weight(scene, camera, light, cam, sampled, s, t, opt.heuristic);
      if (t == 1) {
        const uint32_t target = static_cast<uint32_t>(raster.v) * camera.width() + static_cast<uint32_t>(raster.u);
        splats.add(target, c);
        if (opt.strategy_images) splats.add(target, c, static_cast<uint32_t>(strategy_layer(s, t) + 1));
      } else {
        L += c;
        if (opt.strategy_images && is_finite(c)) film.add_layer_sample(strategy_layer(s, t), pixel, c);
      }
    }
  }
  return L;
}

}  // namespace

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
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, true};
  tbb::enumerable_thread_specific<Subpaths> workspaces;
  const auto estimate = [&](float x, float y, auto& sampler, TraceCounters& counters, SplatList& splats) {
    return bdpt_sample(scene, camera, options, x, y, sampler, workspaces.local(), counters, splats, result.film);
  };
  result.stats = with_sampler(options.sampler, [&](auto tag) {
    return drive_pixels<typename decltype(tag)::type>(result.film, driver, control, estimate);
  });
  return result;
}

}  // namespace dualight
