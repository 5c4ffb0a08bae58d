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
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"
#include "pathspace/strategies.h"

namespace dualight {

struct PathTracerOptions : EstimatorOptions {
  Strategies strategies = Strategies::Mis;  // or BSDF sampling or light sampling alone
};

RenderResult render_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                         RenderControl& control);

}  // namespace dualight
