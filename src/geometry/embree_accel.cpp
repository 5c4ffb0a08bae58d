#include "geometry/embree_accel.h"

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#if __has_include(<embree4/rtcore.h>)
#include <embree4/rtcore.h>
#define DUALIGHT_EMBREE4 1
#else
#include <embree3/rtcore.h>
#define DUALIGHT_EMBREE4 0
#endif

namespace dualight {

namespace {

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using DeviceHandle = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using SceneHandle = std::unique_ptr<RTCSceneTy, SceneDeleter>;

void check_device(RTCDevice device, const char* what) {
  const RTCError err = rtcGetDeviceError(device);
  if (err != RTC_ERROR_NONE) {
    throw std::runtime_error(std::string("Embree error during ") + what + " (code " +
                             std::to_string(static_cast<int>(err)) + ")");
  }
}

// What Embree accepts (its RayK::valid(), an assertion in some builds, e.g. Debian's): origin
// and direction within +-1.844e18 (FLT_LARGE), and a tfar that is not NaN. Rays outside that
// (from scenes at extreme scales, or NaN that slipped through) are treated as missing
// everything and as occluded, which adds no light, instead of aborting the process.
// Without branches, so a loop over a packet's lanes vectorizes; a NaN tmax fails tmax >= 0.
inline bool embree_accepts(float ox, float oy, float oz, float dx, float dy, float dz, float tmax) {
  constexpr float kLarge = 1.844e18f;
  return (std::fabs(ox) <= kLarge) & (std::fabs(oy) <= kLarge) & (std::fabs(oz) <= kLarge) &
         (std::fabs(dx) <= kLarge) & (std::fabs(dy) <= kLarge) & (std::fabs(dz) <= kLarge) & (tmax >= 0.f);
}
bool embree_accepts(const Ray& ray) {
  return embree_accepts(ray.o.x, ray.o.y, ray.o.z, ray.d.x, ray.d.y, ray.d.z, ray.tmax);
}

void fill_ray(const Ray& ray, RTCRay& r) {
  r.org_x = ray.o.x;
  r.org_y = ray.o.y;
  r.org_z = ray.o.z;
  r.dir_x = ray.d.x;
  r.dir_y = ray.d.y;
  r.dir_z = ray.d.z;
  r.tnear = ray.tmin;
  r.tfar = ray.tmax;
  r.time = 0.f;
  r.mask = 0xffffffffu;  // Embree 4 changed the default mask: always set it.
  r.id = 0;
  r.flags = 0;
}

#if DUALIGHT_EMBREE4
using QueryContext = RTCRayQueryContext;
#else
using QueryContext = RTCIntersectContext;
#endif

// Embree hands the query context to the filter callback: our filter rides behind it (a
// packet's, one per lane, found by the ray's id).
struct FilterContext {
  QueryContext context;
  const HitFilter* filter;
  const HitFilter* const* lane_filters;
};

void filter_callback(const RTCFilterFunctionNArguments* args) {
  const auto* fc = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const HitFilter* filter =
        fc->lane_filters != nullptr ? fc->lane_filters[RTCRayN_id(args->ray, args->N, i)] : fc->filter;
    if (filter == nullptr) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float t = RTCRayN_tfar(args->ray, args->N, i);  // the candidate hit's distance
    if (filter->ignore(filter->user, prim, t)) args->valid[i] = 0;
  }
}

#if DUALIGHT_EMBREE4
// An occlusion query's arguments, with fc's filter when `filtered`.
RTCOccludedArguments occluded_arguments(FilterContext& fc, bool filtered) {
  rtcInitRayQueryContext(&fc.context);
  RTCOccludedArguments args;
  rtcInitOccludedArguments(&args);
  args.context = &fc.context;
  if (filtered) {
    // Embree 4 runs an argument filter only when the query asks for it on every geometry.
    args.filter = filter_callback;
    args.flags = static_cast<RTCRayQueryFlags>(args.flags | RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER);
    args.feature_mask = static_cast<RTCFeatureFlags>(RTC_FEATURE_FLAG_ALL);
  }
  return args;
}
#else
// An occlusion query's context, with fc's filter when `filtered`.
void init_context(FilterContext& fc, bool filtered) {
  rtcInitIntersectContext(&fc.context);
  if (filtered) fc.context.filter = filter_callback;
}
#endif

// Lanes [first, first + K) of a packet as Embree's RTCRay16 or RTCRay8; each ray's id is its
// lane in the whole packet, so the filter finds the lane's filter.
template <class RayK, int K>
void fill_lanes(const RayPacket& rays, int first, RayK& r) {
  constexpr size_t bytes = sizeof(float) * K;
  std::memcpy(r.org_x, rays.ox + first, bytes);
  std::memcpy(r.org_y, rays.oy + first, bytes);
  std::memcpy(r.org_z, rays.oz + first, bytes);
  std::memcpy(r.dir_x, rays.dx + first, bytes);
  std::memcpy(r.dir_y, rays.dy + first, bytes);
  std::memcpy(r.dir_z, rays.dz + first, bytes);
  std::memcpy(r.tnear, rays.tmin + first, bytes);
  std::memcpy(r.tfar, rays.tmax + first, bytes);
  for (int i = 0; i < K; ++i) {
    r.time[i] = 0.f;
    r.mask[i] = 0xffffffffu;
    r.id[i] = static_cast<unsigned>(first + i);
    r.flags[i] = 0;
  }
}

// Embree's K-wide closest-hit and occlusion queries (K = 16 or 8).
template <int K, class RayHitK>
void rtc_intersect(const int* valid, RTCScene scene, RayHitK* rh, Coherence coherence) {
#if DUALIGHT_EMBREE4
  RTCIntersectArguments args;
  rtcInitIntersectArguments(&args);
  if (coherence == Coherence::kCoherent) args.flags = RTC_RAY_QUERY_FLAG_COHERENT;
  if constexpr (K == 16) {
    rtcIntersect16(valid, scene, rh, &args);
  } else {
    rtcIntersect8(valid, scene, rh, &args);
  }
#else
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  if (coherence == Coherence::kCoherent) ctx.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  if constexpr (K == 16) {
    rtcIntersect16(valid, scene, &ctx, rh);
  } else {
    rtcIntersect8(valid, scene, &ctx, rh);
  }
#endif
}
template <int K, class RayK>
void rtc_occluded(const int* valid, RTCScene scene, RayK* r, FilterContext& fc, bool filtered) {
#if DUALIGHT_EMBREE4
  RTCOccludedArguments args = occluded_arguments(fc, filtered);
  if constexpr (K == 16) {
    rtcOccluded16(valid, scene, r, &args);
  } else {
    rtcOccluded8(valid, scene, r, &args);
  }
#else
  init_context(fc, filtered);
  if constexpr (K == 16) {
    rtcOccluded16(valid, scene, &fc.context, r);
  } else {
    rtcOccluded8(valid, scene, &fc.context, r);
  }
#endif
}

bool any_valid(const int* valid, int n) {
  int any = 0;
  for (int i = 0; i < n; ++i) any |= valid[i];
  return any != 0;
}

// The closest hits of lanes [first, first + K) (valid: the whole packet's mask).
template <class RayHitK, int K>
void intersect_lanes(RTCScene scene, const RayPacket& rays, const int* valid, int first, HitPacket& hits,
                     Coherence coherence) {
  if (!any_valid(valid + first, K)) return;
  alignas(64) RayHitK rh;
  fill_lanes<decltype(rh.ray), K>(rays, first, rh.ray);
  for (int i = 0; i < K; ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtc_intersect<K>(valid + first, scene, &rh, coherence);
  for (int i = 0; i < K; ++i) {
    if (valid[first + i] == 0 || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
    hits.t[first + i] = rh.ray.tfar[i];
    hits.u[first + i] = rh.hit.u[i];
    hits.v[first + i] = rh.hit.v[i];
    hits.prim[first + i] = rh.hit.primID[i];
  }
}

// Occlusion of lanes [first, first + K), through each lane's filter.
template <class RayK, int K>
void occluded_lanes(RTCScene scene, const RayPacket& rays, const HitFilter* const* filters, const int* valid,
                    int first, int32_t* blocked) {
  if (!any_valid(valid + first, K)) return;
  alignas(64) RayK r;
  fill_lanes<RayK, K>(rays, first, r);
  FilterContext fc{};
  fc.lane_filters = filters;
  rtc_occluded<K>(valid + first, scene, &r, fc, filters != nullptr);
  for (int i = 0; i < K; ++i) {
    if (valid[first + i] != 0) blocked[first + i] = r.tfar[i] < 0.f ? 1 : 0;
  }
}

// Embree's lane masks (-1: trace) for the active lanes whose rays it accepts (embree_accepts);
// false when none.
bool packet_valid(const RayPacket& rays, int* valid) {
  int any = 0;
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    const int ok = embree_accepts(rays.ox[i], rays.oy[i], rays.oz[i], rays.dx[i], rays.dy[i], rays.dz[i],
                                  rays.tmax[i]) &
                   (rays.active[i] != 0);
    valid[i] = -ok;
    any |= ok;
  }
  return any != 0;
}

// Commits `geom`, hands it to `scene` (which then owns it) and builds the scene's BVH.
void commit_into(RTCDevice device, RTCScene scene, RTCGeometry geom) {
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  check_device(device, "scene commit");
}

// An empty scene of high build quality (spatial splits) with the given RTCSceneFlags.
SceneHandle new_scene(RTCDevice device, int flags) {
  SceneHandle scene(rtcNewScene(device));
  rtcSetSceneBuildQuality(scene.get(), RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene.get(), static_cast<RTCSceneFlags>(flags));
  return scene;
}

// A scene without flags (fast mode, no filters) of the triangles whose buffers another
// geometry owns (vertices padded for Embree's 16-byte loads, as it allocated them).
SceneHandle scene_sharing(RTCDevice device, const float* vertices, size_t n_vertices, const uint32_t* indices,
                          size_t n_triangles) {
  SceneHandle scene = new_scene(device, RTC_SCENE_FLAG_NONE);
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices, 0, 3 * sizeof(float),
                             n_vertices);
  rtcSetSharedGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices, 0, 3 * sizeof(uint32_t),
                             n_triangles);
  commit_into(device, scene.get(), geom);
  return scene;
}

}  // namespace

