#include "pathspace/bdpt.h"

#include <tbb/enumerable_thread_specific.h>

#include <algorithm>
#include <array>
#include <stdexcept>
#include <utility>

#include "core/rng.h"
#include "film/pixel_estimate.h"
#include "guiding/guide_training.h"
#include "guiding/guiding_trial.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/mlt_importance.h"
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

// A guided BDPT training iteration's collectors (the radiance guide's, the importance guide's)
// and the importance records' pixel weights.
struct BdptTraining {
  RecordCollector* radiance = nullptr;
  RecordCollector* importance = nullptr;
  const PixelImportance* pixel_weight = nullptr;
};

// The light pool's subpaths (kBdptLightPool, bdpt.h) of the pixels [x0, x1) of row y at sample
// index s, each from a random stream of its own (not its pixel's, which its camera subpath and
// connections draw from), into w.row_light; the length of each group's longest; and the row's
// key at s (LightPool::for_strategy).
constexpr uint64_t kLightPoolSeed = 0x6c69676874706f6full;
template <class Sampler>
void trace_row_light_subpaths(const Scene& scene, const BdptOptions& options, int width, int x0, int x1, int y,
                              uint32_t s, Subpaths& w, TraceCounters& counters) {
  const WalkLimits limits{options.max_depth, options.rr_depth};
  const uint64_t seed = hash_combine(options.seed, kLightPoolSeed);
  const int size = options.light_pool;
  w.row_light.resize(static_cast<size_t>(x1 - x0));
  w.row_longest.assign(static_cast<size_t>((x1 - x0 + size - 1) / size), 0);
  w.row_x0 = x0;
  w.row_key = hash_combine(hash_combine(seed, static_cast<uint64_t>(y)), s);
  for (int x = x0; x < x1; ++x) {
    Sampler sampler(seed, static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x), s);
    Path& light = w.row_light[static_cast<size_t>(x - x0)];
    light_subpath(scene, sampler, limits, light, counters);
    uint32_t& longest = w.row_longest[static_cast<size_t>((x - x0) / size)];
    longest = std::max(longest, static_cast<uint32_t>(light.size()));
  }
}

// Pixel x's light pool: its group of `size` pixels of the row whose subpaths w.row_light holds.
LightPool light_pool_of(const Subpaths& w, int x, int size) {
  const int k = x - w.row_x0, n = static_cast<int>(w.row_light.size());
  const int group = k / size, first = group * size;
  return {w.row_light.data() + first, static_cast<uint32_t>(std::min(size, n - first)),
          static_cast<uint32_t>(k - first), hash_combine(w.row_key, static_cast<uint64_t>(w.row_x0 + first)),
          w.row_longest[static_cast<size_t>(group)]};
}

RenderStats drive_bdpt(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                       RenderControl& control, Film& film, const SubpathGuides& guides,
                       const BdptTraining* training = nullptr) {
  static_assert(kBdptLightPoolMax <= pixel_driver_detail::kTile, "a light pool lies within a tile row");
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, true,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  tbb::enumerable_thread_specific<Subpaths> workspaces;
  const auto estimate = [&](float x, float y, auto& sampler, TraceCounters& counters, SplatList& splats) {
    if (training == nullptr) {
      return bdpt_sample(scene, camera, options, x, y, sampler, workspaces.local(), counters, splats, &film, guides);
    }
    const SubpathRecording recording{&training->radiance->local(), &training->importance->local(),
                                     training->pixel_weight};
    return bdpt_sample(scene, camera, options, x, y, sampler, workspaces.local(), counters, splats, &film, guides,
                       &recording);
  };
  const bool pooled = options.light_pool > 1;
  if (pooled && (guides.any() || training != nullptr)) throw std::logic_error("guided BDPT joins its own subpaths");
  return with_sampler(options.sampler, [&](auto tag) {
    using Sampler = typename decltype(tag)::type;
    if (!pooled) return drive_pixels<Sampler>(film, driver, control, estimate);
    const auto pooled_estimate = [&](float x, float y, Sampler& sampler, TraceCounters& counters, SplatList& splats) {
      Subpaths& w = workspaces.local();
      // The film position's integer part is its pixel's (start_sample).
      const LightPool pool = light_pool_of(w, static_cast<int>(x), options.light_pool);
      return bdpt_sample(scene, camera, options, x, y, sampler, w, counters, splats, &film, {}, nullptr, &pool);
    };
    const auto begin_row = [&](int x0, int x1, int y, uint32_t s, TraceCounters& counters) {
      trace_row_light_subpaths<Sampler>(scene, options, camera.width(), x0, x1, y, s, workspaces.local(), counters);
    };
    return drive_pixels<Sampler>(film, driver, control, row_estimate(pooled_estimate, begin_row));
  });
}

