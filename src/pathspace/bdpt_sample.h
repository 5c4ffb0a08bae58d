// One BDPT sample: a camera subpath through film position (x, y), a light subpath, and every
// strategy joining them, MIS-weighted [Veach 1997, ch. 10]. Returns the contributions to the
// pixel at (x, y) (strategies with t >= 2); light-tracing strategies (t = 1) go to `splats`.
// Shared by BDPT (independent or Sobol samplers) and primary-sample-space MLT (Kelemen's
// sampler): all of its randomness comes from `sampler`.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "core/rng.h"
#include "film/film.h"
#include "film/splat_list.h"
#include "pathspace/bdpt.h"
#include "pathspace/connect.h"
#include "pathspace/mlt_importance.h"
#include "pathspace/subpath.h"
#include "pathspace/subpath_records.h"

namespace dualight {

// Layer of strategy (s, t): depth d = s + t - 1 has d + 1 strategies (t = 1 .. d + 1).
inline size_t strategy_layer(int s, int t) {
  const int d = s + t - 1;
  return static_cast<size_t>((d - 1) * (d + 2) / 2 + (t - 1));
}

struct Subpaths {
  Path camera, light;
  // The light subpaths of a tile row's pixels at one sample index, their groups' longest, the
  // row's first pixel and the row's key for its groups' shifts (BDPT's light pool, bdpt.cpp).
  std::vector<Path> row_light;
  std::vector<uint32_t> row_longest;  // the number of vertices of each group's longest subpath
  int row_x0 = 0;
  uint64_t row_key = 0;
  // What each vertex's strategies contributed (a guided BDPT training iteration's records).
  std::vector<Color> camera_arrived, light_arrived;
};

// Where a guided BDPT training iteration (bdpt.cpp) keeps what its strategies carried: radiance
// records from camera subpaths, importance records from light subpaths. An importance record
// counts a contribution by pixel_weight at its pixel, as the light tracer's do (light_tracer.cpp).
struct SubpathRecording {
  GuideRecords* radiance = nullptr;
  GuideRecords* importance = nullptr;
  const PixelImportance* pixel_weight = nullptr;
};

// Notes weighted contribution c of strategy (s, t) at the subpaths' vertices it came through,
// landing on `pixel`.
inline void note_arrival(Subpaths& paths, const SubpathRecording& rec, int s, int t, const Color& c,
                         uint32_t pixel) {
  if (!is_finite(c)) return;
  paths.camera_arrived[static_cast<size_t>(t - 1)] += c;
  if (s >= 1) paths.light_arrived[static_cast<size_t>(s - 1)] += c * (*rec.pixel_weight)(pixel);
}

// The records of a sample whose arrivals note_arrival noted.
inline void record_subpaths(const Subpaths& paths, const SubpathRecording& rec) {
  record_incident(paths.camera, paths.camera_arrived, TransportMode::Radiance, *rec.radiance);
  record_incident(paths.light, paths.light_arrived, TransportMode::Importance, *rec.importance);
}

// Strategy (s, t)'s half of a hash of (key, strategy): hash_combine(key, s << 32 | t) is
// mix64(key ^ mix_strategy(s, t)).
constexpr uint64_t mix_strategy(int s, int t) {
  return mix64(static_cast<uint64_t>(s) << 32 | static_cast<uint32_t>(t));
}

// The light subpaths a sample's connections take theirs from (BdptOptions::light_pool): the
// `count` subpaths of its pool group, the sample's own at `own`. Strategy (s, t) of the group's
// pixel k takes the subpath k + shift(s, t) (mod count), where the shift, drawn uniformly per
// strategy from `key` (the group's, at this sample index), is the same for all of the group's
// pixels: each pixel's connection takes a uniformly drawn subpath, and each subpath serves one
// pixel of the group per strategy, as in classic BDPT (no subpath is used twice while another
// goes unused).
struct LightPool {
  // mix_strategy, tabulated for s, t < kStrategyHashes.
  static constexpr int kStrategyHashes = 16;
  static constexpr std::array<uint64_t, kStrategyHashes * kStrategyHashes> kStrategyHash = [] {
    std::array<uint64_t, kStrategyHashes * kStrategyHashes> table{};
    for (int s = 0; s < kStrategyHashes; ++s) {
      for (int t = 0; t < kStrategyHashes; ++t) {
        table[static_cast<size_t>(s * kStrategyHashes + t)] = mix_strategy(s, t);
      }
    }
    return table;
  }();
  static uint64_t strategy_hash(int s, int t) {
    if (s >= kStrategyHashes || t >= kStrategyHashes) return mix_strategy(s, t);
    return kStrategyHash[static_cast<size_t>(s * kStrategyHashes + t)];
  }

  const Path* paths;
  uint32_t count;
  uint32_t own;
  uint64_t key;
  uint32_t longest;  // the number of vertices of the pool's longest subpath

  // A sample's own subpath alone (classic BDPT).
  explicit LightPool(const Path& own_path)
      : paths(&own_path), count(1), own(0), key(0), longest(static_cast<uint32_t>(own_path.size())) {}
  LightPool(const Path* group, uint32_t count, uint32_t own, uint64_t key, uint32_t longest)
      : paths(group), count(count), own(own), key(key), longest(longest) {}

