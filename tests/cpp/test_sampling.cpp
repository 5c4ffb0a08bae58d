// Sampling warps against their densities, the discrete distribution, frames, PCG32, and the
// pixel driver's film positions.
#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "check.h"
#include "core/distribution.h"
#include "core/frame.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/strategies.h"

using namespace dualight;

TEST_CASE("cosine_hemisphere_moments_match_its_pdf") {
  // E[cos] = 2/3 and E[cos^2] = 1/2 under p = cos/pi; all samples on the upper hemisphere.
  Pcg32 rng(1, 2);
  const int n = 200000;
  double m1 = 0, m2 = 0, x_mean = 0;
  bool unit = true;
  for (int i = 0; i < n; ++i) {
    const Vec3 w = square_to_cosine_hemisphere({rng.next_float(), rng.next_float()});
    unit &= std::abs(length(w) - 1.f) < 1e-5f && w.z >= 0.f;
    m1 += w.z;
    m2 += w.z * w.z;
    x_mean += w.x;
  }
  CHECK(unit);
  CHECK_NEAR(m1 / n, 2.0 / 3.0, 4e-3);
  CHECK_NEAR(m2 / n, 0.5, 4e-3);
  CHECK_NEAR(x_mean / n, 0.0, 5e-3);
  CHECK_NEAR(cosine_hemisphere_pdf(1.f), kInvPi, 1e-7);
  CHECK(cosine_hemisphere_pdf(-0.1f) == 0.f);
}

TEST_CASE("concentric_disk_matches_its_trigonometric_definition") {
  // The inline sine and cosine against double-precision std::sin and std::cos of Shirley and
  // Chiu's angle, on a grid through every sector and across the sector boundaries (|a| = |b|).
  const int n = 401;
  double worst = 0.0, worst_radius = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const Point2 u{static_cast<float>(i) / (n - 1), static_cast<float>(j) / (n - 1)};
      const double a = 2.0 * u.u - 1.0, b = 2.0 * u.v - 1.0;
      double x = 0.0, y = 0.0;
      if (a != 0.0 || b != 0.0) {
        const bool x_sector = a * a > b * b;
        const double r = x_sector ? a : b;
        const double phi = x_sector ? (kPi / 4.0) * (b / a) : kPi / 2.0 - (kPi / 4.0) * (a / b);
        x = r * std::cos(phi);
        y = r * std::sin(phi);
      }
      const Point2 d = square_to_uniform_disk(u);
      worst = std::max({worst, std::abs(d.u - x), std::abs(d.v - y)});
      worst_radius = std::max(worst_radius, std::hypot(static_cast<double>(d.u), static_cast<double>(d.v)));
    }
  }
  CHECK(worst < 3e-7);
  CHECK(worst_radius < 1.0 + 3e-7);
  float s = 0.f, c = 0.f;
  sincos_within_pi_over_4(kPi / 4.f, s, c);
  CHECK_NEAR(s, std::sin(kPi / 4.0), 1e-7);
  CHECK_NEAR(c, std::cos(kPi / 4.0), 1e-7);
}

TEST_CASE("uniform_triangle_barycentrics_are_uniform") {
  // The mean of uniform barycentrics is the centroid (1/3, 1/3); all inside the triangle.
  Pcg32 rng(3, 4);
  const int n = 200000;
  double b1 = 0, b2 = 0;
  bool inside = true;
  for (int i = 0; i < n; ++i) {
    const Point2 b = square_to_uniform_triangle({rng.next_float(), rng.next_float()});
    inside &= b.u >= 0.f && b.v >= 0.f && b.u + b.v <= 1.f + 1e-6f;
    b1 += b.u;
    b2 += b.v;
  }
  CHECK(inside);
  CHECK_NEAR(b1 / n, 1.0 / 3.0, 3e-3);
  CHECK_NEAR(b2 / n, 1.0 / 3.0, 3e-3);
}

TEST_CASE("power_heuristic_weights_sum_to_one") {
  CHECK_NEAR(power_heuristic(1.f, 3.f) + power_heuristic(3.f, 1.f), 1.f, 1e-6f);
  CHECK(power_heuristic(0.f, 1.f) == 0.f);
  CHECK(power_heuristic(1.f, 0.f) == 1.f);
}

