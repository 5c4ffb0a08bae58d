#include "pathspace/bdpt.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "core/rng.h"
#include "guiding/guide_training.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/light_tracer.h"
#include "pathspace/path_tracer.h"
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

namespace {

RenderStats drive_bdpt(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                       RenderControl& control, Film& film, const SubpathGuides& guides) {
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, true,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  tbb::enumerable_thread_specific<Subpaths> workspaces;
  const auto estimate = [&](float x, float y, auto& sampler, TraceCounters& counters, SplatList& splats) {
    return bdpt_sample(scene, camera, options, x, y, sampler, workspaces.local(), counters, splats, &film, guides);
  };
  return with_sampler(options.sampler, [&](auto tag) {
    return drive_pixels<typename decltype(tag)::type>(film, driver, control, estimate);
  });
}

// A guide's training options from BDPT's: the same budget, depths and threads, half the training
// share (two guides share it), on their own seeds. Their samples are the path and light
// tracers', not BDPT's: the image keeps none. BDPT plays no adjoint-driven roulette, and its
// radiance guide is trained without it, as before (not measured with it).
template <class Options>
Options guide_training_options(const BdptOptions& bdpt, uint64_t seed) {
  Options o;
  static_cast<EstimatorOptions&>(o) = bdpt;
  static_cast<GuidingOptions&>(o) = bdpt;
  o.guide_training = 0.5f * bdpt.guide_training;
  o.guide_keep_iterations = 0;
  o.guide_adjoint_roulette = false;
  o.seed = seed;
  return o;
}

// Trains the radiance guide (camera paths) and then the importance guide (light paths), renders
// the image with both, and adds both trainings' stats. Interrupted during training, the last
// finished training iteration's image is returned (a path- or light-traced image: unbiased).
RenderResult render_bdpt_guided(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                                RenderControl& control, Film film) {
  TrainedGuide radiance = train_radiance_guide(
      scene, camera, guide_training_options<PathTracerOptions>(options, options.seed), control);
  TrainedGuide importance;
  if (!control.cancelled()) {
    importance = train_importance_guide(
        scene, camera, guide_training_options<LightTracerOptions>(options, hash_combine(options.seed, 0x6c74ull)),
        control);
  }
  if (control.cancelled()) {
    TrainedGuide& last = importance.last_image ? importance : radiance;
    RenderResult r = last_training_image(last, camera.width(), camera.height());
    add_guiding_stats(r.stats, radiance, importance);
    return r;
  }
  BdptOptions final_options = options;
  if (options.time_limit > 0.0) {
    const double training = radiance.stats.training_seconds + importance.stats.training_seconds;
    final_options.time_limit = std::max(1e-3, options.time_limit - training);
  }
  RenderResult result{std::move(film), {}};
  result.stats = drive_bdpt(scene, camera, final_options, control, result.film,
                            {radiance.tree.get(), importance.tree.get()});
  add_guiding_stats(result.stats, radiance, importance);
  return result;
}

}  // namespace

RenderResult render_bdpt(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                         RenderControl& control) {
  if (options.strategy_images && options.max_depth < 0) {
    throw std::invalid_argument("strategy images need a bounded max_depth");
  }
  Film film(camera.width(), camera.height());
  if (options.strategy_images) film.add_layers(bdpt_strategies(options.max_depth).size());
  if (options.guiding) return render_bdpt_guided(scene, camera, options, control, std::move(film));
  RenderResult result{std::move(film), {}};
  result.stats = drive_bdpt(scene, camera, options, control, result.film, {});
  return result;
}

}  // namespace dualight