struct EmbreeAccel::Impl {
  DeviceHandle device;
  SceneHandle scene;    // every query's, with the filter flag (occlusion's filters)
  SceneHandle closest;  // fast mode: the closest-hit queries', without it (else null)
  RTCScene closest_hits() const { return closest ? closest.get() : scene.get(); }
  // Embree's widest packet queries this CPU (and Embree's build) runs: 16 needs AVX-512, 8 AVX;
  // 1: lane by lane. Every width gives the same results.
  int packet_width = 1;
};

EmbreeAccel::EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                         bool robust, int max_packet)
    : impl_(std::make_unique<Impl>()) {
  impl_->device.reset(rtcNewDevice(nullptr));
  if (!impl_->device) throw std::runtime_error("could not create an Embree device");
  RTCDevice device = impl_->device.get();
  for (const auto& [width, property] : {std::pair{16, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED},
                                         std::pair{8, RTC_DEVICE_PROPERTY_NATIVE_RAY8_SUPPORTED}}) {
    if (width <= max_packet && rtcGetDeviceProperty(device, property) != 0) {
      impl_->packet_width = width;
      break;
    }
  }
#if DUALIGHT_EMBREE4
  const int filter_flag = RTC_SCENE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS;
#else
  const int filter_flag = RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
#endif
  impl_->scene = new_scene(device, filter_flag | (robust ? RTC_SCENE_FLAG_ROBUST : 0));

  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  const size_t n_vertices = positions.size() / 3, n_triangles = triangles.size() / 3;
  // Embree reads vertices with 16-byte loads: the buffer it allocates is padded for that.
  auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0,
                                                         RTC_FORMAT_FLOAT3, 3 * sizeof(float), n_vertices));
  auto* ib = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), n_triangles));
  check_device(device, "buffer allocation");
  std::copy(positions.begin(), positions.end(), vb);
  std::copy(triangles.begin(), triangles.end(), ib);
  commit_into(device, impl_->scene.get(), geom);
  if (!robust) impl_->closest = scene_sharing(device, vb, n_vertices, ib, n_triangles);
}

