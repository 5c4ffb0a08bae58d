// The SD-tree guide (guiding/): the quadtree's density integrates to one and is the density of
// its samples; a tree is the same whatever order its records come in; the BSDF fraction is
// learnt only from enough records.
#include <algorithm>
#include <cmath>
#include <vector>

#include "check.h"
#include "core/rng.h"
#include "guiding/sd_tree.h"

using namespace dualight;

namespace {

// Records at points in the unit cube whose values favour directions near `lobe` (and a few
// bright outliers), as radiance through a window would.
GuideRecords lobe_records(size_t n, const Vec3& lobe, uint64_t seed) {
  Pcg32 rng(seed, 7);
  GuideRecords records;
  for (size_t i = 0; i < n; ++i) {
    const Vec3 p{rng.next_float(), rng.next_float(), rng.next_float()};
    const Vec3 w = square_to_direction({rng.next_float(), rng.next_float()});
    const float c = std::max(0.f, dot(w, lobe));
    const float value = std::pow(c, 20.f) * 100.f + 0.1f + (rng.next_float() < 1e-3f ? 50.f : 0.f);
    records.push_back({p, direction_to_square(w), value, value, 0.25f * kInvPi, 0.25f * kInvPi});
  }
  return records;
}

}  // namespace

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
  // lobe: the guide matches it far better than the BSDF, so the least fraction allowed wins.
  GuideRecords many = lobe_records(5000, Vec3(0.f, 0.f, 1.f), 11);
  SdTreeSettings settings;
  settings.spatial_threshold = 1u << 30;
  settings.bsdf_fraction = 0.3f;
  const SdTree guided(many, Vec3(0.f), Vec3(1.f), settings);
  CHECK(guided.at(Vec3(0.5f)).bsdf_fraction == doctest::Approx(0.3f));
  // Records whose integrand is the BSDF's own density: the guide adds nothing, fraction 1.
  GuideRecords flat = many;
  for (GuideRecord& r : flat) r.product = r.pdf_bsdf;
  CHECK(SdTree(flat, Vec3(0.f), Vec3(1.f), settings).at(Vec3(0.5f)).bsdf_fraction == doctest::Approx(1.f));
  // Fewer than 16 records that carried anything: no guiding.
  GuideRecords few(many.begin(), many.begin() + 10);
  CHECK(SdTree(few, Vec3(0.f), Vec3(1.f), settings).at(Vec3(0.5f)).bsdf_fraction == 1.f);
}
