// Whether a trained guide pays for itself, measured before the image is rendered with it. A
// guide can lower an estimator's variance per sample by less than it raises the cost per sample
// (BDPT, whose light subpaths already find what the radiance guide would, pays about 1.3x per
// sample for no gain on the scenes measured in issue 22). Under a time limit the render then
// tries both: a pass guided by the trained guide and an unguided pass, of the same samples per
// pixel and each on its own seed, rendered exactly as the image would be. Each pass's efficiency is
// 1 / (expected relMSE of its mean x its seconds), both independent of its sample count, the
// relMSE of pbrt-v4's imgtool (metrics.relmse) with each pixel's variance of the mean in place
// of the squared error and the two passes' mean in place of the reference.
// That reference is not independent of the passes: a pass's bright outliers raise its variance
// and the reference together, so the noisier pass looks better than it is (path tracer, 64 spp
// passes, guided over unguided relMSE 1.16, 1.35, 1.14 on the caustic box, rooms(10) and the door
// where the true reference gives 1.48, 1.48, 0.34; the door's unguided pass misses the light
// through the gap, which pass_disagreement catches). An independent one, the last training
// iteration's image blurred over 3x3 pixels, gave 1.27, 1.30, 0.32, but its dark pixels let a
// single bright sample of one pass decide: in bench_guiding at 8 s, 2 of 30 trials measured
// guiding 4.8x and 1.2x as efficient where those renders were about 0.6x and 0.8x (BDPT on the
// caustic box, the light tracer on rooms(10) dark), and the table came out worse than with the
// passes' mean (issue 22). The passes' mean bounds each pixel's term (a bright sample raises its
// own denominator), and is kept.
// The image is then rendered by the more efficient one. Both passes are unbiased estimates of the
// same image, so the image keeps their samples (its plain mean, as with the kept training
// iterations). The trial runs during the training, before the iteration predicted to be its last
// (the most costly: train_guides's checkpoint), with the guide so far; there, carrying on guided
// also costs that iteration, of which the image keeps only the samples, so the guided pass must
// win by enough to pay for it (ratio_to_pay), and unguided wins stop the training. When no
// iteration was predicted to be the last, it runs after the training.
// Only under a time limit: with spp alone a render is a function of its seed, which a decision
// by measured seconds would break.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/rng.h"
#include "film/film.h"
#include "guiding/guide_training.h"
#include "guiding/guiding_options.h"
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"

