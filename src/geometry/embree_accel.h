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

// Up to kLanes rays traced together (Embree's packet traversal), structure of arrays: lane i
// holds a ray where active[i] != 0.
struct RayPacket {
  static constexpr int kLanes = 16;
  alignas(64) float ox[kLanes], oy[kLanes], oz[kLanes];
  alignas(64) float dx[kLanes], dy[kLanes], dz[kLanes];
  alignas(64) float tmin[kLanes], tmax[kLanes];
  alignas(64) int32_t active[kLanes];
  Ray ray(int i) const { return Ray{{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tmax[i], tmin[i]}; }
  void set(int i, const Ray& r) {
    ox[i] = r.o.x, oy[i] = r.o.y, oz[i] = r.o.z;
    dx[i] = r.d.x, dy[i] = r.d.y, dz[i] = r.d.z;
    tmin[i] = r.tmin, tmax[i] = r.tmax;
  }
};
// The closest hits of a packet: lane i as RayHit (prim kNoHit: none, or an inactive lane).
struct HitPacket {
  alignas(64) float t[RayPacket::kLanes], u[RayPacket::kLanes], v[RayPacket::kLanes];
  alignas(64) uint32_t prim[RayPacket::kLanes];
};

// Sixteen rays and their closest hits in Embree's own packet layout (RTCRayHit16's, where the
// Embree compiled against has that layout: embree_accel.cpp checks it, else copies), so lane code
// fills and reads a packet without copies. The caller sets o, tmin, d and tmax; the query sets the
// rest: where lane i's ray hits, tmax[i] becomes the hit's t and u, v, prim are set; prim is
// RayHit::kNoHit where it does not.
struct alignas(64) RayHit16 {
  static constexpr int kLanes = 16;
  float ox[kLanes], oy[kLanes], oz[kLanes], tmin[kLanes];
  float dx[kLanes], dy[kLanes], dz[kLanes], time[kLanes];
  float tmax[kLanes];
  uint32_t mask[kLanes], id[kLanes], flags[kLanes];
  float ngx[kLanes], ngy[kLanes], ngz[kLanes], u[kLanes], v[kLanes];
  uint32_t prim[kLanes], geom[kLanes], inst[kLanes];
  // Lane i's ray (its tmax the hit's t once a query found one), and setting it, as RayPacket's.
  Ray ray(int i) const { return Ray{{ox[i], oy[i], oz[i]}, {dx[i], dy[i], dz[i]}, tmax[i], tmin[i]}; }
  void set(int i, const Ray& r) {
    ox[i] = r.o.x, oy[i] = r.o.y, oz[i] = r.o.z;
    dx[i] = r.d.x, dy[i] = r.d.y, dz[i] = r.d.z;
    tmin[i] = r.tmin, tmax[i] = r.tmax;
  }
};

// How the rays of a packet relate: incoherent (paths' later segments, in every direction), or
// coherent (camera rays through one pixel or a few neighbouring ones), which Embree traces by
// the packet's common frustum instead of ray by ray. Both find the same hits.
enum class Coherence { kIncoherent, kCoherent };

class EmbreeAccel {
 public:
  // positions: 3 floats per vertex; triangles: 3 indices per triangle. Copied into Embree buffers.
  // robust: Embree's robust mode (RTC_SCENE_FLAG_ROBUST), which avoids the optimisations that
  // lower its arithmetic accuracy: no ray slips through where triangles meet. Without it rays
  // trace 24-30 % faster but leak through the edges of closed meshes (Mitsuba 3's default, its
  // scene's embree_use_robust_intersections = false).
  // In fast mode the closest-hit queries go to a second BVH of the same triangles, built without
  // the filter flag the shadow rays' exact visibility test needs: Embree then runs its filter-free
  // kernels for them, as for a scene without filters (Mitsuba 3's). The same hits; twice the BVH's
  // memory and build time. (Robust mode has no filter-free kernels in Embree 3.)
  // max_packet: the widest of Embree's packet queries to use where the CPU has them (16 with
  // AVX-512, 8 with AVX; 1: lane by lane). Less than 16 is for tests: every width finds the same.
  EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles, bool robust = true,
              int max_packet = 16);
  ~EmbreeAccel();
  EmbreeAccel(const EmbreeAccel&) = delete;
  EmbreeAccel& operator=(const EmbreeAccel&) = delete;

  RayHit intersect(const Ray& ray) const;
  // True when anything blocks the ray in (0, ray.tmax), apart from hits the filter ignores.
  bool occluded(const Ray& ray, const HitFilter* filter = nullptr) const;
  // The same for packets: hits.prim[i] etc. as intersect(rays.ray(i)); blocked[i] (1 or 0) as
  // occluded(rays.ray(i), filters[i]) (filters[i] may be null). Inactive lanes miss and are not blocked.
  void intersect(const RayPacket& rays, HitPacket& hits, Coherence coherence = Coherence::kIncoherent) const;
  void occluded(const RayPacket& rays, const HitFilter* const* filters, int32_t* blocked) const;
  // The same as intersect(RayPacket) in place, for the lanes where active[i] != 0; and as
  // occluded(RayPacket): where lane i's ray is blocked, or Embree would not take it (counted as
  // blocked), tmax[i] becomes negative.
  void intersect(const int32_t* active, RayHit16& packet, Coherence coherence = Coherence::kIncoherent) const;
  void occluded(const int32_t* active, RayHit16& packet, const HitFilter* const* filters = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace dualight
