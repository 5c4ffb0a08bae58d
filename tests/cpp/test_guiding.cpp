// The SD-tree guide (guiding/): the quadtree's density integrates to one and is the density of
// its samples; a tree is the same whatever order its records come in; the BSDF fraction is
// learnt only from enough records; adjoint-driven roulette keeps the expectation; Russian roulette
// keeps the paths the guide sent where it learnt light comes from, and a guided refraction
// reports its eta to the roulette; the trial after
// training picks the more efficient of a guided and an unguided pass, unless they disagree, and
// runs during the training before the iteration predicted to be its last.
#include <algorithm>
#include <cmath>
#include <vector>

#include "check.h"
#include "core/rng.h"
#include "guiding/adjoint_rr.h"
#include "guiding/guide_training.h"
#include "guiding/guided_sampling.h"
#include "guiding/guiding_trial.h"
#include "guiding/sd_tree.h"
#include "lobe_records.h"
#include "pathspace/russian_roulette.h"

using namespace dualight;

TEST_CASE("quadtree_density_integrates_to_one_and_matches_its_samples") {
  GuideRecords records = lobe_records(20000, normalize(Vec3(0.3f, -0.5f, 0.8f)), 1);
  sort_by_square_code(records.data(), records.data() + records.size());
  const DirectionalQuadtree d(records.data(), records.data() + records.size(), 0.01f, 16);
  REQUIRE(!d.empty());
  CHECK(d.node_count() > 10);
  // The integral of pdf_w over the sphere, on a fine grid of the square (4 pi per unit area).
  const int grid = 512;
  double integral = 0.0;
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) integral += d.pdf_square({(i + 0.5f) / grid, (j + 0.5f) / grid});
  }
  CHECK_NEAR(integral / (grid * grid), 1.0, 2e-3);
  // Samples fall in 16 x 16 cells of the square as often as the density says.
  const int cells = 16, n = 400000;
  std::vector<double> observed(cells * cells, 0.0), expected(cells * cells, 0.0);
  Pcg32 rng(3, 4);
  for (int k = 0; k < n; ++k) {
    const Point2 s = direction_to_square(d.sample({rng.next_float(), rng.next_float()}));
    observed[std::min(cells - 1, static_cast<int>(s.u * cells)) * cells + std::min(cells - 1, static_cast<int>(s.v * cells))] += 1;
  }
  for (int i = 0; i < grid; ++i) {
    for (int j = 0; j < grid; ++j) {
      expected[(i * cells / grid) * cells + j * cells / grid] +=
          d.pdf_square({(i + 0.5f) / grid, (j + 0.5f) / grid}) * n / (grid * grid);
    }
  }
  double chi2 = 0.0;
  int dof = 0;
  for (int c = 0; c < cells * cells; ++c) {
    if (expected[c] < 20.0) continue;
    chi2 += (observed[c] - expected[c]) * (observed[c] - expected[c]) / expected[c];
    ++dof;
  }
  // Cells of 1/256 of the square average the grid's own error in; chi2 / dof about 1.
  CHECK(dof > 100);
  CHECK(chi2 / dof < 1.5);
  // The density of a sample is pdf_w at its direction: mean of 1 / pdf over samples = 4 pi
  // (the measure of the support, the whole sphere where every cell has value here).
  double inv = 0.0;
  for (int k = 0; k < 200000; ++k) inv += 1.0 / d.pdf_w(d.sample({rng.next_float(), rng.next_float()}));
  CHECK_NEAR(inv / 200000 / (4.0 * kPi), 1.0, 0.02);
  // The density sample() reports is pdf_w at its direction (the round trip lands in the same cell
  // but within a float's rounding of a cell's edge).
  int same = 0;
  for (int k = 0; k < 100000; ++k) {
    float pdf = 0.f;
    const Vec3 w = d.sample({rng.next_float(), rng.next_float()}, &pdf);
    same += pdf == d.pdf_w(w) ? 1 : 0;
  }
  CHECK(same >= 99990);
}