EmbreeAccel::~EmbreeAccel() = default;

RayHit EmbreeAccel::intersect(const Ray& ray) const {
  if (!embree_accepts(ray)) return RayHit{};
  RTCRayHit rh;
  fill_ray(ray, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
#if DUALIGHT_EMBREE4
  rtcIntersect1(impl_->closest_hits(), &rh);
#else
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(impl_->closest_hits(), &ctx, &rh);
#endif
  RayHit out;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    out.t = rh.ray.tfar;
    out.u = rh.hit.u;
    out.v = rh.hit.v;
    out.prim = rh.hit.primID;
  }
  return out;
}

bool EmbreeAccel::occluded(const Ray& ray, const HitFilter* filter) const {
  if (!embree_accepts(ray)) return true;
  RTCRay r;
  fill_ray(ray, r);
  FilterContext fc{};
  fc.filter = filter;
#if DUALIGHT_EMBREE4
  RTCOccludedArguments args = occluded_arguments(fc, filter != nullptr);
  rtcOccluded1(impl_->scene.get(), &r, &args);
#else
  init_context(fc, filter != nullptr);
  rtcOccluded1(impl_->scene.get(), &fc.context, &r);
#endif
  // Embree signals occlusion by setting tfar to -inf.
  return r.tfar < 0.f;
}

