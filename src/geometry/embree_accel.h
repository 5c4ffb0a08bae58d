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

// Lets an occlusion query ignore some hits (e.g. the surface the ray is aimed at).
struct HitFilter {
  bool (*ignore)(const void* user, uint32_t prim, float t) = nullptr;
  const void* user = nullptr;
};

class EmbreeAccel {
 public:
  // positions: 3 floats per vertex; triangles: 3 indices per triangle. Copied into Embree buffers.
  // robust: Embree's robust mode (RTC_SCENE_FLAG_ROBUST), which avoids the optimisations that
  // lower its arithmetic accuracy: no ray slips through where triangles meet. Without it rays
  // trace 24-30 % faster but leak through the edges of closed meshes (Mitsuba 3's default, its
  // scene's embree_use_robust_intersections = false).
  EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles, bool robust = true);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  RayHit intersect(const Ray& ray) const;
  // True when anything blocks the ray in (0, ray.tmax), apart from hits the filter ignores.
  bool occluded(const Ray& ray, const HitFilter* filter = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dualight
