#include "pathspace/pssmlt.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <utility>
#include <vector>

#include "core/apportion.h"
#include "core/distribution.h"
#include "pathspace/shadow_ray.h"
#include "core/mean_estimate.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "core/primary_sample_sampler.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/chain_rounds.h"
#include "pathspace/chain_runner.h"
#include "pathspace/chain_split.h"
#include "pathspace/direct_light.h"
#include "pathspace/mmlt.h"
#include "pathspace/primary_sample_contribution.h"
#include "pathspace/start_up.h"

namespace dualight {

namespace {

constexpr uint64_t kBootstrapStream = 0x51ed'2701'a3c4'9b1full;
constexpr uint64_t kChainStream = 0x2c9f'77d3'0e41'b58aull;

// A whole BDPT sample from the primary samples, every strategy (Kelemen's PSSMLT; depth 0).
class BdptSampleEvaluator {
 public:
  BdptSampleEvaluator(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt)
      : scene_(scene), camera_(camera), bdpt_(chain_bdpt(opt)) {}

  void operator()(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters) {
    const Point2 film = camera_.film_position(sampler.next_2d());
    const float x = film.u, y = film.v;
    const float pixels = static_cast<float>(camera_.width()) * static_cast<float>(camera_.height());
    splats_.clear();
    const Color L = bdpt_sample(scene_, camera_, bdpt_, x, y, sampler, paths_, counters, splats_, nullptr);
    out.splats.clear();
    invalid_ += splats_.invalid();
    const uint32_t pixel = static_cast<uint32_t>(y) * camera_.width() + static_cast<uint32_t>(x);
    if (!is_finite(L)) {
      ++invalid_;  // dropped and counted, as the pixel driver does
    } else if (!is_black(L)) {
      out.splats.push_back({pixel, 0, L * pixels});
    }
    for (const Splat& s : splats_.splats()) out.splats.push_back(s);
    double f = 0.0;
    for (const Splat& s : out.splats) f += std::max(0.f, luminance(s.value));
    out.f = std::isfinite(f) ? static_cast<float>(f) : 0.f;
  }
  uint64_t invalid() const { return invalid_; }

 private:
  const Scene& scene_;
  const PinholeCamera& camera_;
  BdptOptions bdpt_;
  Subpaths paths_;
  SplatList splats_;
  uint64_t invalid_ = 0;
};

// Calls f(make) with a factory of the evaluator of population depth d: a whole BDPT sample (0)
// or one strategy of the paths of d segments (MMLT, mmlt.h).
template <class F>
void with_evaluator(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt, int d, const F& f) {
  if (d == 0) {
    f([&] { return BdptSampleEvaluator(scene, camera, opt); });
  } else {
    f([&, d] { return StrategyEvaluator(scene, camera, opt, d); });
  }
}

struct Chain {
  PrimarySampleSampler sampler;
  Pcg32 rng;  // acceptance decisions
  Contribution current;
};

// Independent samples of f: the mean, with the variance of the mean from their spread.
// Independent samples (large steps from fresh samplers): their f values, by sample index.
// With seconds > 0 (a share of the time limit, start_up.h), fewer than n if that runs out.
template <class MakeEvaluator, class Elapsed>
std::vector<double> bootstrap(const MakeEvaluator& make, const PssmltOptions& opt, uint64_t seed, size_t n,
                              double seconds, const Elapsed& elapsed, RenderControl& control,
                              SharedTraceCounters& rays, std::atomic<uint64_t>& invalid) {
  std::vector<double> f(n, 0.0);
  const size_t done = run_sample_blocks(opt.threads, n, std::min(n, 8 * kSampleBlock), seconds, elapsed, control,
                                        [&](size_t, size_t begin, size_t end) {
                                          auto evaluate = make();
                                          Contribution c;
                                          TraceCounters counters = rays.local();
                                          for (size_t i = begin; i < end; ++i) {
                                            PrimarySampleSampler sampler(seed, i, opt.sigma,
                                                                         opt.large_step_probability);
                                            sampler.start_large_step();
                                            evaluate(sampler, c, counters);
                                            f[i] = c.f;
                                          }
                                          rays.add(counters);
                                          invalid.fetch_add(evaluate.invalid(), std::memory_order_relaxed);
                                        });
  f.resize(done);
  return f;
}

// Splat layers of the chains: the Metropolis part and the large steps' own part (see run_chains).
constexpr uint32_t kMetropolisLayer = 0, kLargeStepLayer = 1;

uint64_t bootstrap_seed(const PssmltOptions& opt, int depth) {
  return hash_combine(opt.seed, kBootstrapStream + static_cast<uint64_t>(depth));
}
uint64_t chain_seed(const PssmltOptions& opt, int depth) {
  return hash_combine(opt.seed, kChainStream + static_cast<uint64_t>(depth));
}

// What a state's h is multiplied by, before its weight a, 1 - a or L (see run_chains).
struct SplatScale {
  bool large_step_mis;
  float b, p_large;
  float operator()(float f) const { return large_step_mis ? 1.f / (f / b + p_large) : b / f; }
};

// One chain's mutations of a round: Kelemen's proposal (a small or large step of the primary
// samples), accepted with probability min(1, f(y) / f(x)), both states splatted.
template <class Evaluate>
struct PssmltStep {
  const PssmltOptions& opt;
  const SplatScale& per_h;
  Chain& chain;
  Evaluate evaluate;
  TraceCounters& counters;
  MeanEstimate& large_f;
  uint64_t &accepted, &large_acc, &zero;
  std::atomic<uint64_t>& invalid;
  Contribution proposed{};

