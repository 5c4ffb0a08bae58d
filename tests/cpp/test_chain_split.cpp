// The pieces that make a split Metropolis render equal the single-process one bit for bit:
// exact sums that do not depend on the order of additions, chain rounds whose per-chain counts
// do not depend on the clock, and start-ups and chain parts that survive a trip through bytes.
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "check.h"
#include "core/apportion.h"
#include "core/exact_sum.h"
#include "pathspace/chain_rounds.h"
#include "pathspace/chain_split.h"

using namespace dualight;

namespace {

// Values whose double sums round differently in different orders: magnitudes from 1e-12 to 1e8.
std::vector<float> mixed_values(size_t n, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> exponent(-12.f, 8.f), mantissa(1.f, 10.f);
  std::vector<float> v(n);
  for (float& x : v) x = mantissa(rng) * std::pow(10.f, exponent(rng)) * (rng() % 5 == 0 ? -1.f : 1.f);
  return v;
}

bool same_bits(const ExactSums& a, const ExactSums& b) {
  return a.words() == b.words() && a.exponent() == b.exponent();
}

}  // namespace

TEST_CASE("exact_sums_do_not_depend_on_the_order") {
  const std::vector<float> v = mixed_values(20000, 7);
  ExactSums forward(1, 1.0), shuffled(1, 1.0), halves(1, 1.0), second(1, 1.0);
  for (const float x : v) CHECK(forward.add(0, x));
  std::vector<float> w = v;
  std::shuffle(w.begin(), w.end(), std::mt19937(3));
  for (const float x : w) shuffled.add(0, x);
  for (size_t i = 0; i < v.size() / 3; ++i) halves.add(0, v[i]);
  for (size_t i = v.size() / 3; i < v.size(); ++i) second.add(0, v[i]);
  halves.add(second);
  CHECK(same_bits(forward, shuffled));
  CHECK(same_bits(forward, halves));
  // Negative control: plain double sums of the same values in these orders differ.
  double a = 0.0, b = 0.0;
  for (const float x : v) a += x;
  for (const float x : w) b += x;
  CHECK(a != b);
  // And the exact sum is the true sum, to double precision (long double as the reference).
  long double exact = 0.0L;
  for (const float x : v) exact += x;
  const double reference = static_cast<double>(exact);
  CHECK(std::abs(forward.value(0) - reference) <= 1e-12 * std::abs(reference) + 1e-18);
}

TEST_CASE("exact_sums_reject_what_the_grid_cannot_hold") {
  ExactSums s(2, 0.5);  // grid 2^-64: a value must stay below 2^62
  CHECK(!s.add(0, std::nanf("")));
  CHECK(!s.add(0, INFINITY));
  CHECK(!s.add(0, 1e19f));
  CHECK(s.add(0, 1e18f));
  CHECK((s.add(1, -3.25f) && s.add(1, 1e-19f)));
  CHECK((s.value(0) == 1e18f && s.value(1) == static_cast<double>(-3.25f) + static_cast<double>(1e-19f)));
  // Negative values are the exact opposites of positive ones: every value and its negation cancel.
  ExactSums cancel(1, 1.0);
  for (const float x : mixed_values(5000, 11)) {
    cancel.add(0, x);
    cancel.add(0, -x);
  }
  CHECK((cancel.value(0) == 0.0 && cancel.words()[0] == 0 && cancel.words()[1] == 0));
  ExactSums other(3, 0.5), coarser(2, 4.0);
  bool threw = false;
  try {
    s.add(other);
  } catch (const std::invalid_argument&) {
    threw = true;
  }
  CHECK(threw);
  threw = false;
  try {
    s.add(coarser);
  } catch (const std::invalid_argument&) {
    threw = true;
  }
  CHECK(threw);
}

TEST_CASE("chain_rounds_give_each_chain_its_quota_whatever_the_clock") {
  const uint64_t chains = 7, target = 1000;
  for (const uint32_t clock_seed : {1u, 2u, 3u}) {
    // A whole population, and the same chains in three ranges, each with its own clock.
    std::vector<uint64_t> whole(chains, 0), split(chains, 0);
    const auto run = [&](uint64_t first, uint64_t count, std::vector<uint64_t>& per_chain, uint32_t seed) {
      ChainRounds rounds(chains, first, count, target, 0.0);
      RenderControl control;
      std::mt19937 rng(seed);
      double now = 0.0;
      while (rounds.next(now, control)) {
        uint64_t round = 0;
        for (uint64_t i = 0; i < count; ++i) {
          per_chain[first + i] += rounds.share(i);
          round += rounds.share(i);
        }
        now += 1e-4 * static_cast<double>(1 + rng() % 5000);  // rounds of any length
        if (!rounds.finish(round, now, control)) break;
      }
      CHECK(rounds.total() == rounds.range_target());
    };
    run(0, chains, whole, clock_seed);
    run(0, 2, split, clock_seed + 10);
    run(2, 4, split, clock_seed + 20);
    run(6, 1, split, clock_seed + 30);
    for (uint64_t c = 0; c < chains; ++c) CHECK(whole[c] == chain_quota(target, chains, c));
    CHECK(whole == split);
  }
}

