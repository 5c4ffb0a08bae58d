// The one place that knows Embree: builds a BVH over triangles and answers ray queries.
// Embree 3 and 4 differ in headers, query contexts and default masks; callers never see which.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "core/ray.h"

namespace dualight {

struct RayHit {
  float t = 0.f;
  float u = 0.f, v = 0.f;  // barycentrics of vertices 1 and 2
  uint32_t prim = kNoHit;
  static constexpr uint32_t kNoHit = 0xffffffffu;
  bool hit() const { return prim != kNoHit; }
};

class EmbreeAccel {
 public:
  // positions: 3 floats per vertex; triangles: 3 indices per triangle. Copied into Embree buffers.
  EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  RayHit intersect(const Ray& ray) const;
  // True when anything blocks the ray in (0, ray.tmax).
  bool occluded(const Ray& ray) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dualight