  void operator()(SplatList& splats) {
    chain.sampler.start_iteration();
    const bool large_step = chain.sampler.large_step();
    evaluate(chain.sampler, proposed, counters);
    const float a = chain.current.f > 0.f ? std::min(1.f, proposed.f / chain.current.f) : 1.f;
    if (proposed.f > 0.f) {
      const float k = per_h(proposed.f);
      for (const Splat& sp : proposed.splats) {
        splats.add(sp.pixel, sp.value * (a * k), kMetropolisLayer);
        if (large_step && opt.large_step_mis) splats.add(sp.pixel, sp.value * k, kLargeStepLayer);
      }
    } else {
      ++zero;
    }
    if (chain.current.f > 0.f && a < 1.f) {
      const float k = (1.f - a) * per_h(chain.current.f);
      for (const Splat& sp : chain.current.splats) splats.add(sp.pixel, sp.value * k, kMetropolisLayer);
    }
    if (large_step) large_f.add(proposed.f);
    if (proposed.f > 0.f && chain.rng.next_float() < a) {
      std::swap(chain.current, proposed);
      chain.sampler.accept();
      ++accepted;
      large_acc += large_step;
    } else {
      chain.sampler.reject();
    }
  }
  void end_round(const SplatList& splats) {
    invalid.fetch_add(evaluate.invalid() + splats.invalid(), std::memory_order_relaxed);
  }
};

// Chains [lo, hi) of a population, started from bootstrap samples chosen in proportion to f (no
// start-up bias), mutated in rounds until their quotas of the population's target (0: none) or
// the `deadline` (seconds of `elapsed`; 0: none), after a first round of 4 mutations per chain.
// The estimate of M mutations, with h a state's contribution to the film and f its luminance, x
// the current state, y the proposal:
//  * plain (Veach's expected values): y with weight a, x with 1 - a, each splatting h / f
//    times b* / M. In the stationary chain these are samples of density f / b*, b* = E[f], M of
//    them; b* is known only by its estimate, so they splat with the bootstrap's b_splat and
//    the sum is rescaled to the final b (add_estimate).
//  * large_step_mis [Kelemen et al. 2002 sec. 4]: each large step's proposal (probability p
//    per mutation, so p M in expectation) is also a uniform sample, density 1. The
//    multi-sample balance heuristic over the two techniques [Veach97 sec. 9.2] gives every
//    sample h / (M (f / b* + p)). MIS weights only need to sum to one, so they may use b_splat
//    (fixed before the chains run) for b*: w_chain = (f / b) / (f / b + p), w_large = p / (f / b + p).
//    Then a large step adds w_large h / (p M) = h / (M (f / b + p)), unbiased whatever b is; a
//    chain sample adds w_chain h b* / (M f) = h / (M (f / b + p)) times b* / b, rescaled to the
//    final b like the plain estimate. So y splats (a + L) h / (f / b + p) (a in the Metropolis
//    layer; L = 1 for a large step, in the large-step layer) and x (1 - a) h / (f / b + p);
//    with p = 0 this is the plain estimate.
// Returns whether the deadline stopped them.
template <class MakeEvaluator>
bool run_chains(const MakeEvaluator& make, const PssmltOptions& opt, const ChainPopulation& population, uint64_t lo,
                uint64_t hi, double deadline, size_t pixels, const std::function<double()>& elapsed,
                RenderControl& control, SharedTraceCounters& rays, std::atomic<uint64_t>& invalid,
                PopulationPart& pop) {
  const size_t n_chains = hi - lo;
  pop.metropolis = ExactSums(3 * pixels, population.b_splat);
  if (opt.large_step_mis) pop.large = ExactSums(3 * pixels, population.b_splat);
  const uint64_t boot_seed = bootstrap_seed(opt, population.depth);
  const uint64_t seed = chain_seed(opt, population.depth);
  const DiscreteDistribution pick(population.weights);
  std::vector<Chain> chains;
  chains.reserve(n_chains);
  {
    auto evaluate = make();
    TraceCounters counters = rays.local();
    for (uint64_t c = lo; c < hi && !control.cancelled(); ++c) {
      Pcg32 rng(seed, c);
      float u = rng.next_float();
      const size_t i = pick.sample(u);
      Chain chain{PrimarySampleSampler(boot_seed, i, opt.sigma, opt.large_step_probability), rng, {}};
      chain.sampler.start_large_step();
      evaluate(chain.sampler, chain.current, counters);
      chain.sampler.accept();
      chain.sampler.reseed(hash_combine(seed, 1), c);
      chains.push_back(std::move(chain));
    }
    rays.add(counters);
  }
  if (chains.size() < n_chains) return false;  // Ctrl-C while the chains started
  const SplatScale per_h{opt.large_step_mis, static_cast<float>(population.b_splat), opt.large_step_probability};
  pop.large_f.assign(n_chains, MeanEstimate{});
  std::vector<uint64_t> accepted(n_chains, 0), large_acc(n_chains, 0), zero(n_chains, 0);
  ChainRounds rounds(population.chains, lo, n_chains, population.target, deadline);
  uint64_t rejected = 0;  // splats too large for the exact sums
  run_chain_rounds(
      opt.threads, n_chains, rounds, elapsed, control, rays,
      [&](size_t c, TraceCounters& counters) {
        return PssmltStep<decltype(make())>{opt, per_h, chains[c], make(), counters,
                                            pop.large_f[c], accepted[c], large_acc[c], zero[c], invalid};
      },
      [&](size_t, const SplatList& splats) {
        for (const Splat& sp : splats.splats()) {
          ExactSums& sum = sp.layer == kMetropolisLayer ? pop.metropolis : pop.large;
          for (int ch = 0; ch < 3; ++ch) rejected += !sum.add(3 * sp.pixel + ch, sp.value[ch]);
        }
      });
  invalid.fetch_add(rejected, std::memory_order_relaxed);
  pop.mutations = rounds.total();
  for (size_t c = 0; c < n_chains; ++c) {
    pop.accepted += accepted[c];
    pop.large_steps += pop.large_f[c].n;
    pop.large_steps_accepted += large_acc[c];
    pop.zero_proposals += zero[c];
  }
  return rounds.time_limited();
}

// Adds a population's estimate to `image`: its Metropolis layer rescaled from the b it was
// splatted with to the final b, its large-step layer as it is (see run_chains), over its mutations.
void add_estimate(const PopulationPart& pop, double b_splat, double b_final, std::vector<double>& image) {
  if (pop.mutations == 0) return;
  const double m = static_cast<double>(pop.mutations);
  const double k = b_final / b_splat / m;
  for (size_t i = 0; i < image.size(); ++i) image[i] += pop.metropolis.value(i) * k;
  for (size_t i = 0; i < pop.large.size(); ++i) image[i] += pop.large.value(i) / m;
}

void add_population(MltStats& mlt, const PopulationPart& pop) {
  mlt.mutations += pop.mutations;
  mlt.accepted += pop.accepted;
  mlt.large_steps += pop.large_steps;
  mlt.large_steps_accepted += pop.large_steps_accepted;
  mlt.zero_proposals += pop.zero_proposals;
}

// Emitters seen directly and direct light by BDPT, when asked for; true when that is all.
bool render_direct(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt, ChainStartUp& start,
                   RenderControl& control) {
  if (opt.direct_spp == 0) return false;
  const RenderResult r = render_direct_light(scene, camera, opt, opt.direct_spp, opt.heuristic, control,
                                             kDirectShare * opt.time_limit);
  const std::vector<float> mean = r.film.mean();
  std::copy(mean.begin(), mean.end(), start.image.begin());
  start.direct = r.stats;
  return control.cancelled() || (opt.max_depth >= 0 && opt.max_depth <= 2);
}

}  // namespace

// One population of depth 0 (every path length), or with multiplexed MLT one per path length
// from 1 (3 when BDPT renders the direct light apart) to max_depth.
ChainStartUpShape pssmlt_start_up_shape(const PssmltOptions& opt, size_t pixels) {
  ChainStartUpShape shape;
  shape.chains = std::max<uint32_t>(opt.chains, 1);
  shape.mutations = pixels * opt.spp;
  if (opt.multiplexed) {
    shape.first_depth = opt.direct_spp > 0 ? 3 : 1;
    shape.last_depth = opt.max_depth;
    shape.populations = opt.max_depth >= shape.first_depth ? static_cast<size_t>(opt.max_depth - shape.first_depth + 1) : 0;
  }
  return shape;
}

ChainStartUp pssmlt_start_up(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt,
                             RenderControl& control, const std::function<double()>& elapsed) {
  ChainStartUp start;
  MltStats& mlt = start.mlt;
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  start.image.assign(3 * pixels, 0.0);
  SharedTraceCounters rays(connections_unoccluded(scene, camera, opt.skip_unneeded));
  std::atomic<uint64_t> invalid{0};
  if (!render_direct(scene, camera, opt, start, control)) {
    const uint64_t target = pixels * opt.spp;  // 0: until the time limit
    control.total.store(target);
    const size_t n_boot = std::max<uint32_t>(opt.bootstrap, 1);
    const size_t n_chains = std::max<uint32_t>(opt.chains, 1);
    // One population of depth 0 (every path length), or with multiplexed MLT one per path length
    // d, each with its own b_d from its bootstrap; chains, mutations and time are allocated in
    // proportion to the bootstrap b_d, deterministically, so the brightness does not depend on
    // which lengths the chains happened to visit. Each b_d is then refined by its chains' large
    // steps, and its population's Metropolis part rescaled to it.
    const ChainStartUpShape shape = pssmlt_start_up_shape(opt, pixels);
    const int first = shape.first_depth, last = shape.last_depth;
    double b_total = 0.0;
    for (int d = first; d <= last; ++d) {
      // Under a time limit the lengths share the bootstrap's share.
      const double seconds = kBootstrapShare * opt.time_limit / static_cast<double>(last - first + 1);
      ChainPopulation p;
      p.depth = d;
      with_evaluator(scene, camera, opt, d, [&](const auto& make) {
        p.weights = bootstrap(make, opt, bootstrap_seed(opt, d), n_boot, seconds, elapsed, control, rays, invalid);
      });
      p.b_splat = estimate_of(p.weights).mean();
      b_total += p.b_splat;
      start.populations.push_back(std::move(p));
    }
    mlt.b_splatted = b_total;
    std::vector<double> b_per_depth;
    for (const ChainPopulation& p : start.populations) b_per_depth.push_back(p.b_splat);
    const std::vector<uint64_t> chains = apportion(n_chains, b_per_depth, 1);
    const std::vector<uint64_t> targets = apportion(target, b_per_depth, target > 0 ? 1 : 0);
    for (size_t i = 0; i < start.populations.size(); ++i) {
      ChainPopulation& p = start.populations[i];
      if (!(p.b_splat > 0.0)) continue;
      p.chains = opt.multiplexed ? chains[i] : n_chains;
      p.target = opt.multiplexed ? targets[i] : target;
    }
    // Smallest b_d first: each length gets its share of the time left, so the overrun of a
    // length's last round falls on the larger shares after it, where it matters least.
    std::stable_sort(start.populations.begin(), start.populations.end(),
                     [](const ChainPopulation& i, const ChainPopulation& j) { return i.b_splat < j.b_splat; });
    uint64_t next_chain = 0;
    for (ChainPopulation& p : start.populations) {
      p.first_chain = next_chain;
      next_chain += p.chains;
    }
  }
  start.cancelled = control.cancelled();
  rays.into(start.stats);
  start.stats.invalid_samples = invalid.load();
  start.stats.seconds = elapsed();
  return start;
}

ChainPart pssmlt_chains(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt,
                        const ChainStartUp& start, uint64_t first, uint64_t count, RenderControl& control,
                        const std::function<double()>& elapsed) {
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  check_chain_start_up(start, pixels, pssmlt_start_up_shape(opt, pixels));
  ChainPart part = empty_part(start, first, count);
  first = part.first_chain;
  // The range's chains in population p: [lo, hi) in the population's own indices.
  const auto range_in = [&, end = first + part.chains](const ChainPopulation& p) {
    const auto local = [&](uint64_t c) {
      return std::clamp(c, p.first_chain, p.first_chain + p.chains) - p.first_chain;
    };
    return std::pair<uint64_t, uint64_t>{local(first), local(end)};
  };
  SharedTraceCounters rays(connections_unoccluded(scene, camera, opt.skip_unneeded));
  std::atomic<uint64_t> invalid{0};
  uint64_t total = 0;
  for (const ChainPopulation& p : start.populations) {
    const auto [lo, hi] = range_in(p);
    total += ChainRounds(p.chains, lo, hi - lo, p.target, 0.0).range_target();
  }
  control.total.store(total);
  double b_left = 0.0;
  for (const ChainPopulation& p : start.populations) b_left += p.b_splat;
  for (size_t i = 0; i < start.populations.size(); ++i) {
    const ChainPopulation& p = start.populations[i];
    if (p.chains == 0) continue;
    double deadline = 0.0;
    if (opt.time_limit > 0.0) {
      const double now = elapsed();
      deadline = now + std::max(0.0, opt.time_limit - now) * std::min(1.0, p.b_splat / b_left);
      b_left -= p.b_splat;
    }
    const auto [lo, hi] = range_in(p);
    if (lo >= hi || control.cancelled()) continue;
    if (p.weights.empty()) throw std::invalid_argument("the chain start-up holds no bootstrap for these chains");
    with_evaluator(scene, camera, opt, p.depth, [&](const auto& make) {
      part.stats.time_limited |= run_chains(make, opt, p, lo, hi, deadline, pixels, elapsed, control, rays,
                                            invalid, part.populations[i]);
    });
  }
  RenderStats& stats = part.stats;
  rays.into(stats);
  stats.invalid_samples = invalid.load();
  for (const PopulationPart& p : part.populations) stats.samples += p.mutations;
  stats.interrupted = control.cancelled();
  return part;
}

MltResult pssmlt_finish(const ChainStartUp& start, const ChainPart& part, const PssmltOptions& opt,
                        const PinholeCamera& camera) {
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  check_chain_start_up(start, pixels, pssmlt_start_up_shape(opt, pixels));
  check_chain_part(start, part, 3 * pixels);
  MltResult result;
  result.direct = start.direct;
  MltStats& mlt = result.mlt;
  mlt.b_splatted = start.mlt.b_splatted;
  std::vector<double> image = start.image;
  if (opt.multiplexed && !start.populations.empty()) {
    const size_t depths = static_cast<size_t>(opt.max_depth) + 1;
    mlt.b_per_depth.assign(depths, 0.0);
    mlt.b_per_depth_ci95.assign(depths, 0.0);
    mlt.mutations_per_depth.assign(depths, 0);
  }
  double var_total = 0.0;
  for (size_t i = 0; i < start.populations.size(); ++i) {
    const ChainPopulation& p = start.populations[i];
    MeanEstimate b = estimate_of(p.weights);
    if (i < part.populations.size()) {
      const PopulationPart& pop = part.populations[i];
      MeanEstimate large_f;  // large steps are independent samples too (Kelemen et al.)
      for (const MeanEstimate& e : pop.large_f) large_f += e;
      b += large_f;
      add_population(mlt, pop);
      if (p.b_splat > 0.0) add_estimate(pop, p.b_splat, b.mean(), image);
      if (opt.multiplexed) mlt.mutations_per_depth[static_cast<size_t>(p.depth)] = pop.mutations;
    }
    if (opt.multiplexed) {
      mlt.b_per_depth[static_cast<size_t>(p.depth)] = b.mean();
      mlt.b_per_depth_ci95[static_cast<size_t>(p.depth)] = 1.96 * std::sqrt(b.variance_of_mean());
    }
    mlt.b += b.mean();
    var_total += b.variance_of_mean();
    mlt.independent_samples += b.n;
  }
  mlt.b_ci95 = 1.96 * std::sqrt(var_total);
  result.image = chain_image(image);
  result.stats = chain_render_stats(start, part, mlt.mutations, pixels);
  return result;
}

MltResult render_pssmlt(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt,
                        RenderControl& control) {
  const std::function<double()> elapsed = Stopwatch();
  const ChainStartUp start = pssmlt_start_up(scene, camera, opt, control, elapsed);
  const ChainPart part = pssmlt_chains(scene, camera, opt, start, 0, start.chains(), control, elapsed);
  MltResult result = pssmlt_finish(start, part, opt, camera);
  result.stats.seconds = elapsed();
  return result;
}

}  // namespace dualight