void EmbreeAccel::intersect(const RayPacket& rays, HitPacket& hits, Coherence coherence) const {
  for (uint32_t& p : hits.prim) p = RayHit::kNoHit;
  if (impl_->packet_width == 1) {
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      if (rays.active[i] == 0) continue;
      const RayHit h = intersect(rays.ray(i));
      hits.t[i] = h.t, hits.u[i] = h.u, hits.v[i] = h.v, hits.prim[i] = h.prim;
    }
    return;
  }
  alignas(64) int valid[RayPacket::kLanes];
  if (!packet_valid(rays, valid)) return;
  if (impl_->packet_width == 16) {
    intersect_lanes<RTCRayHit16, 16>(impl_->closest_hits(), rays, valid, 0, hits, coherence);
  } else {
    for (int first = 0; first < RayPacket::kLanes; first += 8) {
      intersect_lanes<RTCRayHit8, 8>(impl_->closest_hits(), rays, valid, first, hits, coherence);
    }
  }
}

namespace {

// Whether RayHit16 is the Embree compiled against's RTCRayHit16 (Embree 3's is; Embree 4's may
// hold more instance fields).
constexpr bool same_layout() {
  using R = RTCRayHit16;
  return sizeof(RayHit16) == sizeof(R) && offsetof(RayHit16, ox) == offsetof(R, ray.org_x) &&
         offsetof(RayHit16, tmin) == offsetof(R, ray.tnear) && offsetof(RayHit16, dx) == offsetof(R, ray.dir_x) &&
         offsetof(RayHit16, time) == offsetof(R, ray.time) && offsetof(RayHit16, tmax) == offsetof(R, ray.tfar) &&
         offsetof(RayHit16, mask) == offsetof(R, ray.mask) && offsetof(RayHit16, id) == offsetof(R, ray.id) &&
         offsetof(RayHit16, flags) == offsetof(R, ray.flags) && offsetof(RayHit16, ngx) == offsetof(R, hit.Ng_x) &&
         offsetof(RayHit16, u) == offsetof(R, hit.u) && offsetof(RayHit16, v) == offsetof(R, hit.v) &&
         offsetof(RayHit16, prim) == offsetof(R, hit.primID) && offsetof(RayHit16, geom) == offsetof(R, hit.geomID) &&
         offsetof(RayHit16, inst) == offsetof(R, hit.instID);
}

// values[i] = value where mask[i] is -1 (else 0), lane by lane without a branch: bit masks.
template <class T>
void set_where(const int32_t* mask, T* values, T value) {
  static_assert(sizeof(T) == sizeof(uint32_t));
  uint32_t bits[RayHit16::kLanes], v;
  std::memcpy(bits, values, sizeof bits);
  std::memcpy(&v, &value, sizeof v);
  for (int i = 0; i < RayHit16::kLanes; ++i) {
    const auto m = static_cast<uint32_t>(mask[i]);
    bits[i] = (bits[i] & ~m) | (v & m);
  }
  std::memcpy(values, bits, sizeof bits);
}

// Embree's lane masks (-1: trace) for the active lanes whose rays it accepts (embree_accepts),
// and the ray fields the caller does not set.
void prepare_lanes(const int32_t* active, RayHit16& p, int* valid) {
  for (int i = 0; i < RayHit16::kLanes; ++i) {
    valid[i] = -(embree_accepts(p.ox[i], p.oy[i], p.oz[i], p.dx[i], p.dy[i], p.dz[i], p.tmax[i]) & (active[i] != 0));
    p.time[i] = 0.f, p.mask[i] = 0xffffffffu, p.id[i] = static_cast<uint32_t>(i), p.flags[i] = 0;
    p.geom[i] = RTC_INVALID_GEOMETRY_ID, p.inst[i] = RTC_INVALID_GEOMETRY_ID;
  }
}

// The rays of a RayHit16 as a RayPacket (for the copying queries).
RayPacket packet_rays(const int32_t* active, const RayHit16& p) {
  RayPacket rays;
  for (int i = 0; i < RayHit16::kLanes; ++i) {
    rays.set(i, p.ray(i));
    rays.active[i] = active[i];
  }
  return rays;
}

}  // namespace

