// What every estimator's binding shares: the result as numpy arrays and a dict, and the fields
// of the options they all take.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bindings/numpy_util.h"
#include "bindings/options.h"
#include <pybind11/stl.h>

#include "geometry/camera.h"
#include "guiding/guiding_options.h"
#include "pathspace/mlt.h"
#include "pathspace/mlt_result.h"
#include "pathspace/pssmlt.h"
#include "pathspace/render_stats.h"
#include "geometry/scene.h"

namespace dualight::bindings {

namespace py = pybind11;

// What training a guide took and made (RenderStats::guiding, Guide.stats).
inline py::dict guiding_dict(const GuidingStats& g) {
  py::dict d;
  d["iterations"] = g.iterations;
  d["training_spp"] = g.training_spp;
  d["records"] = g.records;
  d["spatial_leaves"] = g.spatial_leaves;
  d["directional_nodes"] = g.directional_nodes;
  d["training_seconds"] = g.training_seconds;
  d["rendering_seconds"] = g.rendering_seconds;
  d["bsdf_fraction"] = g.bsdf_fraction;
  d["bsdf_fraction_min"] = g.bsdf_fraction_min;
  d["bsdf_fraction_max"] = g.bsdf_fraction_max;
  d["stopped_by_records"] = g.stopped_by_records;
  d["stopped_by_trial"] = g.stopped_by_trial;
  d["seeded"] = g.seeded;
  d["adjoint_roulette"] = g.adjoint_roulette;
  d["split_paths"] = g.split_paths;
  d["roulette_stops"] = g.roulette_stops;
  d["kept_spp"] = g.kept_spp;
  d["trial"] = g.trial;
  d["trial_spp"] = g.trial_spp;
  d["trial_seconds"] = g.trial_seconds;
  d["efficiency_ratio"] = g.efficiency_ratio;
  d["trial_ratio_to_pay"] = g.trial_ratio_to_pay;
  d["trial_disagreement"] = g.trial_disagreement;
  d["rendered_guided"] = g.rendered_guided;
  return d;
}

inline py::dict stats_dict(const RenderStats& s) {
  py::dict d;
  d["samples"] = s.samples;
  d["rays"] = s.rays;
  d["skipped_connections"] = s.skipped_connections;
  d["skipped_shadow_rays"] = s.skipped_shadow_rays;
  d["unoccluded"] = s.unoccluded;
  d["invalid_samples"] = s.invalid_samples;
  d["spp"] = s.spp;
  d["seconds"] = s.seconds;
  d["samples_per_second"] = s.seconds > 0 ? static_cast<double>(s.samples) / s.seconds : 0.0;
  d["rays_per_second"] = s.seconds > 0 ? static_cast<double>(s.rays) / s.seconds : 0.0;
  d["interrupted"] = s.interrupted;
  d["time_limited"] = s.time_limited;
  if (s.lanes != nullptr) d["lanes"] = s.lanes;
  if (!s.lanes_off_because.empty()) {
    d["lanes"] = "off";
    d["lanes_off_because"] = s.lanes_off_because;
  }
  if (s.guiding.used && s.importance_guiding.used) {
    py::dict g;  // guided BDPT: two guides
    g["training_seconds"] = s.guiding.training_seconds;  // one training made both
    g["rendering_seconds"] = s.guiding.rendering_seconds;
    g["kept_spp"] = s.guiding.kept_spp;
    g["radiance"] = guiding_dict(s.guiding);
    g["importance"] = guiding_dict(s.importance_guiding);
    const py::dict radiance = g["radiance"];
    for (const char* key : {"trial", "trial_spp", "trial_seconds", "efficiency_ratio", "trial_ratio_to_pay",
                            "trial_disagreement", "rendered_guided"}) {
      g[key] = radiance[key];  // one trial judged both guides together
    }
    d["guiding"] = g;
  } else if (s.guiding.used) {
    d["guiding"] = guiding_dict(s.guiding);
  }
  return d;
}

// A film's raw totals as numpy arrays (float64 sums, uint32 counts): what one task of a split
// render returns, to be merged in block order by Film.add_accumulators (film.h).
inline py::dict accumulators_dict(const Film& film) {
  FilmAccumulators a = film.accumulators();
  const py::ssize_t h = film.height(), w = film.width();
  py::dict d;
  d["sum"] = to_numpy(std::move(a.sum), {h, w, 3});
  d["sum_sq"] = to_numpy(std::move(a.sum_sq), {h, w, 3});
  d["count"] = to_numpy(std::move(a.count), {h, w});
  if (a.splat_sum.empty()) {
    d["splat_sum"] = py::none();
    d["splat_sum_sq"] = py::none();
  } else {
    d["splat_sum"] = to_numpy(std::move(a.splat_sum), {h, w, 3});
    d["splat_sum_sq"] = to_numpy(std::move(a.splat_sum_sq), {h, w, 3});
  }
  d["light_paths"] = a.light_paths;
  return d;
}

// Film and stats as numpy arrays and a dict; the arrays own the film's buffers. With
// `accumulators`, also the film's raw totals (accumulators_dict).
inline py::dict result_dict(RenderResult&& r, bool keyboard_interrupt, bool accumulators = false) {
  const py::ssize_t h = r.film.height(), w = r.film.width();
  py::dict d;
  d["mean"] = to_numpy(r.film.mean(), {h, w, 3});
  d["variance"] = to_numpy(r.film.variance_of_mean(), {h, w, 3});
  d["counts"] = to_numpy(r.film.sample_counts(), {h, w});
  d["light_paths"] = r.film.light_paths();
  d["stats"] = stats_dict(r.stats);
  d["keyboard_interrupt"] = keyboard_interrupt;
  if (accumulators) d["accumulators"] = accumulators_dict(r.film);
  return d;
}

// The longest bounded path and the latest start of Russian roulette: BDPT keeps max_depth + 1
// vertices per subpath and MMLT a chain population per length (2^31 - 1 took GBs), and a path
// that starts roulette never in a closed scene of high albedo does not end (issue 18).
inline constexpr int kMaxPathDepth = 1024;
// Markov chains and bootstrap samples of the Metropolis methods: each chain keeps its state
// (10 million chains took minutes to start, deaf to Ctrl-C), each bootstrap sample a double
// (per path length with MMLT).
inline constexpr double kMaxChains = 1 << 20, kMaxBootstrap = 1 << 26;
inline Range chain_range() { return up_to(1, kMaxChains, "(each chain keeps its own state)"); }
inline Range bootstrap_range() { return up_to(1, kMaxBootstrap, "(each sample is kept to start the chains)"); }

// The fields of EstimatorOptions, spp named `budget` in Python (the MLT methods count
// mutations: mutations_per_pixel).
template <class T>
void add_estimator_fields(OptionsClass<T>& o, const char* budget, const char* budget_doc) {
  o.field(budget, &EstimatorOptions::spp, budget_doc)
      .field("max_depth", &EstimatorOptions::max_depth,
             "Longest path in segments, as in Mitsuba (1: emitters seen directly); -1 = unbounded.",
             up_to(-1, kMaxPathDepth, "(longer paths carry no light worth their memory)"))
      .field("rr_depth", &EstimatorOptions::rr_depth, "Russian roulette from this path vertex on.",
             up_to(1, kMaxPathDepth, "(later, a path in a closed bright scene never ends)"))
      .field("seed", &EstimatorOptions::seed, "The image depends on the seed only, not on the threads.")
      .field("threads", &EstimatorOptions::threads, "Worker threads; 0 = all cores.", at_least(0))
      .field("time_limit", &EstimatorOptions::time_limit, "Seconds of wall time; 0 = none.", at_least(0))
      .field("skip_unneeded", &EstimatorOptions::skip_unneeded,
             "Skip work the scene makes pointless; False does it all.");
}

// The fields only the pixel estimators (path, light, BDPT) read: their sampler and the first
// sample of one task of a split render.
template <class T>
void add_pixel_fields(OptionsClass<T>& o, const char* spp_doc) {
  add_estimator_fields(o, "spp", spp_doc);
  o.field("sampler", &EstimatorOptions::sampler, "Where the random numbers come from (core/sampler.h).")
      .field("first_sample", &EstimatorOptions::first_sample,
             "First sample index rendered (one task of a split render; see Film).");
}

// The fields of an estimator that can be guided (guiding/guiding_options.h).
template <class T>
void add_guiding_fields(OptionsClass<T>& o) {
  o.field("guiding", &GuidingOptions::guiding, "Train a guide first, then sample directions from it (guiding/).")
      .field("guide_training", &GuidingOptions::guide_training,
             "Share of the budget (spp, or time_limit) spent training, in iterations of 1, 2, 4, ... spp; "
             "with spp the image still has spp samples per pixel.",
             strictly_within(0.0, 1.0))
      .field("guide_keep_iterations", &GuidingOptions::guide_keep_iterations,
             "The image keeps the samples of this many last training iterations (0: none; BDPT with "
             "strategy_images: none), as unbiased as its own; the stats' kept_spp counts them.",
             up_to(0.0, 64, "(training has at most 21 iterations)"))
      .field("guide_trial", &GuidingOptions::guide_trial,
             "Under a time limit, render before the last training iteration (or after training) a guided and "
             "an unguided pass of half the last iteration's spp each (at least 32; kept in the image), and "
             "the image with the more efficient of the two (guided when the passes disagree beyond their variances; "
             "unguided stops the training).")
      .field("guide_learn_bsdf_fraction", &GuidingOptions::guide_learn_bsdf_fraction,
             "Learn each spatial leaf's probability of sampling the BSDF (of 0.1, ..., 1, at least "
             "guide_bsdf_fraction: the least second moment over its records); else guide_bsdf_fraction everywhere.")
      .field("guide_bsdf_fraction", &GuidingOptions::guide_bsdf_fraction,
             "Probability of sampling the BSDF instead of the guide (one-sample MIS); the least one when learnt.",
             within(0.0, 1.0))
      .field("guide_spatial_threshold", &GuidingOptions::guide_spatial_threshold,
             "Records a spatial leaf may hold at 1 spp before it is split (times sqrt(spp)).", at_least(1))
      .field("guide_adjoint_roulette", &GuidingOptions::guide_adjoint_roulette,
             "'path': adjoint-driven Russian roulette and splitting (Vorba and Krivanek 2016) in the "
             "final render and the training iterations after the first, from the guide's reflected-radiance "
             "estimates and the previous iteration's image.")
      .field("guide_rho", &GuidingOptions::guide_rho,
             "A directional node holding more than this share of its leaf's value is split.",
             strictly_within(0.0, 1.0))
      .field("guide_max_records", &GuidingOptions::guide_max_records,
             "Records one training iteration may keep (24 bytes each); training stops before more.",
             up_to(1.0, 1u << 28, "(6 GB of records)"));
}

inline void check_emitters(const Scene& scene) {
  if (scene.emitter_count() == 0) throw py::value_error("scene has no emitter: nothing would be lit");
}


// An MLT method's result: its image (no per-pixel variance: chain samples are correlated),
// light_paths = mutations, and stats with b, its interval, the acceptance rate and the direct
// light's share of the work.
inline py::dict mlt_result_dict(MltResult&& r, int width, int height, uint32_t direct_spp,
                                bool keyboard_interrupt) {
  const MltStats& s = r.mlt;
  py::dict d;
  d["mean"] = to_numpy(std::move(r.image), {height, width, 3});
  d["variance"] = py::none();
  d["light_paths"] = s.mutations;
  d["keyboard_interrupt"] = keyboard_interrupt;
  py::dict stats = stats_dict(r.stats);
  stats["b"] = s.b;
  stats["b_ci95"] = s.b_ci95;
  stats["b_samples"] = s.independent_samples;
  stats["mutations"] = s.mutations;
  stats["acceptance_rate"] = s.mutations > 0 ? static_cast<double>(s.accepted) / s.mutations : 0.0;
  stats["zero_proposals"] = s.zero_proposals;
  stats["pilot_samples"] = s.pilot_samples;
  stats["direct_spp"] = direct_spp > 0 ? r.direct.spp : 0u;  // fewer than asked when time-limited
  stats["direct_seconds"] = r.direct.seconds;
  stats["rays"] = r.stats.rays + r.direct.rays;
  stats["skipped_connections"] = r.stats.skipped_connections + r.direct.skipped_connections;
  stats["skipped_shadow_rays"] = r.stats.skipped_shadow_rays + r.direct.skipped_shadow_rays;
  d["stats"] = stats;
  return d;
}

// PSSMLT's and MMLT's result: mlt_result_dict plus large-step rates and, multiplexed, b by path
// length.
inline py::dict pssmlt_result_dict(MltResult&& r, const PinholeCamera& camera, const PssmltOptions& options,
                                   bool keyboard_interrupt) {
  const MltStats s = r.mlt;
  py::dict d = mlt_result_dict(std::move(r), camera.width(), camera.height(), options.direct_spp,
                               keyboard_interrupt);
  py::dict stats = d["stats"];
  stats["b_per_depth"] = s.b_per_depth;
  stats["b_per_depth_ci95"] = s.b_per_depth_ci95;
  stats["mutations_per_depth"] = s.mutations_per_depth;
  stats["large_step_mis"] = options.large_step_mis;
  stats["large_steps"] = s.large_steps;
  stats["large_step_acceptance_rate"] =
      s.large_steps > 0 ? static_cast<double>(s.large_steps_accepted) / s.large_steps : 0.0;
  stats["small_step_acceptance_rate"] =
      s.mutations > s.large_steps
          ? static_cast<double>(s.accepted - s.large_steps_accepted) / (s.mutations - s.large_steps)
          : 0.0;
  return d;
}

inline py::dict mutation_stats_dict(const std::vector<MutationStats>& mutations) {
  py::dict per_mutation;
  for (const MutationStats& ms : mutations) {
    py::dict e;
    e["proposed"] = ms.proposed;
    e["accepted"] = ms.accepted;
    e["failed"] = ms.failed;
    e["acceptance_rate"] = ms.proposed > 0 ? static_cast<double>(ms.accepted) / ms.proposed : 0.0;
    per_mutation[ms.name.c_str()] = e;
  }
  return per_mutation;
}

// Path-space MLT's result: mlt_result_dict plus counts per mutation type.
inline py::dict path_mlt_result_dict(PathMltResult&& r, const PinholeCamera& camera, const MltOptions& options,
                                     bool keyboard_interrupt) {
  const std::vector<MutationStats> mutations = r.mutations;
  py::dict d = mlt_result_dict(std::move(r.result), camera.width(), camera.height(), options.direct_spp,
                               keyboard_interrupt);
  py::dict stats = d["stats"];
  stats["mutation_types"] = mutation_stats_dict(mutations);
  stats["skipped_mutations"] = r.skipped_mutations;
  stats["importance"] = options.importance == MltImportance::Flattened ? "flattened" : "luminance";
  return d;
}

}  // namespace dualight::bindings
