#include "pathspace/pssmlt.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <functional>
#include <vector>

#include "core/distribution.h"
#include "core/parallel.h"
#include "core/primary_sample_sampler.h"
#include "pathspace/bdpt_sample.h"

namespace dualight {

namespace {

constexpr uint64_t kBootstrapStream = 0x51ed'2701'a3c4'9b1full;
constexpr uint64_t kChainStream = 0x2c9f'77d3'0e41'b58aull;

// What one BDPT sample contributes to the film: the own pixel's value scaled by the pixel count
// (the film position is uniform over the film) and the light-tracing splats; f is their total
// luminance.
struct Contribution {
  std::vector<Splat> splats;
  float f = 0.f;
};

// depth 0: a whole BDPT sample, every strategy (Kelemen's PSSMLT). depth d > 0: one strategy of
// the paths of d segments, chosen by the first number (multiplexed MLT, Hachisuka et al. 2014),
// its MIS-weighted contribution divided by the strategy's probability.
class Evaluator {
 public:
  Evaluator(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt, int depth)
      : scene_(scene), camera_(camera), depth_(depth) {
    bdpt_.max_depth = opt.max_depth;
    bdpt_.rr_depth = opt.rr_depth;
    bdpt_.heuristic = opt.heuristic;
    bdpt_.min_depth = opt.direct_spp > 0 ? 3 : 1;
  }

  void operator()(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters) {
    if (depth_ > 0) {
      one_strategy(sampler, out, counters);
      return;
    }
    const Point2 u = sampler.next_2d();
    const float w = static_cast<float>(camera_.width()), h = static_cast<float>(camera_.height());
    const float x = std::min(u.u * w, std::nextafter(w, 0.f)), y = std::min(u.v * h, std::nextafter(h, 0.f));
    splats_.clear();
    const Color L = bdpt_sample(scene_, camera_, bdpt_, x, y, sampler, paths_, counters, splats_, nullptr);
    out.splats.clear();
    invalid_ += splats_.invalid();
    const uint32_t pixel = static_cast<uint32_t>(y) * camera_.width() + static_cast<uint32_t>(x);
    if (!is_finite(L)) {
      ++invalid_;  // dropped and counted, as the pixel driver does
    } else if (!is_black(L)) {
      out.splats.push_back({pixel, 0, L * (w * h)});
    }
    for (const Splat& s : splats_.splats()) out.splats.push_back(s);
    double f = 0.0;
    for (const Splat& s : out.splats) f += std::max(0.f, luminance(s.value));
    out.f = std::isfinite(f) ? static_cast<float>(f) : 0.f;
  }
  uint64_t invalid() const { return invalid_; }

 private:
  void one_strategy(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters) {
    out.splats.clear();
    out.f = 0.f;
    const int d = depth_;
    const int n = d == 1 ? 1 : d + 1;  // (s, t) with s + t = d + 1, t >= 1; (1, 1) only as (0, 2)
    const int s = d == 1 ? 0 : std::min(static_cast<int>(sampler.next_1d() * static_cast<float>(n)), n - 1);
    const int t = d + 1 - s;
    const Point2 u = sampler.next_2d();
    const float w = static_cast<float>(camera_.width()), h = static_cast<float>(camera_.height());
    const float x = std::min(u.u * w, std::nextafter(w, 0.f)), y = std::min(u.v * h, std::nextafter(h, 0.f));
    // Subpaths of exactly t and s vertices (no Russian roulette: the strategy fixes the length).
    camera_subpath(scene_, camera_, x, y, sampler, WalkLimits{t - 1, 1 << 30}, paths_.camera, counters);
    if (static_cast<int>(paths_.camera.size()) != t) return;
    sampler.start_stream(1);
    paths_.light.clear();
    if (s > 0) {
      light_subpath(scene_, sampler, WalkLimits{s, 1 << 30}, paths_.light, counters);
      if (static_cast<int>(paths_.light.size()) != s) return;
    }
    sampler.start_stream(2);
    Vertex sampled;
    Point2 raster{};
    Color c = connect(scene_, camera_, paths_.light, paths_.camera, s, t, sampler, sampled, raster, counters);
    if (is_black(c)) return;
    c *= mis_weight(scene_, camera_, paths_.light, paths_.camera, sampled, s, t, bdpt_.heuristic) *
         static_cast<float>(n);
    if (!is_finite(c)) {
      ++invalid_;
      return;
    }
    if (t == 1) {
      out.splats.push_back(
          {static_cast<uint32_t>(raster.v) * camera_.width() + static_cast<uint32_t>(raster.u), 0, c});
    } else {
      out.splats.push_back(
          {static_cast<uint32_t>(y) * camera_.width() + static_cast<uint32_t>(x), 0, c * (w * h)});
    }
    out.f = std::max(0.f, luminance(out.splats.back().value));
  }