void EmbreeAccel::occluded(const int32_t* active, RayHit16& p, const HitFilter* const* filters) const {
  constexpr int kLanes = RayHit16::kLanes;
  alignas(64) int valid[kLanes];
  prepare_lanes(active, p, valid);
  if constexpr (same_layout() && offsetof(RTCRayHit16, ray) == 0) {
    if (impl_->packet_width == 16) {
      // Without a branch per lane (mispredicted where lanes differ): masks, as set_where.
      alignas(64) int32_t refused[kLanes];
      for (int i = 0; i < kLanes; ++i) refused[i] = -static_cast<int32_t>((active[i] != 0) & (valid[i] == 0));
      set_where(refused, p.tmax, -std::numeric_limits<float>::infinity());
      FilterContext fc{};
      fc.lane_filters = filters;
      rtc_occluded<16>(valid, impl_->scene.get(), reinterpret_cast<RTCRay16*>(&p), fc, filters != nullptr);
      return;
    }
  }
  int32_t blocked[kLanes];
  occluded(packet_rays(active, p), filters, blocked);
  for (int i = 0; i < kLanes; ++i) {
    if (active[i] != 0 && blocked[i] != 0) p.tmax[i] = -std::numeric_limits<float>::infinity();
  }
}

void EmbreeAccel::intersect(const int32_t* active, RayHit16& p, Coherence coherence) const {
  constexpr int kLanes = RayHit16::kLanes;
  static_assert(kLanes == RayPacket::kLanes);
  alignas(64) int valid[kLanes];
  prepare_lanes(active, p, valid);
  if constexpr (same_layout()) {
    if (impl_->packet_width == 16) {
      rtc_intersect<16>(valid, impl_->closest_hits(), reinterpret_cast<RTCRayHit16*>(&p), coherence);
      alignas(64) int32_t missed[kLanes];  // without a branch per lane, as in occluded above
      for (int i = 0; i < kLanes; ++i) {
        missed[i] = -static_cast<int32_t>((valid[i] == 0) | (p.geom[i] == RTC_INVALID_GEOMETRY_ID));
      }
      set_where(missed, p.prim, RayHit::kNoHit);
      return;
    }
  }
  HitPacket hits;
  intersect(packet_rays(active, p), hits, coherence);
  for (int i = 0; i < kLanes; ++i) {
    p.prim[i] = hits.prim[i];
    if (hits.prim[i] == RayHit::kNoHit) continue;
    p.tmax[i] = hits.t[i], p.u[i] = hits.u[i], p.v[i] = hits.v[i];
  }
}

void EmbreeAccel::occluded(const RayPacket& rays, const HitFilter* const* filters, int32_t* blocked) const {
  // Rays Embree would not accept count as occluded, as in occluded() above.
  for (int i = 0; i < RayPacket::kLanes; ++i) blocked[i] = rays.active[i] != 0 ? 1 : 0;
  if (impl_->packet_width == 1) {
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      if (rays.active[i] != 0) blocked[i] = occluded(rays.ray(i), filters != nullptr ? filters[i] : nullptr) ? 1 : 0;
    }
    return;
  }
  alignas(64) int valid[RayPacket::kLanes];
  if (!packet_valid(rays, valid)) return;
  if (impl_->packet_width == 16) {
    occluded_lanes<RTCRay16, 16>(impl_->scene.get(), rays, filters, valid, 0, blocked);
  } else {
    for (int first = 0; first < RayPacket::kLanes; first += 8) {
      occluded_lanes<RTCRay8, 8>(impl_->scene.get(), rays, filters, valid, first, blocked);
    }
  }
}

}  // namespace dualight