TEST_CASE("one_strategy_alone_weights_sum_to_one") {
  // For every pair of densities (0 where a strategy cannot sample the point), the two
  // strategies' weights sum to 1 under MIS and under either strategy alone; alone, the chosen
  // one keeps every point it can sample.
  const float pdfs[] = {0.f, 1e-3f, 0.5f, 2.f, 1e4f};
  for (const Strategies chosen : {Strategies::Mis, Strategies::Bsdf, Strategies::Light}) {
    for (const float p_bsdf : pdfs) {
      for (const float p_light : pdfs) {
        if (p_bsdf == 0.f && p_light == 0.f) continue;
        const float w_bsdf = p_bsdf > 0.f ? two_strategy_weight(chosen, Strategies::Bsdf, p_bsdf, p_light) : 0.f;
        const float w_light = p_light > 0.f ? two_strategy_weight(chosen, Strategies::Light, p_light, p_bsdf) : 0.f;
        CHECK_NEAR(w_bsdf + w_light, 1.f, 1e-6f);
        if (chosen == Strategies::Bsdf && p_bsdf > 0.f) CHECK(w_bsdf == 1.f);
        if (chosen == Strategies::Light && p_light > 0.f) CHECK(w_light == 1.f);
      }
    }
  }
  // BDPT's preference: s = 0 first for BSDF sampling; s = 1, then s = 0 for light sampling.
  CHECK(strategy_rank(Strategies::Bsdf, 0) < strategy_rank(Strategies::Bsdf, 1));
  CHECK(strategy_rank(Strategies::Light, 1) < strategy_rank(Strategies::Light, 0));
  CHECK(strategy_rank(Strategies::Light, 0) < strategy_rank(Strategies::Light, 2));
}

TEST_CASE("discrete_distribution_samples_in_proportion") {
  const DiscreteDistribution d({1.0, 0.0, 3.0});
  CHECK_NEAR(d.pmf(0), 0.25f, 1e-7f);
  CHECK(d.pmf(1) == 0.f);
  std::vector<int> counts(3, 0);
  Pcg32 rng(5, 6);
  for (int i = 0; i < 100000; ++i) {
    float u = rng.next_float();
    const size_t k = d.sample(u);
    CHECK((u >= 0.f && u < 1.f));
    ++counts[k];
  }
  CHECK(counts[1] == 0);
  CHECK_NEAR(counts[0] / 100000.0, 0.25, 6e-3);
  bool threw = false;
  try {
    DiscreteDistribution({0.0, 0.0});
  } catch (const std::invalid_argument&) {
    threw = true;
  }
  CHECK(threw);
}

// The lanes count the item ends u passes instead of searching: the same item for every u,
// including the floats next to each end (where rounding the ends down instead of up fails).
TEST_CASE("counting_float_item_ends_picks_what_sample_picks") {
  Pcg32 rng(7, 8);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> weights(1 + rng.next_uint() % 40);
    for (double& w : weights) w = rng.next_float() < 0.2f ? 0.0 : std::exp(8.0 * rng.next_float());
    weights[rng.next_uint() % weights.size()] = 1.0;
    const DiscreteDistribution d(weights);
    const std::vector<float> ends = d.float_item_ends();
    REQUIRE(ends.size() == d.size());
    std::vector<float> us;
    for (int i = 0; i < 200; ++i) us.push_back(rng.next_float());
    for (const float end : ends) {
      for (float u = std::nextafter(std::nextafter(end, 0.f), 0.f), k = 0; k < 5; u = std::nextafter(u, 1.f), ++k) {
        if (u >= 0.f && u < 1.f) us.push_back(u);
      }
    }
    bool same = true;
    for (float u : us) {
      size_t passed = 0;
      for (const float end : ends) passed += u >= end ? 1 : 0;
      float v = u;
      same = same && std::min(passed, d.size() - 1) == d.sample(v);
    }
    CHECK(same);
  }
}

// sample() searches only its guide table's bracket: the same item, and the same rescaled u, as the
// search of the whole CDF it replaced, for random distributions (zero weights, sizes past the
// guide's 2^16 slices), at random u, at the floats next to each item's end and each slice's start,
// and at ties (dyadic weights, whose ends are floats). Control: a search that resolves ties the
// other way (lower_bound) is told apart.
TEST_CASE("guided_search_picks_what_a_whole_search_picks") {
  Pcg32 rng(11, 12);
  bool control_differs = false;
  for (int trial = 0; trial < 60; ++trial) {
    const size_t n = trial == 0 ? 70000 : 1 + rng.next_uint() % (trial % 3 == 0 ? 3000 : 40);
    std::vector<double> weights(n);
    for (double& w : weights) {
      w = rng.next_float() < 0.2f ? 0.0 : (trial % 2 == 0 ? 1.0 : std::exp(8.0 * rng.next_float()));
    }
    weights[rng.next_uint() % n] = 1.0;
    const DiscreteDistribution d(weights);
    // The CDF as the constructor computes it.
    std::vector<double> cdf{0.0};
    for (const double w : weights) cdf.push_back(cdf.back() + w);
    const double total = cdf.back();
    for (double& c : cdf) c /= total;
    std::vector<float> us{0.f, std::nextafter(1.f, 0.f)};
    for (int i = 0; i < 300; ++i) us.push_back(rng.next_float());
    const auto near = [&us](double x) {
      for (float u = std::nextafter(std::nextafter(static_cast<float>(x), 0.f), 0.f), k = 0; k < 5;
           u = std::nextafter(u, 1.f), ++k) {
        if (u >= 0.f && u < 1.f) us.push_back(u);
      }
    };
    for (size_t k = 1; k < cdf.size() && k < 2000; ++k) near(cdf[k]);
    for (int j = 1; j < 64; ++j) near(j / 64.0);
    bool same = true;
    for (const float u : us) {
      const auto whole = [&](auto bound) {
        const auto it = bound(cdf.begin() + 1, cdf.end(), static_cast<double>(u));
        const size_t i = std::min<size_t>(static_cast<size_t>(it - cdf.begin()) - 1, n - 1);
        const double width = cdf[i + 1] - cdf[i];
        return std::make_pair(i, width > 0 ? static_cast<float>(std::min((u - cdf[i]) / width, 0.99999994)) : 0.f);
      };
      float v = u;
      const size_t i = d.sample(v);
      const auto upper = whole([](auto a, auto b, double x) { return std::upper_bound(a, b, x); });
      const auto lower = whole([](auto a, auto b, double x) { return std::lower_bound(a, b, x); });
      same = same && upper.first == i && upper.second == v;
      control_differs = control_differs || lower.first != i;
    }
    CHECK(same);
  }
  CHECK(control_differs);
}