TEST_CASE("start_ups_and_parts_survive_bytes") {
  ChainStartUp start;
  start.image = {1.0, 2.0, 3.0};
  start.mlt.b = start.mlt.b_splatted = 0.5;
  start.stats.rays = 42;
  start.stats.unoccluded = true;
  for (int d = 0; d < 2; ++d) {
    ChainPopulation p;
    p.depth = d + 3;
    p.weights = {0.25, 0.75};
    p.b_splat = 0.5;
    p.first_chain = 5 * static_cast<uint64_t>(d);
    p.chains = 5;
    p.target = 100;
    start.populations.push_back(p);
  }
  const ChainStartUp back = start_up_from_bytes(to_bytes(start));
  CHECK((back.chains() == 10 && back.image == start.image && back.mlt.b == 0.5 && back.stats.rays == 42));
  CHECK((back.stats.unoccluded && back.populations[1].depth == 4));
  CHECK(back.populations[1].weights == start.populations[1].weights);
  const ChainStartUp trimmed = start.for_chains(0, 5);
  CHECK((!trimmed.populations[0].weights.empty() && trimmed.populations[1].weights.empty()));

  ChainPart part;
  part.first_chain = 2;
  part.chains = 3;
  part.populations.resize(2);
  part.populations[0].metropolis = ExactSums(3, 0.5);
  part.populations[0].metropolis.add(1, 0.125f);
  part.populations[0].large_f.resize(3);
  part.populations[0].large_f[2].add(4.0);
  part.mutations = {{"bidirectional", 3, 2, 1}};
  part.stats.seconds = 1.5;
  const ChainPart copy = part_from_bytes(to_bytes(part));
  CHECK((copy.first_chain == 2 && copy.chains == 3 && copy.stats.seconds == 1.5));
  CHECK((copy.populations[0].metropolis.value(1) == 0.125 && copy.populations[0].large_f[2].sum == 4.0));
  CHECK((copy.mutations.size() == 1 && copy.mutations[0].name == "bidirectional" && copy.mutations[0].failed == 1));

  // Malformed input is an error, not garbage: truncated, another kind, or trailing bytes.
  const std::string bytes = to_bytes(part);
  int errors = 0;
  for (const std::string& bad : {bytes.substr(0, bytes.size() - 1), to_bytes(start), bytes + "x", std::string("abc")}) {
    try {
      part_from_bytes(bad);
    } catch (const std::invalid_argument&) {
      ++errors;
    }
  }
  CHECK(errors == 4);
  // Parts merge in chain order only.
  ChainPart first;
  first.first_chain = 5;
  first.chains = 2;
  bool threw = false;
  try {
    first.merge(part);
  } catch (const std::invalid_argument&) {
    threw = true;
  }
  CHECK(threw);
}

// Multiplexed MLT splits its chains and mutations over path lengths by b_d: the parts must sum
// to what was asked for (rounding each share on its own gave 39 chains of 40), follow the
// weights to within one unit, and give every length with light at least one chain.
TEST_CASE("apportion_sums_to_the_total_and_follows_the_weights") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> weight(0.0, 1.0);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<double> w(1 + rng() % 8);
    for (double& x : w) x = rng() % 4 == 0 ? 0.0 : std::pow(weight(rng), 6.0);
    const uint64_t total = rng() % 200;
    const std::vector<uint64_t> part = apportion(total, w, 1);
    uint64_t sum = 0, positive = 0;
    double w_sum = 0.0;
    for (size_t i = 0; i < w.size(); ++i) {
      sum += part[i];
      positive += w[i] > 0.0;
      w_sum += w[i];
      CHECK((w[i] > 0.0 ? part[i] >= 1 : part[i] == 0));
    }
    CHECK(sum == (positive > total ? positive : (positive ? total : 0)));
    // Without minimums to honour, every part is its quota rounded up or down.
    bool bumped = positive == 0;
    for (const double x : w) bumped |= x > 0.0 && total * x / w_sum < 1.0;
    if (bumped) continue;
    for (size_t i = 0; i < w.size(); ++i) CHECK(std::abs(static_cast<double>(part[i]) - total * w[i] / w_sum) < 1.0);
  }
  CHECK(apportion(40, {0.1, 0.2, 0.3, 0.4}, 1) == std::vector<uint64_t>{4, 8, 12, 16});
  CHECK(apportion(10, {1.0, 1.0, 1.0}, 1) == std::vector<uint64_t>{4, 3, 3});
}
