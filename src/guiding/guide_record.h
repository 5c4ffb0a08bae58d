// What a guide learns from: one sampled direction at a path vertex, with the value it carried.
// A record holds the vertex position, the direction in the square of the cylindrical map
// (directional_quadtree.h) and value = L / pdf_w: the radiance (or importance) that arrived
// along the direction over the solid-angle density it was sampled with, a one-sample estimate of
// the incident quantity integrated over the sphere [Müller, Gross, Novák 2017, sec. 3.3].
// For the choice of each leaf's BSDF fraction (sd_tree.h) a record also keeps the integrand of
// the vertex's one-sample estimate in that direction, product = f |cos| L (scalars as `value`),
// the BSDF's density of the direction and the density it was sampled with.
// Records are sorted by their contents before a guide is built, so the guide is the same
// whatever order threads produced them in (records of equal contents are interchangeable).
#pragma once
#include <algorithm>
#include <cstdint>
#include <tuple>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include "core/sampling.h"
#include "core/vec3.h"

namespace dualight {

struct GuideRecord {
  Vec3 p;
  Point2 dir;   // direction_to_square(w)
  float value;  // L / pdf_sampled, a luminance-like scalar (>= 0, finite)
  float product = 0.f;      // f |cos| L
  float pdf_bsdf = 0.f;     // the BSDF's solid-angle density of the direction
  float pdf_sampled = 1.f;  // the density the direction was sampled with (> 0)
};

inline bool operator<(const GuideRecord& a, const GuideRecord& b) {
  return std::tie(a.p.x, a.p.y, a.p.z, a.dir.u, a.dir.v, a.value, a.product, a.pdf_bsdf, a.pdf_sampled) <
         std::tie(b.p.x, b.p.y, b.p.z, b.dir.u, b.dir.v, b.value, b.product, b.pdf_bsdf, b.pdf_sampled);
}

using GuideRecords = std::vector<GuideRecord>;

// Reorders the n records at begin so that record i is the one that was at source(i).
template <class Source>
void gather_records(GuideRecord* begin, size_t n, const Source& source) {
  GuideRecords moved(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) { moved[i] = begin[source(i)]; });
  std::copy(moved.begin(), moved.end(), begin);
}

// Sorts records by `key` (then by contents, for a total order whatever order they came in):
// sorts (key, index) pairs, comparing records only where keys tie, then moves each record once.
template <class Key>
void sort_records_by(GuideRecord* begin, GuideRecord* end, const Key& key) {
  struct Keyed {
    uint64_t key;
    uint32_t index;
  };
  const size_t n = static_cast<size_t>(end - begin);
  std::vector<Keyed> keyed(n);
  tbb::parallel_for(size_t(0), n, [&](size_t i) { keyed[i] = {key(begin[i]), static_cast<uint32_t>(i)}; });
  tbb::parallel_sort(keyed.begin(), keyed.end(), [begin](const Keyed& a, const Keyed& b) {
    return a.key != b.key ? a.key < b.key : begin[a.index] < begin[b.index];
  });
  gather_records(begin, n, [&](size_t i) { return keyed[i].index; });
}

// Sorts records that are in a fixed order by `key` alone, keeping that order among equal keys
// (the result is then as fixed as the input): one sort of (key, index) integers.
template <class Key>
void stable_sort_records_by(GuideRecord* begin, GuideRecord* end, const Key& key) {
  const size_t n = static_cast<size_t>(end - begin);
  std::vector<uint64_t> keyed(n);
  for (size_t i = 0; i < n; ++i) keyed[i] = (static_cast<uint64_t>(key(begin[i])) << 32) | i;
  std::sort(keyed.begin(), keyed.end());
  gather_records(begin, n, [&](size_t i) { return static_cast<uint32_t>(keyed[i]); });
}

// The scalar a guide learns from a colour seen through a throughput: the mean over channels of
// C / beta where beta is not 0 (the quantity arriving along the vertex's sampled direction,
// whatever colour the path had picked up before it).
inline float incident_scalar(const Color& C, const Color& beta) {
  float sum = 0.f;
  for (int c = 0; c < 3; ++c) {
    if (beta[c] > 0.f) sum += C[c] / beta[c];
  }
  return sum * (1.f / 3.f);
}

}  // namespace dualight
