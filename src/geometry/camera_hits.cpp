#include "geometry/camera_hits.h"

#include <stdexcept>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/triangle_grid.h"

namespace dualight {

CameraHits trace_camera_hits(const Scene& scene, const PinholeCamera& camera, int samples_per_axis, uint64_t seed,
                             int threads) {
  if (samples_per_axis < 1 || samples_per_axis > 64) throw std::invalid_argument("samples_per_axis must be in [1, 64]");
  CameraHits hits;
  hits.width = camera.width();
  hits.height = camera.height();
  hits.samples = samples_per_axis * samples_per_axis;
  const size_t n = static_cast<size_t>(hits.width) * hits.height * hits.samples;
  hits.prim.assign(n, -1);
  hits.barycentric.assign(2 * n, 0.f);
  parallel_for_each_index(threads, static_cast<size_t>(hits.height), [&](size_t y) {
    for (int x = 0; x < hits.width; ++x) {
      const size_t pixel = y * hits.width + x;
      Pcg32 rng(hash_combine(seed, pixel), 0);
      for (int s = 0; s < hits.samples; ++s) {
        // Jittered grid: stratified film positions, so a box-filtered pixel is well estimated.
        const float fx = static_cast<float>(x) + (static_cast<float>(s % samples_per_axis) + rng.next_float()) / samples_per_axis;
        const float fy = static_cast<float>(y) + (static_cast<float>(s / samples_per_axis) + rng.next_float()) / samples_per_axis;
        SurfaceHit hit;
        if (!scene.intersect(camera.generate_ray(fx, fy), hit)) continue;
        const size_t k = pixel * hits.samples + s;
        hits.prim[k] = static_cast<int32_t>(hit.prim);
        // Barycentrics of the hit point, recomputed from the position (the scene keeps p, not u, v).
        const Point2 b = barycentrics(scene.vertex(hit.prim, 0), scene.vertex(hit.prim, 1), scene.vertex(hit.prim, 2), hit.p);
        hits.barycentric[2 * k] = b.u;
        hits.barycentric[2 * k + 1] = b.v;
      }
    }
  });
  return hits;
}

}  // namespace dualight