TEST_CASE("frames_are_orthonormal_for_any_normal") {
  Pcg32 rng(7, 8);
  for (int i = 0; i < 10000; ++i) {
    const Vec3 n = normalize(Vec3(rng.next_float() - .5f, rng.next_float() - .5f, rng.next_float() - .5f));
    const Frame f = Frame::from_normal(n);
    CHECK_NEAR(dot(f.s, f.t), 0.f, 1e-5f);
    CHECK_NEAR(dot(f.s, f.n), 0.f, 1e-5f);
    CHECK_NEAR(length(f.s), 1.f, 1e-5f);
    CHECK(length(f.to_world(f.to_local(Vec3(1, 2, 3))) - Vec3(1, 2, 3)) < 1e-4f);
  }
  const Frame down = Frame::from_normal(Vec3(0, 0, -1));  // the branch at n.z < 0
  CHECK_NEAR(dot(down.s, down.t), 0.f, 1e-6f);
}

TEST_CASE("pcg32_floats_stay_below_one_and_streams_differ") {
  Pcg32 a(1, 1), b(1, 2);
  bool below = true, differ = false;
  for (int i = 0; i < 100000; ++i) {
    const float x = a.next_float();
    below &= x >= 0.f && x < 1.f;
    differ |= x != b.next_float();
  }
  CHECK(below);
  CHECK(differ);
}

// Streams of one seed are what a pixel's samples, an MLT population's chains and a patch's
// form-factor rays draw from: the k-th numbers of streams s and s + lag must be uncorrelated.
// With the state seeded as seed + increment, lag 2 correlated -0.078 and lag 8 -0.096 (the
// standard error here is 0.0022); the bound is a Sidak-corrected 1 % level over 64 tests.
TEST_CASE("pcg32_streams_of_one_seed_are_uncorrelated") {
  constexpr int kStreams = 200000, kNumbers = 8;
  std::vector<float> x(static_cast<size_t>(kStreams) * kNumbers);
  for (int s = 0; s < kStreams; ++s) {
    Pcg32 rng(0x5eedull, static_cast<uint64_t>(s));
    for (int k = 0; k < kNumbers; ++k) x[static_cast<size_t>(s) * kNumbers + k] = rng.next_float() - 0.5f;
  }
  double worst = 0.0;
  for (const int lag : {1, 2, 3, 4, 8, 16, 64, 128}) {
    for (int k = 0; k < kNumbers; ++k) {
      double sum = 0.0;
      for (int s = 0; s + lag < kStreams; ++s) {
        sum += static_cast<double>(x[static_cast<size_t>(s) * kNumbers + k]) * x[static_cast<size_t>(s + lag) * kNumbers + k];
      }
      worst = std::max(worst, std::abs(12.0 * sum / (kStreams - lag)));
    }
  }
  CHECK(worst < 3.78 / std::sqrt(static_cast<double>(kStreams)));
}

namespace {

// A sampler whose numbers are all the largest float below 1.
struct LargestJitter {
  LargestJitter(uint64_t, uint64_t, uint32_t) {}
  Point2 next_2d() const { return {std::nextafter(1.f, 0.f), std::nextafter(1.f, 0.f)}; }
};

}  // namespace

TEST_CASE("film_positions_stay_inside_their_pixel") {
  // The largest jitter: x + jitter rounds up to x + 1 in floats for most x (the control), but the
  // film position's integer parts are still the pixel's.
  const float jitter = std::nextafter(1.f, 0.f);
  std::optional<LargestJitter> sampler;
  int rounded_up = 0, outside = 0;
  for (int x = 0; x < 4096; ++x) {
    rounded_up += static_cast<float>(x) + jitter == static_cast<float>(x + 1);
    const Point2 p = start_sample(0, 4096, {x, 4095 - x, 0}, sampler);
    outside += static_cast<int>(p.u) != x || static_cast<int>(p.v) != 4095 - x || !(p.u > static_cast<float>(x));
  }
  CHECK(rounded_up > 4000);
  CHECK(outside == 0);
}
