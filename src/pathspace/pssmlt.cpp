#include "pathspace/pssmlt.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <vector>

#include "core/distribution.h"
#include "core/parallel.h"
#include "core/primary_sample_sampler.h"
#include "pathspace/bdpt_sample.h"

namespace dualight {

namespace {

constexpr uint64_t kBootstrapStream = 0x51ed'2701'a3c4'9b1full;
constexpr uint64_t kChainStream = 0x2c9f'77d3'0e41'b58aull;

float luminance(const Color& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

// What one BDPT sample contributes to the film: the own pixel's value scaled by the pixel count
// (the film position is uniform over the film) and the light-tracing splats; f is their total
// luminance.
struct Contribution {
  std::vector<Splat> splats;
  float f = 0.f;
};

class Evaluator {
 public:
  Evaluator(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt)
      : scene_(scene), camera_(camera) {
    bdpt_.max_depth = opt.max_depth;
    bdpt_.rr_depth = opt.rr_depth;
    bdpt_.heuristic = opt.heuristic;
    bdpt_.min_depth = opt.direct_spp > 0 ? 3 : 1;
  }

  void operator()(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters) {
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
  const Scene& scene_;
  const PinholeCamera& camera_;
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

}  // namespace

MltResult render_pssmlt(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& opt,
                        RenderControl& control) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };
  MltResult result{{Film(camera.width(), camera.height()), {}}, {Film(camera.width(), camera.height()), {}}, {}};
  if (opt.direct_spp > 0) {
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
      return result;
    }
  }
  MltStats& mlt = result.mlt;
  const uint64_t pixels = static_cast<uint64_t>(camera.width()) * camera.height();
  std::atomic<uint64_t> rays{0}, invalid{0};

  // 1. Bootstrap: independent samples estimate b and are the chains' candidate start states.
  const size_t n_boot = std::max<uint32_t>(opt.bootstrap, 1);
  std::vector<double> f_boot(n_boot, 0.0);
  parallel_for_each_index(opt.threads, (n_boot + 1023) / 1024, [&](size_t block) {
    Evaluator evaluate(scene, camera, opt);
    Contribution c;
    TraceCounters counters;
    for (size_t i = block * 1024; i < std::min(n_boot, (block + 1) * 1024); ++i) {
      PrimarySampleSampler sampler(hash_combine(opt.seed, kBootstrapStream), i, opt.sigma,
                                   opt.large_step_probability);
      sampler.start_large_step();
      evaluate(sampler, c, counters);
      f_boot[i] = c.f;
    }
    rays.fetch_add(counters.rays, std::memory_order_relaxed);
    invalid.fetch_add(evaluate.invalid(), std::memory_order_relaxed);
  });
  double sum = 0.0, sum_sq = 0.0;
  for (const double f : f_boot) {
    sum += f;
    sum_sq += f * f;
  }
  mlt.b_splatted = sum / static_cast<double>(n_boot);
  if (!(mlt.b_splatted > 0.0)) {
    result.render.stats.seconds = elapsed();
    return result;  // nothing reaches the camera: a black image
  }

  // 2. Chains start from bootstrap samples chosen in proportion to f (no start-up bias).
  const DiscreteDistribution pick(f_boot);
  const size_t n_chains = std::max<uint32_t>(opt.chains, 1);
  std::vector<Chain> chains;
  chains.reserve(n_chains);
  {
    Evaluator evaluate(scene, camera, opt);
    TraceCounters counters;
    for (size_t c = 0; c < n_chains; ++c) {
      Pcg32 rng(hash_combine(opt.seed, kChainStream), c);
      float u = rng.next_float();
      const size_t i = pick.sample(u);
      Chain chain{PrimarySampleSampler(hash_combine(opt.seed, kBootstrapStream), i, opt.sigma,
                                       opt.large_step_probability),
                  rng, {}};
      chain.sampler.start_large_step();
      evaluate(chain.sampler, chain.current, counters);
      chain.sampler.accept();
      chain.sampler.reseed(hash_combine(opt.seed, kChainStream + 1), c);
      chains.push_back(std::move(chain));
    }
    rays.fetch_add(counters.rays, std::memory_order_relaxed);
  }

  // 3. Rounds of mutations on every chain; each chain's splats are added in chain order.
  const bool unbounded = opt.spp == 0;
  const uint64_t target = unbounded ? 0 : pixels * opt.spp;
  control.total.store(target);
  const float scale = static_cast<float>(mlt.b_splatted);
  std::vector<double> large_f(n_chains, 0.0), large_f_sq(n_chains, 0.0);
  std::vector<SplatList> out(n_chains);
  std::vector<uint64_t> done(n_chains, 0), accepted(n_chains, 0), large(n_chains, 0), large_acc(n_chains, 0),
      zero(n_chains, 0);
  uint64_t total = 0;
  uint64_t per_chain = 16;
  while ((unbounded || total < target) && !control.cancelled()) {
    if (opt.time_limit > 0.0 && elapsed() >= opt.time_limit) {
      result.render.stats.time_limited = true;
      break;
    }
    const double round_start = elapsed();
    const uint64_t remaining = unbounded ? UINT64_MAX : target - total;
    parallel_for_each_index(opt.threads, n_chains, [&](size_t c) {
      // Chain c's share of this round: remaining mutations split evenly, the first ones take the rest.
      const uint64_t share =
          unbounded ? per_chain : std::min<uint64_t>(per_chain, remaining / n_chains + (c < remaining % n_chains));
      Chain& chain = chains[c];
      Evaluator evaluate(scene, camera, opt);
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
          for (const Splat& s : proposed.splats) splats.add(s.pixel, s.value * (scale * a / proposed.f));
        } else {
          ++zero[c];
        }
        if (chain.current.f > 0.f && a < 1.f) {
          for (const Splat& s : chain.current.splats) {
            splats.add(s.pixel, s.value * (scale * (1.f - a) / chain.current.f));
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
      result.render.film.add_splats(out[c], done[c]);
      round += done[c];
    }
    total += round;
    if (control.cancelled() || round == 0) break;
    const double per_mutation = std::max(elapsed() - round_start, 1e-6) / static_cast<double>(round);
    per_chain = static_cast<uint64_t>(std::clamp(0.25 / per_mutation / n_chains, 1.0, 1e6));
  }

  mlt.mutations = total;
  for (size_t c = 0; c < n_chains; ++c) {
    mlt.accepted += accepted[c];
    mlt.large_steps += large[c];
    mlt.large_steps_accepted += large_acc[c];
    mlt.zero_proposals += zero[c];
    sum += large_f[c];
    sum_sq += large_f_sq[c];
  }
  const double n = static_cast<double>(n_boot + mlt.large_steps);
  mlt.independent_samples = n_boot + mlt.large_steps;
  mlt.b = sum / n;
  mlt.b_ci95 = 1.96 * std::sqrt(std::max(0.0, (sum_sq - sum * mlt.b) / std::max(n - 1.0, 1.0)) / n);
  RenderStats& stats = result.render.stats;
  stats.seconds = elapsed();
  stats.rays = rays.load();
  stats.invalid_samples = invalid.load();
  stats.samples = total;
  stats.spp = static_cast<uint32_t>(total / pixels);
  stats.interrupted = control.cancelled();
  return result;
}

}  // namespace dualight
