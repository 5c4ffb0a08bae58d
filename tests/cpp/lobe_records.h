// Guide records the C++ tests share (test_guiding.cpp, test_path.cpp).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/rng.h"
#include "guiding/guide_record.h"
#include "guiding/sd_tree.h"

namespace dualight {

// Records at points in the unit cube whose values favour directions near `lobe` (and a few
// bright outliers), as radiance through a window would.
inline GuideRecords lobe_records(size_t n, const Vec3& lobe, uint64_t seed) {
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

// A guide of records favouring `lobe` whose leaves' BSDF fractions are learnt (at least
// `bsdf_fraction`), judged by an earlier tree of the same lobe.
inline SdTree lobe_guide(const Vec3& lobe, float bsdf_fraction, uint64_t seed) {
  SdTreeSettings settings;
  settings.spatial_threshold = 4000;
  settings.bsdf_fraction = bsdf_fraction;
  GuideRecords earlier = lobe_records(20000, lobe, seed), records = lobe_records(20000, lobe, seed + 1);
  const SdTree previous(earlier, Vec3(0.f), Vec3(1.f), settings);
  return SdTree(records, Vec3(0.f), Vec3(1.f), settings, &previous);
}

}  // namespace dualight
