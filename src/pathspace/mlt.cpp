#include "pathspace/mlt.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <atomic>
#include <memory>
#include <utility>

#include "core/distribution.h"
#include "core/mean_estimate.h"
#include "core/parallel.h"
#include "core/sampler.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/chain_rounds.h"
#include "pathspace/direct_light.h"
#include "pathspace/mutations/bidirectional.h"
#include "pathspace/mutations/caustic_perturbation.h"
#include "pathspace/mutations/lens_perturbation.h"
#include "pathspace/mutations/lens_subpath.h"
#include "pathspace/shadow_ray.h"
#include "pathspace/start_up.h"

namespace dualight {

namespace {

constexpr uint64_t kBootstrapStream = 0x7a3d'19c0'e5b2'4f61ull;
constexpr uint64_t kChainStream = 0x0b8e'c2f4'6d17'a935ull;
constexpr uint64_t kPilotStream = 0x5c61'e08d'3a9f'b247ull;

uint32_t pixel_of(const PinholeCamera& camera, const Point2& raster) {
  const uint32_t x = std::min(static_cast<uint32_t>(std::max(raster.u, 0.f)), static_cast<uint32_t>(camera.width() - 1));
  const uint32_t y = std::min(static_cast<uint32_t>(std::max(raster.v, 0.f)), static_cast<uint32_t>(camera.height() - 1));
  return y * camera.width() + x;
}

// A chain's state: the path, its contribution, the pixel it lands in and its target value f*.
struct State {
  Path path;
  PathValue f;
  uint32_t pixel = 0;
  double target = 0.0;  // f_lum times the pixel's importance factor
};

bool evaluate(const PinholeCamera& camera, const PixelImportance& importance, State& s) {
  Point2 raster{};
  s.f = path_contribution(camera, s.path, raster);
  s.pixel = pixel_of(camera, raster);
  s.target = s.f.f_lum * importance(s.pixel);
  return s.target > 0.0;
}

BdptOptions bootstrap_bdpt(const MltOptions& opt) {
  BdptOptions bdpt;
  bdpt.max_depth = opt.max_depth;
  bdpt.rr_depth = opt.rr_depth;
  bdpt.heuristic = opt.heuristic;
  bdpt.min_depth = opt.direct_spp > 0 ? 3 : 1;
  return bdpt;
}

// One BDPT sample of the bootstrap (a uniform film position, every strategy); calls
// visit(s, t, unweighted, mis weight, sampled, raster) for each strategy that carries light.
// Values of strategies with t >= 2 are scaled by the pixel count: they estimate the whole
// film's integral.
template <class Visit>
void bootstrap_sample(const Scene& scene, const PinholeCamera& camera, const BdptOptions& bdpt, uint64_t seed,
                      uint64_t index, Subpaths& paths, TraceCounters& counters, const Visit& visit) {
  IndependentSampler sampler(seed, index, 0);
  const Point2 film = camera.film_position(sampler.next_2d());
  const WalkLimits limits{bdpt.max_depth, bdpt.rr_depth};
  camera_subpath(scene, camera, film.u, film.v, sampler, limits, paths.camera, counters);
  light_subpath(scene, sampler, limits, paths.light, counters);
  const float pixels = static_cast<float>(camera.width()) * static_cast<float>(camera.height());
  for_each_strategy(scene, camera, bdpt, paths, sampler, counters,
                    [&](int s, int t, Color c, const Vertex& sampled, const Point2& raster) {
                      if (t >= 2) c *= pixels;
                      visit(s, t, c, mis_weight(scene, camera, paths.light, paths.camera, sampled, s, t, bdpt.heuristic),
                            sampled, t == 1 ? raster : film);
                    });
}

// The complete path (emitter first) that strategy (s, t) made.
Path strategy_path(const Subpaths& paths, const Vertex& sampled, int s, int t) {
  Path z;
  if (s == 1) {
    z.push_back(sampled);
  } else {
    z.assign(paths.light.begin(), paths.light.begin() + s);
  }
  if (t == 1) {
    z.push_back(sampled);  // the camera vertex
  } else {
    for (int i = t - 1; i >= 0; --i) z.push_back(paths.camera[i]);
  }
  z.front().type = VertexType::Light;
  return z;
}

double weight_of(const Color& c, float mis) {
  const double w = static_cast<double>(std::max(0.f, luminance(c))) * mis;
  return std::isfinite(w) ? w : 0.0;
}

// The importance factor of each pixel for MltImportance::Flattened: the direct light plus a pilot
// estimate of the chains' part from `count` BDPT samples of their own stream (independent of
// the bootstrap, so that b stays unbiased), merged in block order (deterministic).
template <class Elapsed>
PixelImportance pixel_importance(const Scene& scene, const PinholeCamera& camera, const BdptOptions& bdpt,
                                 const MltOptions& opt, const std::vector<double>& direct, size_t wanted,
                                 double seconds, const Elapsed& elapsed, const RenderControl& control,
                                 SharedTraceCounters& rays, size_t& count) {
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  const uint64_t seed = hash_combine(opt.seed, kPilotStream);
  std::vector<std::vector<std::pair<uint32_t, double>>> blocks((wanted + kSampleBlock - 1) / kSampleBlock);
  count = run_sample_blocks(opt.threads, wanted, std::min(wanted, 2 * kSampleBlock), seconds, elapsed, control,
                            [&](size_t block, size_t begin, size_t end) {
                              Subpaths paths;
                              TraceCounters counters = rays.local();
                              for (size_t i = begin; i < end; ++i) {
                                bootstrap_sample(scene, camera, bdpt, seed, i, paths, counters,
                                                 [&](int, int, const Color& c, float mis, const Vertex&,
                                                     const Point2& raster) {
                                                   blocks[block].emplace_back(pixel_of(camera, raster),
                                                                              weight_of(c, mis));
                                                 });
                              }
                              rays.add(counters);
                            });
  // Per pixel: the direct light's luminance plus the pilot's (sum over samples landing there,
  // over the sample count: the chains' image has the same units, its luminance summing to b).
  std::vector<double> lum(pixels, 0.0);
  for (size_t p = 0; p < pixels; ++p) {
    lum[p] = direct.empty() ? 0.0
                            : std::max(0.0, static_cast<double>(luminance(
                                                Color{static_cast<float>(direct[3 * p]), static_cast<float>(direct[3 * p + 1]),
                                                      static_cast<float>(direct[3 * p + 2])})));
  }
  const double inv = 1.0 / static_cast<double>(std::max<size_t>(count, 1));  // blocks past count are empty
  for (const auto& block : blocks) {
    for (const auto& [pixel, w] : block) lum[pixel] += w * inv;
  }
  // A 5x5 box (radius 2) smooths the pilot's noise (about bootstrap / 4 / pixels samples each);
  // the floor of 1 % of the mean keeps pixels the pilot missed reachable at finite cost.
  return PixelImportance(lum, camera.width(), camera.height(), 2, 0.01);
}

// The mutations and their selection weights; a path picks among those that suit it.
class MutationSet {
 public:
  // Without mirrors or glass no path has a specular vertex, and the caustic and multi-chain
  // perturbations suit none: they are left out (and reported) instead of asked at every step.
  MutationSet(const MltOptions& opt, const PinholeCamera& camera, const SceneFeatures& scene) {
    const bool needs_specular = !opt.skip_unneeded || scene.specular;
    const float r_max = opt.lens_radius_max > 0.f ? opt.lens_radius_max : 0.1f * static_cast<float>(camera.width());
    const PerturbationRange film{std::min(opt.lens_radius_min, r_max), r_max};
    const PerturbationRange angle{opt.angle_min, opt.angle_max};
    add(std::make_unique<BidirectionalMutation>(), opt.bidirectional);
    add(std::make_unique<LensSubpathMutation>(), opt.lens_subpath);
    add(std::make_unique<EyePerturbation>(false, film, angle), opt.lens_perturbation);
    add(std::make_unique<CausticPerturbation>(angle), opt.caustic_perturbation, needs_specular);
    add(std::make_unique<EyePerturbation>(true, film, angle), opt.multi_chain_perturbation, needs_specular);
  }
  // Mutations enabled by their weight but left out because the scene cannot use them.
  const std::vector<std::string>& skipped() const { return skipped_; }
  size_t size() const { return mutations_.size(); }
  const Mutation& operator[](size_t i) const { return *mutations_[i]; }
  // Total weight of the mutations that suit x.
  double total(const Path& x) const {
    double sum = 0.0;
    for (size_t i = 0; i < size(); ++i) sum += suitable_weight(i, x);
    return sum;
  }
  double suitable_weight(size_t i, const Path& x) const {
    return weights_[i] > 0.f && mutations_[i]->suitable(x) ? weights_[i] : 0.0;
  }
  // A mutation for x, chosen in proportion to weight among the suitable (one draw from rng),
  // and its probability; size() when none suits x (no draw).
  size_t select(const Path& x, Pcg32& rng, double& probability) const {
    const double sum = total(x);
    if (!(sum > 0.0)) return size();
    double target = rng.next_float() * sum;
    size_t last = 0;
    double last_weight = 0.0;
    for (size_t i = 0; i < size(); ++i) {
      const double w = suitable_weight(i, x);
      if (w <= 0.0) continue;
      last = i;
      last_weight = w;
      if (target < w) break;
      target -= w;
    }
    probability = last_weight / sum;
    return last;
  }

