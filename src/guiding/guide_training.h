// Trains a guide in iterations of doubling samples per pixel [MGN17, sec. 4]: iteration k renders
// 2^k samples per pixel (on its own seed) guided by the tree of iteration k - 1, and records what
// its paths carried; the records build iteration k's tree. Training ends when its share of the
// budget would be exceeded (samples per pixel, or time assuming each iteration takes twice the
// last), or before an iteration would store more than guide_max_records, or on cancellation.
// Under a time limit a checkpoint (the guiding trial, guiding_trial.h) may look at the guides
// before the iteration predicted to be the last, and stop the training there: when the guide
// does not pay, that iteration, the training's most costly, is not spent.
// With spp the iterations and the tree are a function of the seed alone, whatever the threads.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <utility>

#include <tbb/enumerable_thread_specific.h>

#include "core/render_control.h"
#include "core/rng.h"
#include "core/stopwatch.h"
#include "geometry/scene.h"
#include "guiding/guiding_options.h"
#include "guiding/sd_tree.h"
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"

namespace dualight {

// Records gathered by threads, each into its own list.
class RecordCollector {
 public:
  GuideRecords& local() { return lists_.local(); }
  // Every list, concatenated (their order does not matter: SdTree sorts them).
  GuideRecords take() {
    GuideRecords all;
    size_t n = 0;
    for (const GuideRecords& l : lists_) n += l.size();
    all.reserve(n);
    for (GuideRecords& l : lists_) {
      all.insert(all.end(), l.begin(), l.end());
      GuideRecords().swap(l);
    }
    return all;
  }

