// The ray-tracing limit: casts incoherent closest-hit rays through Embree with no shading, so
// an estimator's rays per second can be stated as a fraction of what the BVH alone sustains.
#pragma once
#include <cstdint>

#include "geometry/camera.h"
#include "geometry/scene.h"

namespace dualight {

struct RayCastStats {
  uint64_t rays = 0;
  uint64_t hits = 0;
  double seconds = 0.0;
};

// Rays start at points seen from the camera and leave in cosine-distributed directions, the
// same mix of origins and directions a diffuse path tracer produces after its first bounce.
RayCastStats cast_random_rays(const Scene& scene, const PinholeCamera& camera, uint64_t n_rays, uint64_t seed,
                              int threads);

}  // namespace dualight
