#include "pathspace/light_tracer.h"

#include <algorithm>
#include <atomic>
#include <vector>

#include "core/parallel.h"
#include "core/stopwatch.h"
#include "film/pixel_estimate.h"
#include "film/splat_list.h"
#include "guiding/guide_training.h"
#include "guiding/guiding_trial.h"
#include "pathspace/mlt_importance.h"
#include "pathspace/connect.h"
#include "pathspace/subpath.h"
#include "pathspace/subpath_records.h"

namespace dualight {

namespace {

// Particles are traced in chunks of a fixed size, each chunk's splats kept apart and added to the
// film in chunk order: the image does not depend on the thread count or schedule. Chunks start
// at multiples of kChunk from the start of their block of kBlockSpp x pixels particles (film.h),
// whose splats are summed apart, so a render split into tasks of whole blocks is the same sum.
constexpr uint64_t kChunk = 4096;
// Particle i's random numbers: the sampler's "pixel" slot names the particle stream, its sample
// index is i, so a Sobol sampler stratifies over all particles.
constexpr uint64_t kParticleStream = 0x9a3f'6c21'0b7d'e584ull;

// The guide of a guided render, and where a training iteration keeps its records. Importance is
// learnt for each pixel's relative error, not for the image's total: a contribution counts in
// proportion to `pixel_weight` (the last iteration's image, smoothed, to the power -1/2, as
// MLT's flattened target, mlt_importance.h). Otherwise the few pixels that see a bright surface
// directly would draw every particle to it (on the door: the bright room's sliver seen through
// the gap, not the dark room around it).
struct ParticleGuiding {
  WalkGuide walk;
  RecordCollector* collector = nullptr;
  const PixelImportance* pixel_weight = nullptr;
};

template <class Sampler>
void trace_particle(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& opt, uint64_t index,
                    Path& path, SplatList& splats, TraceCounters& counters, const ParticleGuiding& guiding,
                    std::vector<Color>& contribution) {
  Sampler sampler(opt.seed, kParticleStream ^ (index >> 32), static_cast<uint32_t>(index));
  light_subpath(scene, sampler, WalkLimits{opt.max_depth, opt.rr_depth}, path, counters, guiding.walk);
  splats.begin_path();
  const bool recording = guiding.collector != nullptr;
  if (recording) contribution.assign(path.size(), Color(0.f));
  for (size_t k = 0; k < path.size(); ++k) {
    Point2 raster{};
    const Color c = connect_to_camera(scene, camera, path[k], raster, counters);
    if (is_black(c)) continue;
    const uint32_t pixel = static_cast<uint32_t>(raster.v) * camera.width() + static_cast<uint32_t>(raster.u);
    if (recording) contribution[k] = guiding.pixel_weight != nullptr ? c * (*guiding.pixel_weight)(pixel) : c;
    splats.add(pixel, c);
  }
  splats.end_path();
  if (recording) record_incident(path, contribution, TransportMode::Importance, guiding.collector->local());
}

template <class Sampler>
RenderStats drive_particles(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& opt,
                            Film& film, RenderControl& control, const ParticleGuiding& guiding) {
  const uint64_t pixels = static_cast<uint64_t>(camera.width()) * camera.height();
  const bool unbounded = opt.spp == 0;
  const uint64_t target = unbounded ? 0 : pixels * opt.spp;
  control.total.store(target);
  const Stopwatch elapsed;

  RenderStats stats;
  SharedTraceCounters work(connections_unoccluded(scene, camera, opt.skip_unneeded));
  const uint64_t first_particle = static_cast<uint64_t>(opt.first_sample) * pixels;
  const uint64_t block = static_cast<uint64_t>(kBlockSpp) * pixels;
  const auto block_end = [&](uint64_t i) { return (i / block + 1) * block; };
  uint64_t invalid = 0;
  uint64_t traced = 0;
  uint64_t pass_chunks = 4;
  std::vector<SplatList> chunk_splats;
  std::vector<uint64_t> chunk_particles;
  std::vector<std::pair<uint64_t, uint64_t>> chunk_range;
  while ((unbounded || traced < target) && !control.cancelled()) {
    if (opt.time_limit > 0.0 && elapsed() >= opt.time_limit) {
      stats.time_limited = true;
      break;
    }
    // The pass's chunks: up to pass_chunks, none crossing a block's end or the target.
    chunk_range.clear();
    for (uint64_t i = first_particle + traced; chunk_range.size() < pass_chunks;) {
      if (!unbounded && i >= first_particle + target) break;
      uint64_t last = std::min(i + kChunk, block_end(i));
      if (!unbounded) last = std::min(last, first_particle + target);
      chunk_range.emplace_back(i, last);
      i = last;
    }
    const size_t n_chunks = chunk_range.size();
    chunk_splats.resize(n_chunks);
    chunk_particles.assign(n_chunks, 0);
    const double pass_start = elapsed();
    parallel_for_each_index(opt.threads, n_chunks, [&](size_t chunk) {
      const auto [first, last] = chunk_range[chunk];
      SplatList& splats = chunk_splats[chunk];
      splats.clear();
      Path path;
      std::vector<Color> contribution;
      TraceCounters local = work.local();
      for (uint64_t i = first; i < last; ++i) {
        if ((i & 255u) == 0 && control.cancelled()) break;
        trace_particle<Sampler>(scene, camera, opt, i, path, splats, local, guiding, contribution);
        ++chunk_particles[chunk];
      }
      work.add(local);
      control.done.fetch_add(chunk_particles[chunk], std::memory_order_relaxed);
    });
    // A cancelled pass keeps only its complete prefix of chunks, so the particle count is exact.
    for (size_t chunk = 0; chunk < n_chunks; ++chunk) {
      const auto [first, last] = chunk_range[chunk];
      film.add_splats(chunk_splats[chunk], chunk_particles[chunk]);
      invalid += chunk_splats[chunk].invalid();
      traced += chunk_particles[chunk];
      if (chunk_particles[chunk] < last - first) break;
      if (last == block_end(first)) film.end_splat_block();
    }
    if (control.cancelled()) break;
    // Aim for passes of about a quarter second so time limits and progress stay responsive.
    const double per_chunk = std::max(elapsed() - pass_start, 1e-6) / static_cast<double>(n_chunks);
    pass_chunks = static_cast<uint64_t>(std::clamp(0.25 / per_chunk, 1.0, 65536.0));
  }
  film.end_blocks();  // the last block, when the render ends inside one
  stats.seconds = elapsed();
  work.into(stats);
  stats.invalid_samples = invalid;
  stats.interrupted = control.cancelled();
  stats.samples = traced;
  stats.spp = static_cast<uint32_t>(traced / pixels);
  return stats;
}

RenderStats drive_light(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& options,
                        RenderControl& control, Film& film, const ParticleGuiding& guiding) {
  return with_sampler(options.sampler, [&](auto tag) {
    return drive_particles<typename decltype(tag)::type>(scene, camera, options, film, control, guiding);
  });
}

// The importance guide's training; `checkpoint` as train_guides's.
TrainedGuide train_importance_guide_with(const Scene& scene, const PinholeCamera& camera,
                                         const LightTracerOptions& options, RenderControl& control,
                                         const TrainingCheckpoint<1>* checkpoint) {
  PixelImportance pixel_weight;  // uniform until an iteration's image is there
  return train_guide(
      scene, options, options, camera.width(), camera.height(), control, options.guide_start_importance,
      [&](uint32_t spp, uint64_t seed, const SdTree* tree, RecordCollector& collector, Film& film) {
        const LightTracerOptions o = iteration_options(options, spp, seed);
        const RenderStats s = drive_light(scene, camera, o, control, film, {{tree}, &collector, &pixel_weight});
        pixel_weight = PixelImportance(film_luminance(film), camera.width(), camera.height(), 2, 0.01);
        return s;
      },
      checkpoint);
}

// Trains the importance guide, tries whether it pays (guiding_trial.h: during the training, which
// it may stop, or after it), renders the image guided or not, and adds the training's and the
// trial's stats and samples.
RenderResult render_light_guided(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& options,
                                 RenderControl& control) {
  const auto render = [&](const SdTree* guide, const LightTracerOptions& o, Film& film) {
    return drive_light(scene, camera, o, control, film, {{guide}, nullptr});
  };
  std::optional<GuidingTrial> trial;
  const auto try_guide = [&](const TrainedGuide& t, bool during_training) {
    trial = try_guiding_trial(options, options, t, t.tree != nullptr, during_training, camera.width(), camera.height(),
                              [&](bool guided, uint32_t spp, uint64_t seed, Film& film) {
                                return render(guided ? t.tree.get() : nullptr, iteration_options(options, spp, seed),
                                              film);
                              });
    return trial && !trial->guided;
  };
  const TrainingCheckpoint<1> checkpoint = [&](const std::array<TrainedGuide, 1>& t) {
    return try_guide(t[0], true);
  };
  TrainedGuide trained = train_importance_guide_with(scene, camera, options, control, &checkpoint);
  if (control.cancelled()) return interrupted_in_training(std::move(trained), camera.width(), camera.height());
  if (!trial) try_guide(trained, false);
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats = render(!trial || trial->guided ? trained.tree.get() : nullptr,
                        after_trial(after_training(options, trained), trial), result.film);
  add_guiding_stats(result.stats, trained);
  keep_training_samples(result.film, result.stats, trained);
  keep_trial(result.film, result.stats, trial);
  return result;
}

}  // namespace

TrainedGuide train_importance_guide(const Scene& scene, const PinholeCamera& camera,
                                    const LightTracerOptions& options, RenderControl& control) {
  return train_importance_guide_with(scene, camera, options, control, nullptr);
}

RenderResult render_light(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& options,
                          RenderControl& control) {
  if (options.guiding) return render_light_guided(scene, camera, options, control);
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats = drive_light(scene, camera, options, control, result.film, {});
  return result;
}

}  // namespace dualight