// Trains guided BDPT's two guides together from its own samples: iteration k renders BDPT with
// iteration k - 1's guides (the first: plain BDPT, or the given start guides) and records, from
// every strategy's MIS-weighted contribution, the radiance that arrived along the camera
// subpaths' directions and the importance along the light subpaths' (subpath_records.h). Each
// guide so learns what its subpaths carry in the combined estimator: the camera subpaths need
// not find what light subpaths already bring in. The iterations render no strategy images; with
// them the image keeps no iteration's samples.
std::array<TrainedGuide, 2> train_bdpt_guides(const Scene& scene, const PinholeCamera& camera,
                                              const BdptOptions& options, RenderControl& control,
                                              const TrainingCheckpoint<2>* checkpoint) {
  GuidingOptions g = options;
  if (options.strategy_images) g.guide_keep_iterations = 0;
  PixelImportance pixel_weight;  // uniform until an iteration's image is there
  return train_guides<2>(
      scene, options, g, camera.width(), camera.height(), control,
      {options.guide_start_radiance, options.guide_start_importance},
      [&](uint32_t spp, uint64_t seed, const std::array<const SdTree*, 2>& trees,
          std::array<RecordCollector, 2>& collectors, Film& film) {
        BdptOptions o = iteration_options(options, spp, seed);
        o.strategy_images = false;
        const BdptTraining training{&collectors[0], &collectors[1], &pixel_weight};
        const RenderStats s = drive_bdpt(scene, camera, o, control, film, {trees[0], trees[1]}, &training);
        pixel_weight = PixelImportance(film_luminance(film), camera.width(), camera.height(), 2, 0.01);
        return s;
      },
      checkpoint);
}

// Trains both guides, tries whether they pay (guiding_trial.h: during the training, which it may
// stop, or after it), renders the image guided or not, and adds the training's and the trial's
// stats and samples. Interrupted during training, the last finished training iteration's image
// is returned.
RenderResult render_bdpt_guided(const Scene& scene, const PinholeCamera& camera, const BdptOptions& guided_options,
                                RenderControl& control, Film film) {
  // Every pass, guided or not, the trial's and the image's, joins each sample's own subpaths: the
  // trial compares the guides with nothing else, and stats["light_pool"] is 1.
  BdptOptions options = guided_options;
  options.light_pool = 1;
  const auto render = [&](const std::array<TrainedGuide, 2>* guided, const BdptOptions& o, Film& into) {
    const SubpathGuides guides = guided ? SubpathGuides{(*guided)[0].tree.get(), (*guided)[1].tree.get()}
                                        : SubpathGuides{};
    return drive_bdpt(scene, camera, o, control, into, guides);
  };
  std::optional<GuidingTrial> trial;
  const auto try_guides = [&](const std::array<TrainedGuide, 2>& t, bool during_training) {
    // With strategy images the passes would need layers: no trial.
    const bool has_guide = (t[0].tree || t[1].tree) && !options.strategy_images;
    trial = try_guiding_trial(options, options, t[0], has_guide, during_training, camera.width(), camera.height(),
                              [&](bool guided, uint32_t spp, uint64_t seed, Film& into) {
                                return render(guided ? &t : nullptr, iteration_options(options, spp, seed), into);
                              });
    return trial && !trial->guided;
  };
  const TrainingCheckpoint<2> checkpoint = [&](const std::array<TrainedGuide, 2>& t) {
    return try_guides(t, true);
  };
  std::array<TrainedGuide, 2> trained = train_bdpt_guides(scene, camera, options, control, &checkpoint);
  TrainedGuide &radiance = trained[0], &importance = trained[1];
  if (control.cancelled()) {
    RenderResult r = last_training_image(radiance, camera.width(), camera.height());
    add_guiding_stats(r.stats, radiance, importance);
    return r;
  }
  if (!trial) try_guides(trained, false);
  RenderResult result{std::move(film), {}};
  result.stats = render(!trial || trial->guided ? &trained : nullptr,
                        after_trial(after_training(options, radiance), trial), result.film);
  add_guiding_stats(result.stats, radiance, importance);
  keep_training_samples(result.film, result.stats, radiance);
  keep_trial(result.film, result.stats, trial);
  result.stats.importance_guiding.kept_spp = result.stats.guiding.kept_spp;
  record_trial(result.stats.importance_guiding, trial);
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