namespace dualight {

// A pass's image: each pixel's and channel's mean and variance of the mean (H x W x 3).
struct PassImage {
  std::vector<float> mean, variance;
  explicit PassImage(const Film& film) : mean(film.mean()), variance(film.variance_of_mean()) {}
};

// The expected relMSE of a pass's mean against a reference image: the mean over pixels and
// channels of its variance of the mean over (reference + eps)^2, eps 1 % of the reference's mean
// (metrics.relmse's 0.01 made independent of the scene's scale).
inline double expected_relmse(const PassImage& pass, const std::vector<float>& reference) {
  double level = 0.0;
  for (const float v : reference) level += std::max(0.f, v);
  const double eps = std::max(1e-2 * level / static_cast<double>(std::max<size_t>(reference.size(), 1)), 1e-30);
  double sum = 0.0;
  for (size_t i = 0; i < pass.variance.size(); ++i) {
    const double y = std::max(0.f, reference[i]) + eps;
    sum += pass.variance[i] / (y * y);
  }
  return sum / static_cast<double>(std::max<size_t>(pass.variance.size(), 1));
}

// How far two unbiased passes of the same image, of n samples per pixel each, disagree beyond
// their own variances: the mean over pixels and channels of t^2 = (a - b)^2 / (var a + var b),
// over its expectation nu / (nu - 2) when the samples are normal (Student's t of Welch's nu =
// 2 (n - 1) degrees of freedom): about 1 when each pass's variance of the mean is right. Well
// above 1, a pass underestimates its variance: its samples have missed the rare, bright paths
// (a heavy tail), and its measured relMSE would flatter it.
inline double pass_disagreement(const PassImage& a, const PassImage& b, uint32_t n) {
  double sum = 0.0;
  size_t count = 0;
  for (size_t i = 0; i < a.mean.size(); ++i) {
    const double v = static_cast<double>(a.variance[i]) + b.variance[i];
    if (!(v > 0.0)) continue;
    const double d = static_cast<double>(a.mean[i]) - b.mean[i];
    sum += d * d / v;
    ++count;
  }
  const double nu = 2.0 * (std::max(n, 3u) - 1.0);
  return count > 0 ? sum / static_cast<double>(count) / (nu / (nu - 2.0)) : 1.0;
}

// Above this disagreement the trial's measurement is not trusted and the image stays guided, as it
// is without a trial. Measured in issue 22 (passes of 32 to 128 spp): 0.96-1.09 on the Cornell
// box, the caustic box, rooms(10) and the door with BDPT and the light tracer, and path tracing
// but on the door, where the unguided pass misses most of the light through the door's gap:
// 1.23-1.26 with passes of 32 spp, 1.44 with 64 (1.09 with 16: too few samples to tell).
constexpr double kTrialDisagreementLimit = 1.15;
// Fewer samples per pixel per pass cannot tell a heavy tail (the door's path tracer above): no
// trial, and the image stays guided.
constexpr uint32_t kTrialMinPassSpp = 32;

// The training still ahead of a trial: its predicted seconds (0 after the training) and the
// samples per pixel of it the image keeps.
struct TrainingAhead {
  double seconds = 0.0;
  uint32_t kept_spp = 0;
};

// The efficiency ratio, guided over unguided, above which guiding pays when `time_left` seconds
// remain for the training ahead and the image: guided, the image's samples take time_left less
// what the training ahead costs beyond its kept samples (`kept_seconds`, their worth at the guided
// pass's cost per sample), against time_left unguided. 1 after the training; infinite when the
// training ahead would use up the time.
inline double ratio_to_pay(double time_left, double ahead_seconds, double kept_seconds) {
  const double lost = std::max(0.0, ahead_seconds - kept_seconds);
  if (lost <= 0.0) return 1.0;
  return time_left > lost ? time_left / (time_left - lost) : std::numeric_limits<double>::infinity();
}

struct GuidingTrial {
  bool guided = true;             // the image is rendered guided
  bool interrupted = false;       // cancelled during a pass: the passes so far are kept, nothing judged
  double efficiency_ratio = 0.0;  // guided over unguided, as measured (0: not judged)
  double ratio_to_pay = 1.0;      // what efficiency_ratio had to reach (ratio_to_pay above)
  double disagreement = 0.0;      // pass_disagreement of the two passes (0: not judged)
  uint32_t spp = 0;               // of both passes together
  double seconds = 0.0;
  uint64_t samples = 0, rays = 0;
  std::vector<FilmAccumulators> films;  // the passes rendered, guided first
};

// The samples per pixel of each of the trial's passes: half the last training iteration's (before
// the last iteration, during the training, the whole spp of the one before it), so the trial
// costs about as much as that iteration, but at least kTrialMinPassSpp; 0 (no trial) when the two
// passes would take more than a quarter of the time limit, at the last iteration's cost per spp.
inline uint32_t trial_pass_spp(const RenderStats& last_iteration, bool during_training, double time_limit) {
  if (last_iteration.spp == 0) return 0;
  const uint32_t spp =
      std::max(during_training ? last_iteration.spp : last_iteration.spp / 2, kTrialMinPassSpp);
  const double predicted = 2.0 * spp * last_iteration.seconds / last_iteration.spp;
  return predicted <= 0.25 * time_limit ? spp : 0;
}

// Runs the trial when it applies (a time limit, a guide, guide_trial, and kTrialMinPassSpp samples
// per pixel per pass; with spp too, the image must have samples left). render(guided, spp, seed,
// film) renders one pass and returns its stats. `spent` is the seconds the render has taken so
// far; `ahead`, the training still to run.
template <class RenderPass>
std::optional<GuidingTrial> run_guiding_trial(const EstimatorOptions& est, const GuidingOptions& g, uint32_t pass_spp,
                                              bool has_guide, int width, int height, const RenderPass& render,
                                              double spent = 0.0, const TrainingAhead& ahead = {}) {
  if (!g.guide_trial || !has_guide || est.time_limit <= 0.0 || pass_spp < kTrialMinPassSpp) return std::nullopt;
  if (est.spp > 0 && 2ull * pass_spp >= est.spp) return std::nullopt;
  GuidingTrial trial;
  std::vector<Film> films;
  double seconds[2] = {0.0, 0.0};
  for (int k = 0; k < 2 && !trial.interrupted; ++k) {
    films.emplace_back(width, height);
    const RenderStats s = render(k == 0, pass_spp, hash_combine(est.seed, 0x747269616cull + k), films.back());
    seconds[k] = s.seconds;
    trial.seconds += s.seconds;
    trial.samples += s.samples;
    trial.rays += s.rays;
    trial.spp += s.spp;
    trial.interrupted = s.interrupted;
    trial.films.push_back(films.back().accumulators());
  }
  if (trial.interrupted) return trial;
  const PassImage guided(films[0]), plain(films[1]);
  std::vector<float> reference(guided.mean.size());
  for (size_t i = 0; i < reference.size(); ++i) reference[i] = 0.5f * (guided.mean[i] + plain.mean[i]);
  const double cost_guided = expected_relmse(guided, reference) * seconds[0];
  const double cost_plain = expected_relmse(plain, reference) * seconds[1];
  trial.efficiency_ratio = cost_guided > 0.0 ? cost_plain / cost_guided : 1.0;
  trial.disagreement = pass_disagreement(guided, plain, pass_spp);
  trial.ratio_to_pay = ratio_to_pay(est.time_limit - spent - trial.seconds, ahead.seconds,
                                    ahead.kept_spp * seconds[0] / pass_spp);
  trial.guided = !(trial.efficiency_ratio < trial.ratio_to_pay) || !(trial.disagreement <= kTrialDisagreementLimit);
  return trial;
}

// The trial of the guide `t` trained so far (guiding_trial.h's run_guiding_trial), during the
// training (its checkpoint, the last iteration still ahead) or after it: passes of trial_pass_spp,
// the time spent being t's training's.
template <class RenderPass>
std::optional<GuidingTrial> try_guiding_trial(const EstimatorOptions& est, const GuidingOptions& g,
                                              const TrainedGuide& t, bool has_guide, bool during_training, int width,
                                              int height, const RenderPass& render) {
  TrainingAhead ahead;
  if (during_training) {
    ahead.seconds = next_iteration_seconds(t.last_iteration_seconds);
    ahead.kept_spp = g.guide_keep_iterations > 0 ? kIterationGrowth * t.last_stats.spp : 0;
  }
  return run_guiding_trial(est, g, trial_pass_spp(t.last_stats, during_training, est.time_limit), has_guide, width,
                           height, render, t.stats.training_seconds, ahead);
}

// The image's options after a trial: its time and samples per pixel off the budget.
template <class Options>
Options after_trial(Options o, const std::optional<GuidingTrial>& trial) {
  if (!trial) return o;
  if (o.time_limit > 0.0) o.time_limit = std::max(1e-3, o.time_limit - trial->seconds);
  if (o.spp > 0) o.spp -= std::min(o.spp, trial->spp);
  return o;
}

// Reports a trial in a guide's stats.
inline void record_trial(GuidingStats& g, const std::optional<GuidingTrial>& trial) {
  if (!trial) return;
  g.trial = true;
  g.trial_spp = trial->spp;
  g.trial_seconds = trial->seconds;
  g.efficiency_ratio = trial->efficiency_ratio;
  g.trial_ratio_to_pay = trial->ratio_to_pay;
  g.trial_disagreement = trial->disagreement;
  g.rendered_guided = trial->guided;
}

// Adds a trial's passes to the image's film and stats (after add_guiding_stats), as
// keep_training_samples does the training's.
inline void keep_trial(Film& film, RenderStats& stats, const std::optional<GuidingTrial>& trial) {
  if (!trial) return;
  for (const FilmAccumulators& a : trial->films) film.add_accumulators(a);
  stats.samples += trial->samples;
  stats.rays += trial->rays;
  stats.spp += trial->spp;
  stats.seconds += trial->seconds;
  stats.interrupted = stats.interrupted || trial->interrupted;
  record_trial(stats.guiding, trial);
}

}  // namespace dualight