TEST_CASE("direction_to_square_agrees_with_libm") {
  // The map's azimuth comes from a polynomial atan2: within two float steps of libm's near 1
  // (1.2e-7 of the square, 7.5e-7 rad), far below the finest cell (1/65536).
  Pcg32 rng(5, 6);
  float worst = 0.f;
  for (int k = 0; k < 1000000; ++k) {
    const Vec3 w = square_to_direction({rng.next_float(), rng.next_float()});
    float v = std::atan2(w.y, w.x) * (0.5f * kInvPi);
    if (v < 0.f) v += 1.f;
    float dv = std::abs(direction_to_square(w).v - v);
    worst = std::max(worst, std::min(dv, 1.f - dv));
  }
  CHECK(worst <= 1.2e-7f);
  CHECK(direction_to_square({1.f, 0.f, 0.f}).v == 0.f);
  CHECK(direction_to_square({0.f, 1.f, 0.f}).v == doctest::Approx(0.25f));
  CHECK(direction_to_square({-1.f, 0.f, 0.f}).v == doctest::Approx(0.5f));
  CHECK(direction_to_square({0.f, -1.f, 0.f}).v == doctest::Approx(0.75f));
}

TEST_CASE("sd_tree_is_the_same_for_records_in_any_order") {
  GuideRecords a = lobe_records(50000, normalize(Vec3(-0.2f, 0.9f, 0.1f)), 5);
  GuideRecords b = a;
  std::reverse(b.begin(), b.end());
  std::rotate(b.begin(), b.begin() + 12345, b.end());
  SdTreeSettings settings;
  settings.spatial_threshold = 4000;
  const SdTree ta(a, Vec3(0.f), Vec3(1.f), settings), tb(b, Vec3(0.f), Vec3(1.f), settings);
  CHECK(ta.leaves() > 8);
  CHECK(ta.leaves() == tb.leaves());
  CHECK(ta.directional_nodes() == tb.directional_nodes());
  Pcg32 rng(9, 9);
  bool same = true;
  for (int k = 0; k < 10000; ++k) {
    const Vec3 p{rng.next_float(), rng.next_float(), rng.next_float()};
    const Vec3 w = square_to_direction({rng.next_float(), rng.next_float()});
    same &= ta.at(p).directions.pdf_w(w) == tb.at(p).directions.pdf_w(w);
    same &= ta.at(p).bsdf_fraction == tb.at(p).bsdf_fraction;
  }
  CHECK(same);
}

TEST_CASE("bsdf_fraction_is_learnt_only_from_enough_records") {
  // Records sampled uniformly (pdf_sampled = pdf_bsdf = 1 / 4 pi) whose integrand is a sharp
  // lobe, judged with the guide of an earlier tree built from other records of the same lobe: the
  // guide matches the lobe far better than the BSDF, so the fraction is low (not the least
  // allowed: the earlier guide misses some of these records' bright outliers).
  GuideRecords earlier = lobe_records(5000, Vec3(0.f, 0.f, 1.f), 10);
  GuideRecords many = lobe_records(5000, Vec3(0.f, 0.f, 1.f), 11);
  SdTreeSettings settings;
  settings.spatial_threshold = 1u << 30;
  settings.bsdf_fraction = 0.3f;
  const SdTree previous(earlier, Vec3(0.f), Vec3(1.f), settings);
  CHECK(previous.at(Vec3(0.5f)).bsdf_fraction == 1.f);  // the first tree: nothing to judge its guide by
  const SdTree guided(many, Vec3(0.f), Vec3(1.f), settings, &previous);
  CHECK(guided.at(Vec3(0.5f)).bsdf_fraction >= 0.3f);
  CHECK(guided.at(Vec3(0.5f)).bsdf_fraction <= 0.5f);
  // Records whose integrand is the BSDF's own density: the guide adds nothing, fraction 1.
  GuideRecords flat = many;
  for (GuideRecord& r : flat) r.product = r.pdf_bsdf;
  CHECK(SdTree(flat, Vec3(0.f), Vec3(1.f), settings, &previous).at(Vec3(0.5f)).bsdf_fraction ==
        doctest::Approx(1.f));
  // Fewer than 16 records that carried anything: no guiding.
  GuideRecords few(many.begin(), many.begin() + 10);
  CHECK(SdTree(few, Vec3(0.f), Vec3(1.f), settings, &previous).at(Vec3(0.5f)).bsdf_fraction == 1.f);
}

