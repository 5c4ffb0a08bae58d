// Unidirectional path tracer: gathers radiance from the eye with next-event estimation and
// BSDF sampling combined by multiple importance sampling [Veach 1997, ch. 9; Kajiya 1986], or
// either strategy alone (strategies.h).
// Depth counts path segments as in Mitsuba: max_depth = 1 shows emitters only, 2 adds direct
// lighting, -1 is unbounded. Russian roulette starts at vertex rr_depth (Mitsuba's default 5).
#pragma once
#include <cstdint>

#include "core/render_control.h"
#include "core/sampler.h"
#include "film/film.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "guiding/guide_training.h"
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"
#include "pathspace/strategies.h"

namespace dualight {

// Which build of the path tracer in lanes (path_tracer_lanes.h) renders: AVX-512 or else AVX2
// where the CPU runs it (Auto), a given one (for tests and benchmarks), or none (Off: one path
// at a time).
enum class LaneIsa { Auto, Off, Sse2, Avx2, Avx512 };

// With `guiding`, camera paths sample directions from a radiance guide trained first (an SD-tree,
// guiding/sd_tree.h) mixed with BSDF sampling [Müller, Gross, Novák 2017].
struct PathTracerOptions : EstimatorOptions, GuidingOptions {
  Strategies strategies = Strategies::Mis;  // or BSDF sampling or light sampling alone
  LaneIsa lanes = LaneIsa::Auto;  // where the scene allows (path_tracer_lanes.h); same image either way
};

// The radiance guide render_path trains when options.guiding (its iterations' images are dropped).
TrainedGuide train_radiance_guide(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                                  RenderControl& control);

RenderResult render_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                         RenderControl& control);

}  // namespace dualight
