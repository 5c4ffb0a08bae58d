// One BDPT sample: a camera subpath through film position (x, y), a light subpath, and every
// strategy joining them, MIS-weighted [Veach 1997, ch. 10]. Returns the contributions to the
// pixel at (x, y) (strategies with t >= 2); light-tracing strategies (t = 1) go to `splats`.
// Shared by BDPT (independent or Sobol samplers) and primary-sample-space MLT (Kelemen's
// sampler): all of its randomness comes from `sampler`.
#pragma once
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

// Every strategy (s, t) joining the two subpaths, of depth s + t - 1 within [opt.min_depth,
// opt.max_depth], that carries light: visit(s, t, unweighted contribution, sampled, raster),
// where `sampled` stands in for the emitter end (s = 1) or the camera (t = 1) and `raster` is
// the film position of a light-tracing strategy (t = 1). Connections draw from `sampler`. In a
// scene lit only by delta lights no camera subpath ends on an emitter: the strategies s = 0
// are not evaluated (render.py's stats say so).
template <class Sampler, class Visit>
void for_each_strategy(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt,
                       const Subpaths& paths, Sampler& sampler, TraceCounters& counters, const Visit& visit) {
  const Path& cam = paths.camera;
  const Path& light = paths.light;
  const int s_first = scene.has_hittable_emitter() ? 0 : 1;
  for (int t = 1; t <= static_cast<int>(cam.size()); ++t) {
    for (int s = s_first; s <= static_cast<int>(light.size()); ++s) {
      const int depth = s + t - 1;
      if (depth < opt.min_depth || (opt.max_depth >= 0 && depth > opt.max_depth)) continue;
      if (s == 1 && t == 1) continue;  // the same paths as (0, 2), which keeps them all
      Vertex sampled;
      Point2 raster{};
      const Color c = connect(scene, camera, light, cam, s, t, sampler, sampled, raster, counters);
      if (!is_black(c)) visit(s, t, c, sampled, raster);
    }
  }
}

// `layers`: the film whose strategy layers receive the own-pixel contributions (only when
// opt.strategy_images), else unused. `guides`: guided BDPT's (subpath.h), or none; `recording`:
// a training iteration's, or none.
template <class Sampler>
Color bdpt_sample(const Scene& scene, const PinholeCamera& camera, const BdptOptions& opt, float x, float y,
                  Sampler& sampler, Subpaths& paths, TraceCounters& counters, SplatList& splats, Film* layers,
                  const SubpathGuides& guides = {}, const SubpathRecording* recording = nullptr) {
  const WalkLimits limits{opt.max_depth, opt.rr_depth};
  // The camera subpath continues the camera stream, which drew the film position.
  camera_subpath(scene, camera, x, y, sampler, limits, paths.camera, counters, guides.camera());
  sampler.start_stream(kLightStream);
  light_subpath(scene, sampler, limits, paths.light, counters, guides.light());
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
  for_each_strategy(scene, camera, opt, paths, sampler, counters,
                    [&](int s, int t, Color c, const Vertex& sampled, const Point2& raster) {
                      c *= mis_weight(scene, camera, paths.light, paths.camera, sampled, s, t, opt.heuristic,
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