TEST_CASE("adjoint_roulette_keeps_the_expectation_and_its_bounds") {
  const AdjointRouletteSettings s;  // window 5: [centre / 3, 5 centre / 3]
  // Where an estimate is missing, the caller's own roulette applies.
  CHECK(!adjoint_roulette(1.f, 0.f, 1.f, 1, 0.5f, s).known);
  CHECK(!adjoint_roulette(1.f, 1.f, 0.f, 1, 0.5f, s).known);
  // Centre = pixel / adjoint = 2: inside the window the path goes on as it is.
  const RouletteOrSplit inside = adjoint_roulette(2.5f, 0.5f, 1.f, 1, 0.99f, s);
  CHECK(inside.known);
  CHECK(inside.paths == 1);
  CHECK(inside.scale == 1.f);
  // Far above: split into throughput / centre paths of 1 / n the throughput each, at most
  // max_paths over the whole sample.
  const RouletteOrSplit above = adjoint_roulette(9.f, 0.5f, 1.f, 1, 0.5f, s);
  CHECK(above.paths == 5);
  CHECK(above.scale == doctest::Approx(0.2f));
  CHECK(adjoint_roulette(1000.f, 0.5f, 1.f, 1, 0.5f, s).paths == s.max_paths);
  CHECK(adjoint_roulette(1000.f, 0.5f, 1.f, 8, 0.5f, s).paths == 2);
  CHECK(adjoint_roulette(1000.f, 0.5f, 1.f, s.max_paths, 0.5f, s).paths == 1);
  // Far below: survival max(min_survival, throughput / centre), the survivor's weight its
  // reciprocal, so the expected weight stays 1 (the mean over a fine grid of u).
  for (const float throughput : {0.5f, 0.01f}) {
    double mean = 0.0;
    const int n = 100000;
    for (int k = 0; k < n; ++k) {
      const RouletteOrSplit r = adjoint_roulette(throughput, 0.5f, 1.f, 1, (k + 0.5f) / n, s);
      mean += r.paths * r.scale;
    }
    CHECK(mean / n == doctest::Approx(1.0).epsilon(1e-3));
  }
  const RouletteOrSplit low = adjoint_roulette(0.01f, 0.5f, 1.f, 1, 0.f, s);
  CHECK(low.scale == doctest::Approx(1.f / s.min_survival));
}

// A Lambertian vertex (albedo 0.5) guided by a quadtree that learnt light from a 15-degree cone
// around its normal, at the depth where Russian roulette starts: how often a path goes into the
// cone and survives the roulette, guided (bsdf_fraction 0.5) and by the BSDF alone. The roulette on
// the BSDF's throughput (russian_roulette.h) keeps the guide's gain; on the guided throughput it
// would stop guided paths in proportion to their density and undo it.
TEST_CASE("russian_roulette_keeps_the_paths_the_guide_sent") {
  const Vec3 lobe(0.f, 0.f, 1.f);
  GuideRecords records = lobe_records(20000, lobe, 5);
  sort_by_square_code(records.data(), records.data() + records.size());
  const DirectionalQuadtree quadtree(records.data(), records.data() + records.size(), 0.01f, 16);
  const Bsdf bsdf = Lambertian{Color(0.5f)};
  const Frame frame = Frame::from_normal(lobe);
  const Vec3 wo(0.f, 0.f, 1.f);
  const VertexGuide guided{&quadtree, 0.5f}, unguided{};
  const float cone = std::cos(15.f * kPi / 180.f);
  const int n = 200000;
  // E[in the cone x survival] for a guide, with the roulette on the BSDF's throughput and on the
  // sample's own.
  const auto survivors_in_cone = [&](const VertexGuide& g, double& on_bsdf, double& on_own) {
    Pcg32 rng(11, 2);
    on_bsdf = on_own = 0.0;
    for (int k = 0; k < n; ++k) {
      BsdfSample bs;
      float ratio;
      const float u = rng.next_float();
      if (!sample_guided(bsdf, frame, g, wo, u, {rng.next_float(), rng.next_float()}, TransportMode::Radiance, bs,
                         ratio)) {
        continue;
      }
      if (dot(frame.to_world(bs.wi), lobe) < cone) continue;
      on_bsdf += roulette_survival(bs.weight, ratio) / n;
      on_own += roulette_survival(bs.weight) / n;
    }
  };
  double guided_bsdf, guided_own, plain_bsdf, plain_own;
  survivors_in_cone(guided, guided_bsdf, guided_own);
  survivors_in_cone(unguided, plain_bsdf, plain_own);
  CHECK(plain_bsdf == doctest::Approx(plain_own));  // unguided: the same roulette
  CHECK(guided_bsdf > 3.0 * plain_bsdf);            // the guide's gain survives the roulette
  CHECK(guided_own < 1.2 * plain_own);              // the control: on its own throughput it does not
  MESSAGE("in the cone and surviving: guided " << guided_bsdf << " (on its own throughput " << guided_own
                                                << "), unguided " << plain_bsdf);
}