 private:
  tbb::enumerable_thread_specific<GuideRecords> lists_;
};

struct TrainedGuide {
  std::shared_ptr<const SdTree> tree;  // null when no iteration finished
  GuidingStats stats;
  uint64_t rays = 0;  // traced by the iterations
  // The last finished iteration's image (none when no iteration finished) and its stats: the
  // roulette's pixel estimates, and what a render interrupted during training returns.
  std::optional<Film> last_image;
  RenderStats last_stats;
  double last_iteration_seconds = 0.0;  // its render and tree building
  // The last finished iterations' samples (at most guide_keep_iterations, oldest first), which
  // the image keeps (keep_training_samples).
  struct Kept {
    uint32_t spp;
    uint64_t samples;
    FilmAccumulators film;
  };
  std::deque<Kept> kept;
};

// Looks at N guides during training; true stops the training (its time does not count in the
// training's).
template <size_t N>
using TrainingCheckpoint = std::function<bool(const std::array<TrainedGuide, N>&)>;

// Each training iteration renders kIterationGrowth times the samples per pixel of the one before,
// and is predicted to take that many times its seconds.
constexpr uint32_t kIterationGrowth = 2;
inline double next_iteration_seconds(double last_seconds) { return kIterationGrowth * last_seconds; }

// Whether the checkpoint is due after an iteration that took last_seconds, the training having
// spent `spent` of its time_budget: the next iteration is predicted to be the last that fits (the
// one after it would not).
inline bool checkpoint_due(double spent, double last_seconds, double time_budget) {
  if (time_budget <= 0.0) return false;
  const double next = next_iteration_seconds(last_seconds);
  return spent + next <= time_budget && spent + (1.0 + kIterationGrowth) * next > time_budget;
}

// The scene's box, grown a little so every vertex falls inside.
inline void guide_bounds(const Scene& scene, Vec3& lo, Vec3& hi) {
  const Vec3 pad = (scene.bounds_max() - scene.bounds_min()) * 1e-3f + Vec3(1e-4f);
  lo = scene.bounds_min() - pad;
  hi = scene.bounds_max() + pad;
}

// The tree an iteration's records build (reordering them), over the guide before it.
inline std::shared_ptr<const SdTree> next_tree(GuideRecords& records, const Vec3& lo, const Vec3& hi,
                                               const GuidingOptions& g, uint32_t spp, const SdTree* previous) {
  SdTreeSettings settings;
  settings.spatial_threshold =
      static_cast<uint32_t>(std::min(4.0e9, g.guide_spatial_threshold * std::sqrt(static_cast<double>(spp))));
  settings.rho = g.guide_rho;
  settings.learn_bsdf_fraction = g.guide_learn_bsdf_fraction;
  settings.bsdf_fraction = g.guide_bsdf_fraction;
  return std::make_shared<const SdTree>(records, lo, hi, settings, previous);
}

// A trained guide's final stats: the training's time and its tree's sizes.
inline void finish_guide_stats(TrainedGuide& out, double seconds) {
  out.stats.training_seconds = seconds;
  if (!out.tree) return;
  out.stats.spatial_leaves = out.tree->leaves();
  out.stats.directional_nodes = out.tree->directional_nodes();
  out.tree->bsdf_fractions(out.stats.bsdf_fraction, out.stats.bsdf_fraction_min, out.stats.bsdf_fraction_max);
}

// Trains N guides in the same iterations. run(spp, seed, trees, collectors, film) renders one
// iteration on `film` (width x height), sampling from `trees` (std::array of N, each may be
// null) and recording guide i's records into collectors[i], and returns its stats. `start` (each
// may be null) guides the first iteration. The iterations' images, kept samples and rays are the
// first guide's (guide_training.h's TrainedGuide); every guide has the training's counts and time.
// `checkpoint` (may be null) is called at most once, when checkpoint_due.
template <size_t N, class RunIteration>
std::array<TrainedGuide, N> train_guides(const Scene& scene, const EstimatorOptions& est, const GuidingOptions& g,
                                         int width, int height, RenderControl& control,
                                         std::array<std::shared_ptr<const SdTree>, N> start, const RunIteration& run,
                                         const TrainingCheckpoint<N>* checkpoint = nullptr) {
  std::array<TrainedGuide, N> out;
  for (size_t i = 0; i < N; ++i) {
    out[i].stats.seeded = start[i] != nullptr;
    out[i].tree = std::move(start[i]);
  }
  TrainedGuide& first = out[0];
  const Stopwatch clock;
  double paused = 0.0;  // in the checkpoint
  const auto elapsed = [&] { return clock() - paused; };
  const double spp_budget = est.spp > 0 ? std::floor(g.guide_training * est.spp) : 0.0;
  const double time_budget = est.time_limit > 0.0 ? g.guide_training * est.time_limit : 0.0;
  Vec3 lo, hi;
  guide_bounds(scene, lo, hi);
  uint32_t spp = 1, spp_done = 0;
  double last_seconds = 0.0;
  size_t last_records = 0;  // the most any guide kept in the last iteration
  for (int k = 0;; ++k, spp *= kIterationGrowth) {
    if (est.spp > 0 && spp_done + spp > spp_budget) break;
    if (time_budget > 0.0 && elapsed() + next_iteration_seconds(last_seconds) > time_budget) break;
    if (2.0 * static_cast<double>(last_records) > g.guide_max_records) {
      for (TrainedGuide& t : out) t.stats.stopped_by_records = true;
      break;
    }
    if (control.cancelled() || spp > (1u << 20)) break;
    const double start_time = elapsed();
    std::array<RecordCollector, N> collectors;
    std::array<const SdTree*, N> trees;
    for (size_t i = 0; i < N; ++i) trees[i] = out[i].tree.get();
    Film film(width, height);
    const RenderStats s =
        run(spp, hash_combine(est.seed, 0x67756964ull + static_cast<uint64_t>(k)), trees, collectors, film);
    first.rays += s.rays;
    if (s.interrupted || control.cancelled()) break;
    if (g.guide_keep_iterations > 0) {
      if (first.kept.size() >= g.guide_keep_iterations) first.kept.pop_front();
      first.kept.push_back({spp, s.samples, film.accumulators()});
    }
    first.last_image = std::move(film);
    first.last_stats = s;
    spp_done += spp;
    last_records = 0;
    for (size_t i = 0; i < N; ++i) {
      GuideRecords records = collectors[i].take();
      last_records = std::max(last_records, records.size());
      out[i].tree = next_tree(records, lo, hi, g, spp, out[i].tree.get());
      out[i].stats.iterations = k + 1;
      out[i].stats.training_spp = spp_done;
      out[i].stats.records = records.size();
    }
    last_seconds = elapsed() - start_time;
    first.last_iteration_seconds = last_seconds;
    if (checkpoint != nullptr && *checkpoint && checkpoint_due(elapsed(), last_seconds, time_budget)) {
      for (TrainedGuide& t : out) t.stats.training_seconds = elapsed();  // so far
      const Stopwatch looking;
      const bool stop = (*checkpoint)(out);
      paused += looking();
      checkpoint = nullptr;
      if (stop) {
        for (TrainedGuide& t : out) t.stats.stopped_by_trial = true;
        break;
      }
    }
  }
  const double seconds = elapsed();
  for (TrainedGuide& t : out) finish_guide_stats(t, seconds);
  return out;
}

// One guide: run(spp, seed, guide, collector, film) as train_guides's run for N = 1.
template <class RunIteration>
TrainedGuide train_guide(const Scene& scene, const EstimatorOptions& est, const GuidingOptions& g, int width,
                         int height, RenderControl& control, std::shared_ptr<const SdTree> start,
                         const RunIteration& run, const TrainingCheckpoint<1>* checkpoint = nullptr) {
  auto trained = train_guides<1>(
      scene, est, g, width, height, control, {std::move(start)},
      [&](uint32_t spp, uint64_t seed, const std::array<const SdTree*, 1>& trees,
          std::array<RecordCollector, 1>& collectors,
          Film& film) { return run(spp, seed, trees[0], collectors[0], film); },
      checkpoint);
  return std::move(trained[0]);
}

// A training iteration's options: spp samples on its own seed, no time limit, from sample 0.
template <class Options>
Options iteration_options(Options o, uint32_t spp, uint64_t seed) {
  o.spp = spp;
  o.seed = seed;
  o.time_limit = 0.0;
  o.first_sample = 0;
  return o;
}

// The image's options after training: under a time limit, the time left.
template <class Options>
Options after_training(Options o, const TrainedGuide& trained) {
  if (o.time_limit > 0.0) o.time_limit = std::max(1e-3, o.time_limit - trained.stats.training_seconds);
  return o;
}

// The image's stats with the training's: its time and rays count in the render's, as an
// equal-time comparison needs.
inline void add_guiding_stats(RenderStats& stats, const TrainedGuide& trained) {
  stats.guiding = trained.stats;
  stats.guiding.used = true;
  stats.guiding.rendering_seconds = stats.seconds;
  stats.seconds += trained.stats.training_seconds;
  stats.rays += trained.rays;
}

// Adds the kept training iterations' samples to the image's film (oldest first, a fixed order)
// and counts them in its stats (after add_guiding_stats): the image is the mean of all its samples.
inline void keep_training_samples(Film& film, RenderStats& stats, const TrainedGuide& trained) {
  for (const TrainedGuide::Kept& k : trained.kept) {
    film.add_accumulators(k.film);
    stats.samples += k.samples;
    stats.spp += k.spp;
    stats.guiding.kept_spp += k.spp;
  }
}

// Guided BDPT's stats: both guides' (trained together, train_guides: the training's time and
// rays, the first guide's, count once).
inline void add_guiding_stats(RenderStats& stats, const TrainedGuide& radiance, const TrainedGuide& importance) {
  add_guiding_stats(stats, radiance);
  stats.importance_guiding = importance.stats;
  stats.importance_guiding.used = true;
  stats.importance_guiding.rendering_seconds = stats.guiding.rendering_seconds;
}

// What a render interrupted during training returns: the last finished iteration's image (an
// empty film when none finished), with its counts, interrupted; no time or rays yet (they are
// the training's: add_guiding_stats adds them).
inline RenderResult last_training_image(TrainedGuide& trained, int width, int height) {
  RenderResult r{trained.last_image ? std::move(*trained.last_image) : Film(width, height), trained.last_stats};
  r.stats.seconds = 0.0;
  r.stats.rays = 0;
  r.stats.interrupted = true;
  return r;
}

// The same with the training's stats, for an estimator with one guide.
inline RenderResult interrupted_in_training(TrainedGuide&& trained, int width, int height) {
  RenderResult r = last_training_image(trained, width, height);
  add_guiding_stats(r.stats, trained);
  return r;
}

}  // namespace dualight
