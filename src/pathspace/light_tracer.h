// Light (particle) tracing: the adjoint of path tracing. Particles leave the emitters with
// importance-weighted power and every non-delta vertex they reach is connected to the camera and
// splatted onto the film, estimating W = We + T* W's measurement <Le, W> [Veach 1997, sec. 4.5 and
// 10.2, strategy t = 1; Pattanaik 1993]. As in Mitsuba's `ptracer`, spp x pixels particles are
// traced. It cannot see paths whose vertex next to the camera is specular (a mirror or glass seen
// directly): those pixels lack that light. Depths count segments as in the path tracer.
#pragma once
#include <cstdint>

#include "core/render_control.h"
#include "core/sampler.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "guiding/guide_training.h"
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"

namespace dualight {

// spp counts particles per pixel. With `guiding`, light paths sample directions at surfaces from an
// importance guide trained first (guiding/sd_tree.h) mixed with BSDF sampling: particles head
// where the camera will see them [Vorba et al. 2014; Peter and Pietrek 1998].
struct LightTracerOptions : EstimatorOptions, GuidingOptions {};

// The importance guide render_light trains when options.guiding (its iterations' images are dropped).
TrainedGuide train_importance_guide(const Scene& scene, const PinholeCamera& camera,
                                    const LightTracerOptions& options, RenderControl& control);

RenderResult render_light(const Scene& scene, const PinholeCamera& camera, const LightTracerOptions& options,
                          RenderControl& control);

}  // namespace dualight