// Frosted glass (GGX 0.3, IOR 1.5) guided towards a lobe across its surface: a direction the
// guide picks through the glass reports the refraction's eta, as one BSDF sampling picks does, so
// the camera path's roulette undoes its 1 / eta^2 (russian_roulette.h) whichever strategy sampled
// it. From above the ratio is 1.5, from below 1 / 1.5; reflections report 1.
TEST_CASE("a_guided_refraction_reports_its_eta") {
  const Bsdf glass = RoughDielectric{Microfacet{MicrofacetType::GGX, 0.3f, 0.3f}, 1.5f};
  const Frame frame = Frame::from_normal(Vec3(0.f, 0.f, 1.f));
  for (const float side : {1.f, -1.f}) {
    GuideRecords records = lobe_records(20000, Vec3(0.f, 0.f, -side), 9);  // across the surface
    sort_by_square_code(records.data(), records.data() + records.size());
    const DirectionalQuadtree quadtree(records.data(), records.data() + records.size(), 0.01f, 16);
    const VertexGuide guide{&quadtree, 0.5f};
    const Vec3 wo = normalize(Vec3(0.3f, 0.f, side));
    const float through = side > 0.f ? 1.5f : 1.f / 1.5f;
    Pcg32 rng(3, 5);
    int guided_through = 0, bsdf_through = 0, wrong = 0;
    for (int k = 0; k < 20000; ++k) {
      const bool by_guide = k % 2 == 0;  // u_select past bsdf_fraction picks the guide
      BsdfSample bs;
      float ratio;
      const float u_select = by_guide ? 0.75f : 0.25f;
      if (!sample_guided(glass, frame, guide, wo, u_select, {rng.next_float(), rng.next_float()},
                         TransportMode::Radiance, bs, ratio)) {
        continue;
      }
      const bool refracted = bs.wi.z * wo.z < 0.f;
      if (refracted) ++(by_guide ? guided_through : bsdf_through);
      if (bs.eta != (refracted ? through : 1.f) || bs.eta != refraction_eta(glass, wo, bs.wi)) ++wrong;
    }
    CHECK(wrong == 0);
    CHECK(guided_through > 1000);  // the guide did send paths through the glass
    CHECK(bsdf_through > 1000);
  }
  // Members that do not bend light report 1 on either side.
  CHECK(refraction_eta(Bsdf{Lambertian{Color(0.5f)}}, Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, -1.f)) == 1.f);
  CHECK(refraction_eta(Bsdf{ThinDielectric{1.5f}}, Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, -1.f)) == 1.f);
  CHECK(refraction_eta(Bsdf{Dielectric{1.5f}}, Vec3(0.f, 0.f, 1.f), Vec3(0.f, 0.f, -1.f)) == 1.5f);
}