 private:
  void add(std::unique_ptr<Mutation> m, float weight, bool useful = true) {
    if (weight > 0.f && !useful) skipped_.push_back(m->name());
    mutations_.push_back(std::move(m));
    weights_.push_back(useful ? weight : 0.f);
  }
  std::vector<std::unique_ptr<Mutation>> mutations_;
  std::vector<float> weights_;
  std::vector<std::string> skipped_;
};

// T(y -> x) / T(x -> y) as the acceptance uses it; the wrong forms are negative controls.
double transition_ratio(TransitionRatio use, const Transition& t) {
  switch (use) {
    case TransitionRatio::Ignored:
      return 1.0;
    case TransitionRatio::Inverted:
      return t.forward / t.reverse;
    case TransitionRatio::Used:
      break;
  }
  return t.reverse / t.forward;
}

struct Chain {
  Pcg32 rng;
  State current;
};

}  // namespace

PathMltResult render_mlt(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                         RenderControl& control) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto elapsed = [start] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  PathMltResult out;
  MltResult& result = out.result;
  MltStats& mlt = result.mlt;
  std::vector<double> image(3 * pixels, 0.0);      // direct light, then the chains' estimate
  std::vector<double> chain_sum(3 * pixels, 0.0);  // the chains' splats, over all mutations
  const MutationSet mutations(opt, camera, scene.features());
  for (size_t i = 0; i < mutations.size(); ++i) out.mutations.push_back({mutations[i].name(), 0, 0, 0});
  out.skipped_mutations = mutations.skipped();
  SharedTraceCounters rays(connections_unoccluded(scene, camera, opt.skip_unneeded));
  if (opt.direct_spp > 0) {
    const RenderResult direct = render_direct_light(scene, camera, opt, opt.direct_spp, opt.heuristic, control,
                                                    kDirectShare * opt.time_limit);
    const std::vector<float> mean = direct.film.mean();
    std::copy(mean.begin(), mean.end(), image.begin());
    result.direct = direct.stats;
  }
  const bool direct_only = opt.direct_spp > 0 && opt.max_depth >= 0 && opt.max_depth <= 2;
  const BdptOptions bdpt = bootstrap_bdpt(opt);
  const uint64_t boot_seed = hash_combine(opt.seed, kBootstrapStream);
  const size_t n_boot = std::max<uint32_t>(opt.bootstrap, 1);
  std::vector<Chain> chains;
  uint64_t total = 0;
  PixelImportance importance;
  if (!direct_only && opt.importance == MltImportance::Flattened && !control.cancelled()) {
    importance = pixel_importance(scene, camera, bdpt, opt, opt.direct_spp > 0 ? image : std::vector<double>{},
                                  std::max<size_t>(n_boot / 4, 1), kPilotShare * opt.time_limit, elapsed, control,
                                  rays, mlt.pilot_samples);
  }
  if (!direct_only && !control.cancelled()) {
    // Bootstrap: each sample's total weight (the sum over its strategies estimates b).
    std::vector<double> weight(n_boot, 0.0);
    const auto bootstrap_block = [&](size_t, size_t begin, size_t end) {
      Subpaths paths;
      TraceCounters counters = rays.local();
      for (size_t i = begin; i < end; ++i) {
        bootstrap_sample(scene, camera, bdpt, boot_seed, i, paths, counters,
                         [&](int, int, const Color& c, float mis, const Vertex&, const Point2& raster) {
                           weight[i] += weight_of(c, mis) * importance(pixel_of(camera, raster));
                         });
      }
      rays.add(counters);
    };
    // At least 8 blocks under a time limit: b's interval stays within a few per cent.
    const size_t n_done = run_sample_blocks(opt.threads, n_boot, std::min(n_boot, 8 * kSampleBlock),
                                            kBootstrapShare * opt.time_limit, elapsed, control, bootstrap_block);
    weight.resize(n_done);
    const MeanEstimate b = estimate_of(weight);
    mlt.b = mlt.b_splatted = b.mean();
    mlt.b_ci95 = 1.96 * std::sqrt(b.variance_of_mean());
    mlt.independent_samples = b.n;

    const size_t n_chains = std::max<uint32_t>(opt.chains, 1);
    if (mlt.b > 0.0 && !control.cancelled()) {
      // Start states: a bootstrap sample in proportion to its weight, then one of its strategies.
      const DiscreteDistribution pick(weight);
      Subpaths paths;
      TraceCounters counters = rays.local();
      for (size_t c = 0; c < n_chains; ++c) {
        Chain chain{Pcg32(hash_combine(opt.seed, kChainStream), c), {}};
        for (int attempt = 0; attempt < 16 && chain.current.target <= 0.0; ++attempt) {
          float u_pick = chain.rng.next_float();
          const size_t i = pick.sample(u_pick);
          double target_w = chain.rng.next_float() * weight[i];
          bool chosen = false;
          bootstrap_sample(scene, camera, bdpt, boot_seed, i, paths, counters,
                           [&](int s, int t, const Color& col, float mis, const Vertex& sampled,
                               const Point2& raster) {
                             const double w = weight_of(col, mis) * importance(pixel_of(camera, raster));
                             if (chosen || w <= 0.0) return;
                             if (target_w < w) {
                               chain.current.path = strategy_path(paths, sampled, s, t);
                               chosen = true;
                             }
                             target_w -= w;
                           });
          if (chosen) evaluate(camera, importance, chain.current);
        }
        // A chain without a start path would count mutations that splat nothing and darken
        // the image; the others share its mutations.
        if (chain.current.target > 0.0) chains.push_back(std::move(chain));
      }
      rays.add(counters);
    }

    // Rounds: each chain mutates its share; splats merge in chain order.
    const uint64_t target = pixels * opt.spp;  // 0: until the time limit
    control.total.store(target);
    const float scale = static_cast<float>(mlt.b_splatted);
    std::vector<SplatList> splat_lists(chains.size());
    std::vector<std::vector<MutationStats>> counts(chains.size(), out.mutations);
    std::vector<uint64_t> done(chains.size(), 0);
    ChainRounds rounds(chains.size(), target, opt.time_limit);
    while (!chains.empty() && rounds.next(elapsed(), control)) {
      parallel_for_each_index(opt.threads, chains.size(), [&](size_t c) {
        const uint64_t share = rounds.share(c);
        Chain& chain = chains[c];
        TraceCounters counters = rays.local();
        const MutationContext ctx{scene, camera, bdpt.min_depth, opt.max_depth, counters};
        SplatList& splats = splat_lists[c];
        splats.clear();
        done[c] = 0;
        State proposed;
        for (uint64_t m = 0; m < share; ++m) {
          if ((m & 63u) == 0 && control.cancelled()) break;
          ++done[c];
          State& x = chain.current;
          double select_x = 0.0;
          const size_t k = mutations.select(x.path, chain.rng, select_x);
          if (k == mutations.size()) {
            // No enabled mutation suits x (only when bidirectional is off, in tests): staying
            // put is a kernel that keeps f invariant too.
            splats.add(x.pixel, x.f.color * (scale / importance(x.pixel)));
            continue;
          }
          MutationStats& stat = counts[c][k];
          ++stat.proposed;
          Transition t;
          float a = 0.f;
          if (mutations[k].propose(ctx, x.path, chain.rng, proposed.path, t) &&
              evaluate(camera, importance, proposed) && t.forward > 0.0) {
            const double select_y = mutations.suitable_weight(k, proposed.path) / mutations.total(proposed.path);
            const double t_ratio = transition_ratio(opt.transition_ratio, t);
            const double ratio = (proposed.target * t_ratio * select_y) / (x.target * select_x);
            a = std::isfinite(ratio) ? static_cast<float>(std::min(1.0, ratio)) : 0.f;
          } else {
            ++stat.failed;
          }
          // Expected values: each state's f / f* times b, weighted by its acceptance odds (f.color
          // is f / f_lum; f* = f_lum times the pixel's factor).
          if (a > 0.f) splats.add(proposed.pixel, proposed.f.color * (scale * a / importance(proposed.pixel)));
          if (a < 1.f) splats.add(x.pixel, x.f.color * (scale * (1.f - a) / importance(x.pixel)));
          if (a > 0.f && chain.rng.next_float() < a) {
            std::swap(x, proposed);
            ++stat.accepted;
          }
        }
        rays.add(counters);
        control.done.fetch_add(done[c], std::memory_order_relaxed);
      });
      // In chain order, so that the sums do not depend on the schedule.
      uint64_t round = 0;
      for (size_t c = 0; c < chains.size(); ++c) {
        for (const Splat& sp : splat_lists[c].splats()) {
          for (int ch = 0; ch < 3; ++ch) chain_sum[3 * sp.pixel + ch] += sp.value[ch];
        }
        round += done[c];
      }
      if (!rounds.finish(round, elapsed(), control)) break;
    }
    total = rounds.total();
    result.stats.time_limited = rounds.time_limited();
    for (const auto& chain_counts : counts) {
      for (size_t i = 0; i < chain_counts.size(); ++i) {
        out.mutations[i].proposed += chain_counts[i].proposed;
        out.mutations[i].accepted += chain_counts[i].accepted;
        out.mutations[i].failed += chain_counts[i].failed;
      }
    }
  }
  if (total > 0) {
    for (size_t i = 0; i < image.size(); ++i) image[i] += chain_sum[i] / static_cast<double>(total);
  }
  result.image.assign(image.begin(), image.end());
  mlt.mutations = total;
  for (const MutationStats& s : out.mutations) {
    mlt.accepted += s.accepted;
    mlt.zero_proposals += s.failed;
  }
  RenderStats& stats = result.stats;
  stats.seconds = elapsed();
  rays.into(stats);
  stats.samples = total;
  stats.spp = static_cast<uint32_t>(total / pixels);
  stats.interrupted = control.cancelled();
  return out;
}

namespace {

// Every strategy's complete path of the first `count` bootstrap samples (for the test hooks):
// visit(s, t, unweighted contribution, path).
template <class Visit>
void for_each_bootstrap_path(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt, size_t count,
                             const Visit& visit) {
  const BdptOptions bdpt = bootstrap_bdpt(opt);
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