  const Scene& scene_;
  const PinholeCamera& camera_;
  int depth_;
  BdptOptions bdpt_;
  Subpaths paths_;
  SplatList splats_;
  uint64_t invalid_ = 0;
};

struct Chain {
  PrimarySampleSampler sampler;
  Pcg32 rng;  // acceptance decisions
  Contribution current;
};

// Independent samples (large steps from fresh samplers): their f values, by sample index.
template <class MakeEvaluator>
std::vector<double> bootstrap(const MakeEvaluator& make, const PssmltOptions& opt, uint64_t seed, size_t n,
                              RenderControl& control, std::atomic<uint64_t>& rays, std::atomic<uint64_t>& invalid) {
  std::vector<double> f(n, 0.0);
  parallel_for_each_index(opt.threads, (n + 1023) / 1024, [&](size_t block) {
    if (control.cancelled()) return;
    auto evaluate = make();
    Contribution c;
    TraceCounters counters;
    for (size_t i = block * 1024; i < std::min(n, (block + 1) * 1024); ++i) {
      PrimarySampleSampler sampler(seed, i, opt.sigma, opt.large_step_probability);
      sampler.start_large_step();
      evaluate(sampler, c, counters);
      f[i] = c.f;
    }
    rays.fetch_add(counters.rays, std::memory_order_relaxed);
    invalid.fetch_add(evaluate.invalid(), std::memory_order_relaxed);
  });
  return f;
}

struct Population {
  uint64_t mutations = 0, accepted = 0, large_steps = 0, large_steps_accepted = 0, zero_proposals = 0;
  double large_f = 0.0, large_f_sq = 0.0;  // f of the large steps' proposals (independent samples)
  bool time_limited = false;
};

// Chains started from bootstrap samples chosen in proportion to f (no start-up bias), mutated
// in rounds until `target` mutations (0: until the time limit); every mutation splats the
// current and proposed states' contributions times `scale` / f, weighted by their acceptance
// probabilities, and counts as one path of the film's normalisation.
template <class MakeEvaluator>
Population run_chains(const MakeEvaluator& make, const PssmltOptions& opt, const std::vector<double>& f_boot,
                      uint64_t boot_seed, uint64_t chain_seed, size_t n_chains, uint64_t target, float scale,
                      const std::function<double()>& elapsed, RenderControl& control, Film& film,
                      std::atomic<uint64_t>& rays, std::atomic<uint64_t>& invalid) {
  Population pop;
  const DiscreteDistribution pick(f_boot);
  std::vector<Chain> chains;
  chains.reserve(n_chains);
  {
    auto evaluate = make();
    TraceCounters counters;
    for (size_t c = 0; c < n_chains; ++c) {
      Pcg32 rng(chain_seed, c);
      float u = rng.next_float();
      const size_t i = pick.sample(u);
      Chain chain{PrimarySampleSampler(boot_seed, i, opt.sigma, opt.large_step_probability), rng, {}};
      chain.sampler.start_large_step();
      evaluate(chain.sampler, chain.current, counters);
      chain.sampler.accept();
      chain.sampler.reseed(hash_combine(chain_seed, 1), c);
      chains.push_back(std::move(chain));
    }
    rays.fetch_add(counters.rays, std::memory_order_relaxed);
  }
  const bool unbounded = target == 0;
  std::vector<SplatList> out(n_chains);
  std::vector<double> large_f(n_chains, 0.0), large_f_sq(n_chains, 0.0);
  std::vector<uint64_t> done(n_chains, 0), accepted(n_chains, 0), large(n_chains, 0), large_acc(n_chains, 0),
      zero(n_chains, 0);
  uint64_t total = 0;
  uint64_t per_chain = 16;
  while ((unbounded || total < target) && !control.cancelled()) {
    if (opt.time_limit > 0.0 && elapsed() >= opt.time_limit) {
      pop.time_limited = true;
      break;
    }
    const double round_start = elapsed();
    const uint64_t remaining = unbounded ? UINT64_MAX : target - total;
    parallel_for_each_index(opt.threads, n_chains, [&](size_t c) {
      // Chain c's share of this round: remaining mutations split evenly, the first ones take the rest.
      const uint64_t share =
          unbounded ? per_chain : std::min<uint64_t>(per_chain, remaining / n_chains + (c < remaining % n_chains));
      Chain& chain = chains[c];
      auto evaluate = make();
      Contribution proposed;
      TraceCounters counters;
      SplatList& splats = out[c];
      splats.clear();
      done[c] = 0;
      for (uint64_t m = 0; m < share; ++m) {
        if ((m & 63u) == 0 && control.cancelled()) break;
        chain.sampler.start_iteration();
        const bool large_step = chain.sampler.large_step();
        evaluate(chain.sampler, proposed, counters);
        const float a = chain.current.f > 0.f ? std::min(1.f, proposed.f / chain.current.f) : 1.f;
        if (proposed.f > 0.f) {
          for (const Splat& sp : proposed.splats) splats.add(sp.pixel, sp.value * (scale * a / proposed.f));
        } else {
          ++zero[c];
        }
        if (chain.current.f > 0.f && a < 1.f) {
          for (const Splat& sp : chain.current.splats) {
            splats.add(sp.pixel, sp.value * (scale * (1.f - a) / chain.current.f));
          }
        }
        if (large_step) {
          ++large[c];
          large_f[c] += proposed.f;
          large_f_sq[c] += static_cast<double>(proposed.f) * proposed.f;
        }
        if (proposed.f > 0.f && chain.rng.next_float() < a) {
          std::swap(chain.current, proposed);
          chain.sampler.accept();
          ++accepted[c];
          large_acc[c] += large_step;
        } else {
          chain.sampler.reject();
        }
        ++done[c];
      }
      rays.fetch_add(counters.rays, std::memory_order_relaxed);
      invalid.fetch_add(evaluate.invalid(), std::memory_order_relaxed);
      control.done.fetch_add(done[c], std::memory_order_relaxed);
    });
    uint64_t round = 0;
    for (size_t c = 0; c < n_chains; ++c) {
      film.add_splats(out[c], done[c]);
      round += done[c];
    }
    total += round;
    if (control.cancelled() || round == 0) break;
    const double per_mutation = std::max(elapsed() - round_start, 1e-6) / static_cast<double>(round);
    per_chain = static_cast<uint64_t>(std::clamp(0.25 / per_mutation / n_chains, 1.0, 1e6));
  }
  pop.mutations = total;
  for (size_t c = 0; c < n_chains; ++c) {
    pop.accepted += accepted[c];
    pop.large_steps += large[c];
    pop.large_steps_accepted += large_acc[c];
    pop.zero_proposals += zero[c];
    pop.large_f += large_f[c];
    pop.large_f_sq += large_f_sq[c];
  }
  return pop;
}

void add_population(MltStats& mlt, const Population& pop) {
  mlt.mutations += pop.mutations;
  mlt.accepted += pop.accepted;
  mlt.large_steps += pop.large_steps;
  mlt.large_steps_accepted += pop.large_steps_accepted;
  mlt.zero_proposals += pop.zero_proposals;
}

// Emitters seen directly and direct light by BDPT, when asked for; true when that is all.
bool render_direct(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt, MltResult& result,
                   RenderControl& control) {
  if (opt.direct_spp == 0) return false;
  BdptOptions direct;
  static_cast<EstimatorOptions&>(direct) = opt;
  direct.spp = opt.direct_spp;
  direct.time_limit = 0.0;
  direct.max_depth = opt.max_depth < 0 ? 2 : std::min(opt.max_depth, 2);
  direct.heuristic = opt.heuristic;
  direct.seed = hash_combine(opt.seed, 0xd1ec7ull);
  result.direct = render_bdpt(scene, camera, direct, control);
  control.done.store(0);
  if (control.cancelled() || (opt.max_depth >= 0 && opt.max_depth <= 2)) {
    result.render.stats = result.direct.stats;
    return true;
  }
  return false;
}

}  // namespace

MltResult render_pssmlt(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt,
                        RenderControl& control) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const std::function<double()> elapsed = [start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  MltResult result{{Film(camera.width(), camera.height()), {}}, {Film(camera.width(), camera.height()), {}}, {}};
  if (render_direct(scene, camera, opt, result, control)) return result;
  MltStats& mlt = result.mlt;
  const uint64_t pixels = static_cast<uint64_t>(camera.width()) * camera.height();
  const uint64_t target = pixels * opt.spp;  // 0: until the time limit
  control.total.store(target);
  std::atomic<uint64_t> rays{0}, invalid{0};
  const size_t n_boot = std::max<uint32_t>(opt.bootstrap, 1);
  const size_t n_chains = std::max<uint32_t>(opt.chains, 1);

  if (opt.multiplexed) {
    // Multiplexed MLT: one population of chains per path length d, each with its own b_d from
    // its bootstrap; chains and mutations are allocated in proportion to b_d, deterministically,
    // so the brightness does not depend on which lengths the chains happened to visit.
    const int first = opt.direct_spp > 0 ? 3 : 1;
    std::vector<double> b(static_cast<size_t>(opt.max_depth) + 1, 0.0), var(b.size(), 0.0);
    std::vector<std::vector<double>> f_boot(b.size());
    double b_total = 0.0, var_total = 0.0;
    for (int d = first; d <= opt.max_depth; ++d) {
      const auto make = [&, d] { return Evaluator(scene, camera, opt, d); };
      f_boot[d] = bootstrap(make, opt, hash_combine(opt.seed, kBootstrapStream + d), n_boot, control, rays, invalid);
      double sum = 0.0, sum_sq = 0.0;
      for (const double f : f_boot[d]) {
        sum += f;
        sum_sq += f * f;
      }
      b[d] = sum / static_cast<double>(n_boot);
      var[d] = std::max(0.0, (sum_sq - sum * b[d]) / std::max(1.0, static_cast<double>(n_boot - 1))) / n_boot;
      b_total += b[d];
      var_total += var[d];
    }
    mlt.b = mlt.b_splatted = b_total;
    mlt.b_ci95 = 1.96 * std::sqrt(var_total);
    mlt.independent_samples = n_boot * static_cast<uint64_t>(std::max(0, opt.max_depth - first + 1));
    if (b_total > 0.0) {
      std::vector<uint64_t> targets(b.size(), 0);
      uint64_t target_sum = 0;
      for (int d = first; d <= opt.max_depth; ++d) {
        if (b[d] > 0.0) targets[d] = std::max<uint64_t>(1, std::llround(static_cast<double>(target) * b[d] / b_total));
        target_sum += targets[d];
      }
      for (int d = first; d <= opt.max_depth && !control.cancelled(); ++d) {
        if (targets[d] == 0) continue;
        const auto make = [&, d] { return Evaluator(scene, camera, opt, d); };
        const size_t chains_d = std::max<size_t>(1, static_cast<size_t>(std::llround(n_chains * b[d] / b_total)));
        // Splats of length d carry b_d times its share of the normalisation: the film divides by
        // the sum of all targets.
        const float scale = static_cast<float>(b[d] * static_cast<double>(target_sum) / targets[d]);
        const Population pop = run_chains(make, opt, f_boot[d], hash_combine(opt.seed, kBootstrapStream + d),
                                          hash_combine(opt.seed, kChainStream + d), chains_d, targets[d], scale,
                                          elapsed, control, result.render.film, rays, invalid);
        add_population(mlt, pop);
      }
    }
  } else {
    const auto make = [&] { return Evaluator(scene, camera, opt, 0); };
    const uint64_t boot_seed = hash_combine(opt.seed, kBootstrapStream);
    const std::vector<double> f_boot = bootstrap(make, opt, boot_seed, n_boot, control, rays, invalid);
    double sum = 0.0, sum_sq = 0.0;
    for (const double f : f_boot) {
      sum += f;
      sum_sq += f * f;
    }
    mlt.b_splatted = sum / static_cast<double>(n_boot);
    if (mlt.b_splatted > 0.0) {
      const Population pop =
          run_chains(make, opt, f_boot, boot_seed, hash_combine(opt.seed, kChainStream), n_chains, target,
                     static_cast<float>(mlt.b_splatted), elapsed, control, result.render.film, rays, invalid);
      add_population(mlt, pop);
      result.render.stats.time_limited = pop.time_limited;
      sum += pop.large_f;
      sum_sq += pop.large_f_sq;
      // b from the bootstrap and every large step (independent samples too, Kelemen et al.).
      const double n = static_cast<double>(n_boot + pop.large_steps);
      mlt.independent_samples = n_boot + pop.large_steps;
      mlt.b = sum / n;
      mlt.b_ci95 = 1.96 * std::sqrt(std::max(0.0, (sum_sq - sum * mlt.b) / std::max(n - 1.0, 1.0)) / n);
    }
  }
  RenderStats& stats = result.render.stats;
  stats.seconds = elapsed();
  stats.rays = rays.load();
  stats.invalid_samples = invalid.load();
  stats.samples = mlt.mutations;
  stats.spp = static_cast<uint32_t>(mlt.mutations / pixels);
  stats.interrupted = control.cancelled();
  return result;
}

}  // namespace dualight