// A pass of a synthetic estimator: every pixel's samples are 1 + sigma * (a standard normal), and
// the pass "took" seconds_per_sample per sample.
static RenderStats synthetic_pass(Film& film, uint32_t spp, uint64_t seed, double sigma, double seconds_per_sample) {
  Pcg32 rng(seed, 7);
  for (size_t p = 0; p < film.pixel_count(); ++p) {
    for (uint32_t k = 0; k < spp; ++k) {
      // Box-Muller: a standard normal from two uniforms.
      const double u1 = std::max(1e-12, static_cast<double>(rng.next_float())), u2 = rng.next_float();
      const float v = static_cast<float>(1.0 + sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307 * u2));
      film.add_sample(p, Color(v, v, v));
    }
    film.end_block(p);
  }
  RenderStats s;
  s.spp = spp;
  s.samples = spp * film.pixel_count();
  s.seconds = seconds_per_sample * static_cast<double>(s.samples);
  return s;
}

// A pass whose samples are 1 / p with probability p and else 0 (mean 1, variance 1 / p - 1): at
// a few samples per pixel most pixels see none of the rare ones, and its variance looks small.
static RenderStats heavy_tailed_pass(Film& film, uint32_t spp, uint64_t seed, double p) {
  Pcg32 rng(seed, 11);
  for (size_t i = 0; i < film.pixel_count(); ++i) {
    for (uint32_t k = 0; k < spp; ++k) {
      const float v = rng.next_float() < p ? static_cast<float>(1.0 / p) : 0.f;
      film.add_sample(i, Color(v, v, v));
    }
    film.end_block(i);
  }
  RenderStats s;
  s.spp = spp;
  s.samples = spp * film.pixel_count();
  s.seconds = static_cast<double>(s.samples);
  return s;
}

TEST_CASE("guiding_trial_picks_the_pass_of_least_variance_times_time") {
  EstimatorOptions est;
  est.spp = 0;
  est.time_limit = 1.0;
  GuidingOptions g;
  // Efficiency is 1 / (variance x time): guided 1 / (0.25 x 2) = 2, unguided 1 / (1 x 1) = 1.
  const auto run = [&](double sigma_guided, double cost_guided) {
    return run_guiding_trial(est, g, 32, true, 64, 64, [&](bool guided, uint32_t spp, uint64_t seed, Film& film) {
      return guided ? synthetic_pass(film, spp, seed, sigma_guided, cost_guided) : synthetic_pass(film, spp, seed, 1.0, 1.0);
    });
  };
  const std::optional<GuidingTrial> pays = run(0.5, 2.0);
  REQUIRE(pays);
  CHECK(pays->spp == 64);
  CHECK(pays->films.size() == 2);
  CHECK(pays->efficiency_ratio == doctest::Approx(2.0).epsilon(0.1));
  CHECK(pays->guided);
  // The control: the same variance at 6x the time is a third as efficient, and loses.
  const std::optional<GuidingTrial> loses = run(0.5, 6.0);
  REQUIRE(loses);
  CHECK(loses->efficiency_ratio == doctest::Approx(2.0 / 3.0).epsilon(0.1));
  CHECK(!loses->guided);
  CHECK(pays->disagreement == doctest::Approx(1.0).epsilon(0.1));
  CHECK(loses->disagreement == doctest::Approx(1.0).epsilon(0.1));
  // An unguided pass that misses a heavy tail measures itself as more efficient than a guided pass
  // at 20x the time (its true variance is 4000x the guided one's); the passes disagree far beyond
  // their variances, so the measurement is not trusted and the image stays guided.
  const std::optional<GuidingTrial> tail =
      run_guiding_trial(est, g, 32, true, 64, 64, [&](bool guided, uint32_t spp, uint64_t seed, Film& film) {
        return guided ? synthetic_pass(film, spp, seed, 0.5, 20.0) : heavy_tailed_pass(film, spp, seed, 1e-3);
      });
  REQUIRE(tail);
  CHECK(tail->efficiency_ratio < 1.0);
  CHECK(tail->disagreement > 10.0);
  CHECK(tail->guided);
  // No trial without a time limit (the render would depend on measured seconds), with too few
  // samples per pass, or when turned off.
  est.time_limit = 0.0;
  est.spp = 1024;
  CHECK(!run(0.5, 2.0));
  est.time_limit = 1.0;
  CHECK(!run_guiding_trial(est, g, kTrialMinPassSpp - 1, true, 64, 64, [](bool, uint32_t, uint64_t, Film&) { return RenderStats{}; }));
  g.guide_trial = false;
  CHECK(!run(0.5, 2.0));
}

