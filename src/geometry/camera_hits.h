// What the camera sees: for each pixel, stratified sample positions and the triangle (and
// barycentrics) each one hits. Used for the radiosity receiver R and to draw patch solutions.
#pragma once
#include <cstdint>
#include <vector>

#include "geometry/camera.h"
#include "geometry/scene.h"

namespace dualight {

struct CameraHits {
  int width = 0, height = 0, samples = 0;  // samples per pixel (a samples_per_axis^2 grid)
  std::vector<int32_t> prim;               // H x W x S, -1 for a miss
  std::vector<float> barycentric;          // H x W x S x 2 (b1, b2)
};

CameraHits trace_camera_hits(const Scene& scene, const PinholeCamera& camera, int samples_per_axis, uint64_t seed,
                             int threads);

}  // namespace dualight
