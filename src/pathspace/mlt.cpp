#include "pathspace/mlt.h"

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <cmath>
#include <atomic>
#include <memory>
#include <utility>

#include "core/distribution.h"
#include "core/mean_estimate.h"
#include "core/parallel.h"
#include "core/stopwatch.h"
#include "pathspace/chain_rounds.h"
#include "pathspace/chain_runner.h"
#include "pathspace/chain_split.h"
#include "pathspace/direct_light.h"
#include "pathspace/mlt_bootstrap.h"
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

double weight_of(const Color& c, float mis) {
  const double w = static_cast<double>(std::max(0.f, luminance(c))) * mis;
  return std::isfinite(w) ? w : 0.0;
}

// The per-pixel luminance MltImportance::Flattened divides by (importance_of): the direct light
// plus a pilot estimate of the chains' part from `count` BDPT samples of their own stream (independent of
// the bootstrap, so that b stays unbiased), merged in block order (deterministic).
template <class Elapsed>
std::vector<double> pilot_luminance(const Scene& scene, const PinholeCamera& camera, const BdptOptions& bdpt,
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
  return lum;
}

PixelImportance importance_of(const ChainStartUp& start, const PinholeCamera& camera) {
  if (start.pilot_luminance.empty()) return {};
  // A 5x5 box (radius 2) smooths the pilot's noise (about bootstrap / 4 / pixels samples each);
  // the floor of 1 % of the mean keeps pixels the pilot missed reachable at finite cost.
  return PixelImportance(start.pilot_luminance, camera.width(), camera.height(), 2, 0.01);
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

struct Chain {
  Pcg32 rng;
  State current;
};

// One chain's mutations of a round: a mutation chosen among those that suit the path, its
// proposal accepted by Metropolis-Hastings with the mutation's transition densities and
// selection probabilities, both states splatted with their expected weights.
struct MltStep {
  const PinholeCamera& camera;
  const MutationSet& mutations;
  const PixelImportance& importance;
  const MltChainHooks& hooks;
  Chain& chain;
  std::vector<MutationStats>& counts;
  float scale;  // b: a state splats f / f* times b
  MutationContext ctx;
  State proposed{};

  void operator()(SplatList& splats) {
    State& x = chain.current;
    double select_x = 0.0;
    const size_t k = mutations.select(x.path, chain.rng, select_x);
    if (k == mutations.size()) {
      // No enabled mutation suits x (only when bidirectional is off, in tests): staying
      // put is a kernel that keeps f invariant too.
      splats.add(x.pixel, x.f.color * (scale / importance(x.pixel)));
      return;
    }
    MutationStats& stat = counts[k];
    ++stat.proposed;
    Transition t;
    float a = 0.f;
    if (mutations[k].propose(ctx, x.path, chain.rng, proposed.path, t) && evaluate(camera, importance, proposed) &&
        t.forward > 0.0) {
      const double select_y = mutations.suitable_weight(k, proposed.path) / mutations.total(proposed.path);
      // T(y -> x) / T(x -> y) of the Metropolis-Hastings acceptance; only a test hook replaces it.
      const double t_ratio = hooks.transition_ratio ? hooks.transition_ratio(t) : t.reverse / t.forward;
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
  void end_round(const SplatList&) const {}
};

// Chain `id`'s start: a bootstrap sample in proportion to its weight, then one of its
// strategies in proportion to theirs (at most 16 tries); its target is 0 if none was found.
Chain start_chain(const Scene& scene, const PinholeCamera& camera, const BdptOptions& bdpt, const MltOptions& opt,
                  const PixelImportance& importance, const ChainPopulation& population,
                  const DiscreteDistribution& pick, uint32_t id, Subpaths& paths, TraceCounters& counters) {
  const uint64_t boot_seed = hash_combine(opt.seed, kBootstrapStream);
  Chain chain{Pcg32(hash_combine(opt.seed, kChainStream), id), {}};
  for (int attempt = 0; attempt < 16 && chain.current.target <= 0.0; ++attempt) {
    float u_pick = chain.rng.next_float();
    const size_t i = pick.sample(u_pick);
    double target_w = chain.rng.next_float() * population.weights[i];
    bool chosen = false;
    bootstrap_sample(scene, camera, bdpt, boot_seed, i, paths, counters,
                     [&](int s, int t, const Color& col, float mis, const Vertex& sampled, const Point2& raster) {
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
  return chain;
}

}  // namespace

// One population of every path length: the chains that found a start path share the mutations.
void check_path_space_supports(const Scene& scene) {
  // A path's vertices are specular or not by their BSDF (full_path.h), so a path through the
  // Dirac lobe of a BSDF that also has a diffuse or glossy one would be evaluated without it.
  if (scene.features().mixed_delta) {
    throw std::invalid_argument(
        "path-space MLT (method 'mlt') does not support BSDFs with both Dirac and diffuse or glossy lobes "
        "(smooth plastic): it would miss the light of the Dirac lobe; use 'pssmlt', 'mmlt' or 'bdpt', or "
        "roughplastic");
  }
}

ChainStartUpShape mlt_start_up_shape(const MltOptions& opt, size_t pixels) {
  ChainStartUpShape shape;
  shape.chains = std::max<uint32_t>(opt.chains, 1);
  shape.mutations = pixels * opt.spp;
  return shape;
}

ChainStartUp mlt_start_up(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                          RenderControl& control, const std::function<double()>& elapsed) {
  check_path_space_supports(scene);
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  ChainStartUp start;
  MltStats& mlt = start.mlt;
  start.image.assign(3 * pixels, 0.0);
  SharedTraceCounters rays(connections_unoccluded(scene, camera, opt.skip_unneeded));
  if (opt.direct_spp > 0) {
    const RenderResult direct = render_direct_light(scene, camera, opt, opt.direct_spp, opt.heuristic, control,
                                                    kDirectShare * opt.time_limit);
    const std::vector<float> mean = direct.film.mean();
    std::copy(mean.begin(), mean.end(), start.image.begin());
    start.direct = direct.stats;
  }
  const bool direct_only = opt.direct_spp > 0 && opt.max_depth >= 0 && opt.max_depth <= 2;
  const BdptOptions bdpt = chain_bdpt(opt);
  const uint64_t boot_seed = hash_combine(opt.seed, kBootstrapStream);
  const size_t n_boot = std::max<uint32_t>(opt.bootstrap, 1);
  if (!direct_only && opt.importance == MltImportance::Flattened && !control.cancelled()) {
    start.pilot_luminance =
        pilot_luminance(scene, camera, bdpt, opt, opt.direct_spp > 0 ? start.image : std::vector<double>{},
                        std::max<size_t>(n_boot / 4, 1), kPilotShare * opt.time_limit, elapsed, control, rays,
                        mlt.pilot_samples);
  }
  const PixelImportance importance = importance_of(start, camera);
  if (!direct_only && !control.cancelled()) {
    // Bootstrap: each sample's total weight (the sum over its strategies estimates b).
    ChainPopulation population;
    std::vector<double>& weight = population.weights;
    weight.assign(n_boot, 0.0);
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
    mlt.b = mlt.b_splatted = population.b_splat = b.mean();
    mlt.b_ci95 = 1.96 * std::sqrt(b.variance_of_mean());
    mlt.independent_samples = b.n;
    if (mlt.b > 0.0 && !control.cancelled()) {
      // A chain without a start path would count mutations that splat nothing and darken the
      // image: only the chains that find one run, and they share the mutations.
      const DiscreteDistribution pick(weight);
      Subpaths paths;
      TraceCounters counters = rays.local();
      for (uint32_t id = 0; id < std::max<uint32_t>(opt.chains, 1) && !control.cancelled(); ++id) {
        if (start_chain(scene, camera, bdpt, opt, importance, population, pick, id, paths, counters).current.target >
            0.0) {
          population.chain_ids.push_back(id);
        }
      }
      rays.add(counters);
      population.chains = population.chain_ids.size();
      population.target = pixels * opt.spp;  // 0: until the time limit
    }
    start.populations.push_back(std::move(population));
  }
  start.cancelled = control.cancelled();
  rays.into(start.stats);
  start.stats.seconds = elapsed();
  return start;
}

namespace {

// mlt_chains, with render_mlt's hooks.
ChainPart run_chains(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                     const ChainStartUp& start, uint64_t first, uint64_t count, RenderControl& control,
                     const std::function<double()>& elapsed, const MltChainHooks& hooks) {
  check_path_space_supports(scene);
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  check_chain_start_up(start, pixels, mlt_start_up_shape(opt, pixels));
  ChainPart part = empty_part(start, first, count);
  first = part.first_chain;
  const MutationSet mutations(opt, camera, scene.features());
  for (size_t i = 0; i < mutations.size(); ++i) part.mutations.push_back({mutations[i].name(), 0, 0, 0});
  SharedTraceCounters rays(connections_unoccluded(scene, camera, opt.skip_unneeded));
  if (part.chains == 0) {
    rays.into(part.stats);
    return part;
  }
  const ChainPopulation& population = start.populations.front();  // the only one
  if (population.weights.empty() || population.chain_ids.size() != population.chains) {
    throw std::invalid_argument("the chain start-up holds no bootstrap or chain seeds for these chains");
  }
  PopulationPart& pop = part.populations.front();
  const BdptOptions bdpt = chain_bdpt(opt);
  const PixelImportance importance = importance_of(start, camera);
  std::vector<Chain> chains;
  {
    const DiscreteDistribution pick(population.weights);
    Subpaths paths;
    TraceCounters counters = rays.local();
    for (uint64_t c = first; c < first + part.chains && !control.cancelled(); ++c) {
      chains.push_back(start_chain(scene, camera, bdpt, opt, importance, population, pick,
                                   population.chain_ids[c], paths, counters));
    }
    rays.add(counters);
  }

  // Rounds: each chain mutates its share; splats merge into exact sums.
  ChainRounds rounds(population.chains, first, chains.size(), population.target, opt.time_limit);
  control.total.store(rounds.range_target());
  pop.metropolis = ExactSums(3 * pixels, population.b_splat);
  const float scale = static_cast<float>(population.b_splat);
  std::vector<std::vector<MutationStats>> counts(chains.size(), part.mutations);
  uint64_t rejected = 0;  // splats too large for the exact sums
  run_chain_rounds(
      opt.threads, chains.size(), rounds, elapsed, control, rays,
      [&](size_t c, TraceCounters& counters) {
        const MutationContext ctx{scene, camera, bdpt.min_depth, opt.max_depth, counters};
        return MltStep{camera, mutations, importance, hooks, chains[c], counts[c], scale, ctx};
      },
      [&](size_t, const SplatList& splats) {
        for (const Splat& sp : splats.splats()) {
          for (int ch = 0; ch < 3; ++ch) rejected += !pop.metropolis.add(3 * sp.pixel + ch, sp.value[ch]);
        }
        rejected += splats.invalid();
      });
  pop.mutations = rounds.total();
  for (const auto& chain_counts : counts) {
    for (size_t i = 0; i < chain_counts.size(); ++i) {
      part.mutations[i].proposed += chain_counts[i].proposed;
      part.mutations[i].accepted += chain_counts[i].accepted;
      part.mutations[i].failed += chain_counts[i].failed;
    }
  }
  for (const MutationStats& s : part.mutations) {
    pop.accepted += s.accepted;
    pop.zero_proposals += s.failed;
  }
  RenderStats& stats = part.stats;
  rays.into(stats);
  stats.invalid_samples = rejected;
  stats.samples = pop.mutations;
  stats.time_limited = rounds.time_limited();
  stats.interrupted = control.cancelled();
  return part;
}

}  // namespace

ChainPart mlt_chains(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                     const ChainStartUp& start, uint64_t first, uint64_t count, RenderControl& control,
                     const std::function<double()>& elapsed) {
  return run_chains(scene, camera, opt, start, first, count, control, elapsed, {});
}

PathMltResult mlt_finish(const Scene& scene, const ChainStartUp& start, const ChainPart& part,
                         const MltOptions& opt, const PinholeCamera& camera) {
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  check_chain_start_up(start, pixels, mlt_start_up_shape(opt, pixels));
  check_chain_part(start, part, 3 * pixels);
  PathMltResult out;
  MltResult& result = out.result;
  result.direct = start.direct;
  MltStats& mlt = result.mlt;
  mlt = start.mlt;
  std::vector<double> image = start.image;
  const MutationSet mutations(opt, camera, scene.features());
  out.skipped_mutations = mutations.skipped();
  out.mutations = part.mutations;
  if (out.mutations.empty()) {
    for (size_t i = 0; i < mutations.size(); ++i) out.mutations.push_back({mutations[i].name(), 0, 0, 0});
  }
  const uint64_t total = part.populations.empty() ? 0 : part.populations.front().mutations;
  if (total > 0) {
    const ExactSums& chain_sum = part.populations.front().metropolis;
    for (size_t i = 0; i < image.size(); ++i) image[i] += chain_sum.value(i) / static_cast<double>(total);
  }
  result.image = chain_image(image);
  mlt.mutations = total;
  for (const MutationStats& s : out.mutations) {
    mlt.accepted += s.accepted;
    mlt.zero_proposals += s.failed;
  }
  result.stats = chain_render_stats(start, part, total, pixels);
  return out;
}

PathMltResult render_mlt(const Scene& scene, const PinholeCamera& camera, const MltOptions& opt,
                         RenderControl& control, const MltChainHooks& hooks) {
  const std::function<double()> elapsed = Stopwatch();
  const ChainStartUp start = mlt_start_up(scene, camera, opt, control, elapsed);
  const ChainPart part = run_chains(scene, camera, opt, start, 0, start.chains(), control, elapsed, hooks);
  PathMltResult out = mlt_finish(scene, start, part, opt, camera);
  out.result.stats.seconds = elapsed();
  return out;
}

}  // namespace dualight