TEST_CASE("a_guide_must_pay_for_the_training_still_ahead") {
  CHECK(ratio_to_pay(10.0, 0.0, 0.0) == 1.0);  // after the training
  CHECK(ratio_to_pay(5.0, 1.0, 0.5) == doctest::Approx(5.0 / 4.5));
  CHECK(ratio_to_pay(5.0, 1.0, 2.0) == 1.0);  // its kept samples are worth more than it costs
  CHECK(std::isinf(ratio_to_pay(0.4, 1.0, 0.5)));
  // Guided twice as efficient (synthetic passes of 32 spp on 64 x 64: 131072 s unguided, twice
  // that guided). With 1e6 s left and 6e5 s of training ahead whose samples the image does not
  // keep, guiding must be 2.5x as efficient: the image is rendered unguided. The control: when
  // the image keeps 64 spp of it (worth 64 x 8192 s at the guided pass's cost), 1.08x is enough.
  EstimatorOptions est;
  est.spp = 0;
  est.time_limit = 3.0 * 131072.0 + 1e6;
  const GuidingOptions g;
  const auto run = [&](uint32_t kept_spp) {
    return run_guiding_trial(
        est, g, 32, true, 64, 64,
        [&](bool guided, uint32_t spp, uint64_t seed, Film& film) {
          return guided ? synthetic_pass(film, spp, seed, 0.5, 2.0) : synthetic_pass(film, spp, seed, 1.0, 1.0);
        },
        0.0, TrainingAhead{6e5, kept_spp});
  };
  const std::optional<GuidingTrial> unkept = run(0), kept = run(64);
  REQUIRE(unkept);
  REQUIRE(kept);
  CHECK(unkept->efficiency_ratio == doctest::Approx(2.0).epsilon(0.1));
  CHECK(unkept->ratio_to_pay == doctest::Approx(2.5));
  CHECK(!unkept->guided);
  CHECK(kept->ratio_to_pay == doctest::Approx(1e6 / (1e6 - (6e5 - 64 * 8192.0))));
  CHECK(kept->guided);
}

TEST_CASE("the_trial_checkpoint_comes_before_the_last_training_iteration") {
  // Iterations double in time: after one of 0.1 s, at 0.2 s spent, the next (0.2 s) fits a
  // budget of 0.5 s and the one after (0.4 s) would not: the next is the last, so now.
  CHECK(checkpoint_due(0.2, 0.1, 0.5));
  CHECK(!checkpoint_due(0.2, 0.1, 0.9));   // two more fit: later
  CHECK(!checkpoint_due(0.2, 0.1, 0.35));  // none fits: the training ends, the trial follows it
  CHECK(!checkpoint_due(0.2, 0.1, 0.0));   // no time limit: no trial
  // The passes: half the last iteration's spp after the training, its whole spp before the last
  // iteration, at least kTrialMinPassSpp, and none when both would take over a quarter of the time.
  RenderStats last;
  last.spp = 128;
  last.seconds = 0.4;
  CHECK(trial_pass_spp(last, false, 2.0) == 64);
  CHECK(trial_pass_spp(last, true, 4.0) == 128);
  last.spp = 16;
  last.seconds = 0.1;
  CHECK(trial_pass_spp(last, false, 2.0) == kTrialMinPassSpp);  // 2 x 32 spp take 0.4 s
  CHECK(trial_pass_spp(last, false, 1.0) == 0);
}