  const Path& own_path() const { return paths[own]; }
  const Path& for_strategy(int s, int t) const {
    if (count == 1) return paths[own];
    // The shift in [0, count) by multiply and shift (Lemire 2019), no division: this runs for
    // every strategy of every sample.
    const uint64_t h = mix64(key ^ strategy_hash(s, t));
    const uint32_t shift = static_cast<uint32_t>(((h >> 32) * count) >> 32);
    const uint32_t k = own + shift;
    return paths[k >= count ? k - count : k];
  }
};

// Every strategy (s, t) joining camera subpath `cam` to the light subpaths of `pool`, of depth
// s + t - 1 within [opt.min_depth, opt.max_depth], that carries light: visit(light, s, t,
// unweighted contribution, sampled, raster), where `light` is the light subpath it used (the
// pool's own but where s >= 2 and t >= 2: LightPool::for_strategy's), `sampled` stands in
// for the emitter end (s = 1) or the camera (t = 1) and `raster` is the film position of a
// light-tracing strategy (t = 1). Connections draw from `sampler`. In a scene lit only by delta
// lights no camera subpath ends on an emitter: the strategies s = 0 are not evaluated (render.py's
// stats say so).
template <class Sampler, class Visit>
void for_each_strategy(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt, const Path& cam,
                       const LightPool& pool, Sampler& sampler, TraceCounters& counters, const Visit& visit) {
  const int s_first = scene.has_hittable_emitter() ? 0 : 1;
  const int s_last = static_cast<int>(pool.longest);
  Vertex sampled;  // set by connect where s = 1 or t = 1, the only strategies that read it
  for (int t = 1; t <= static_cast<int>(cam.size()); ++t) {
    // The strategies of depth s + t - 1 within [opt.min_depth, opt.max_depth].
    const int s_end = opt.max_depth >= 0 ? std::min(s_last, opt.max_depth + 1 - t) : s_last;
    for (int s = std::max(s_first, opt.min_depth + 1 - t); s <= s_end; ++s) {
      if (s == 1 && t == 1) continue;  // the same paths as (0, 2), which keeps them all
      const Path& light = s >= 2 && t >= 2 ? pool.for_strategy(s, t) : pool.own_path();
      if (s > static_cast<int>(light.size())) continue;
      Point2 raster{};
      const Color c = connect(scene, camera, light, cam, s, t, sampler, sampled, raster, counters);
      if (!is_black(c)) visit(light, s, t, c, sampled, raster);
    }
  }
}

// The same for one sample's own subpaths: visit(s, t, c, sampled, raster).
template <class Sampler, class Visit>
void for_each_strategy(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt,
                       const Subpaths& paths, Sampler& sampler, TraceCounters& counters, const Visit& visit) {
  for_each_strategy(scene, camera, opt, paths.camera, LightPool(paths.light), sampler, counters,
                    [&](const Path&, int s, int t, const Color& c, const Vertex& sampled, const Point2& raster) {
                      visit(s, t, c, sampled, raster);
                    });
}

// `layers`: the film whose strategy layers receive the own-pixel contributions (only when
// opt.strategy_images), else unused. `guides`: guided BDPT's (subpath.h), or none; `recording`:
// a training iteration's, or none. `pool`: the light subpaths already traced for this sample's
// connections (unguided, not recording), or none: then the sample traces its own.
template <class Sampler>
Color bdpt_sample(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt, float x, float y,
                  Sampler& sampler, Subpaths& paths, TraceCounters& counters, SplatList& splats, Film* layers,
                  const SubpathGuides& guides = {}, const SubpathRecording* recording = nullptr,
                  const LightPool* pool = nullptr) {
  const WalkLimits limits{opt.max_depth, opt.rr_depth};
  // The camera subpath continues the camera stream, which drew the film position.
  camera_subpath(scene, camera, x, y, sampler, limits, paths.camera, counters, guides.camera());
  if (pool == nullptr) {
    sampler.start_stream(kLightStream);
    light_subpath(scene, sampler, limits, paths.light, counters, guides.light());
  }
  sampler.start_stream(kConnectStream);
  if (guides.any()) {
    set_vertex_guides(paths.camera, guides, TransportMode::Radiance);
    set_vertex_guides(paths.light, guides, TransportMode::Importance);
  }
  const size_t pixel = static_cast<size_t>(y) * camera.width() + static_cast<size_t>(x);
  if (recording != nullptr) {
    paths.camera_arrived.assign(paths.camera.size(), Color(0.f));
    paths.light_arrived.assign(paths.light.size(), Color(0.f));
  }

  Color L(0.f);
  const LightPool own(paths.light);
  for_each_strategy(scene, camera, opt, paths.camera, pool != nullptr ? *pool : own, sampler, counters,
                    [&](const Path& light, int s, int t, Color c, const Vertex& sampled, const Point2& raster) {
                      c *= mis_weight(scene, camera, light, paths.camera, sampled, s, t, opt.heuristic,
                                      opt.strategies, guides.any() ? &guides : nullptr);
                      if (t == 1) {
                        const uint32_t target = static_cast<uint32_t>(raster.v) * camera.width() +
                                                static_cast<uint32_t>(raster.u);
                        splats.add(target, c);
                        if (opt.strategy_images) splats.add(target, c, static_cast<uint32_t>(strategy_layer(s, t) + 1));
                        if (recording != nullptr) note_arrival(paths, *recording, s, t, c, target);
                      } else {
                        L += c;
                        if (recording != nullptr) {
                          note_arrival(paths, *recording, s, t, c, static_cast<uint32_t>(pixel));
                        }
                        if (opt.strategy_images && is_finite(c)) {
                          layers->add_layer_sample(strategy_layer(s, t), pixel, c);
                        }
                      }
                    });
  if (recording != nullptr) record_subpaths(paths, *recording);
  return L;
}

}  // namespace dualight
