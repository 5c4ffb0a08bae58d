#include "geometry/embree_accel.h"

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>

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
bool embree_accepts(const Ray& ray) {
  constexpr float kLarge = 1.844e18f;
  for (int i = 0; i < 3; ++i) {
    if (!(std::fabs(ray.o[i]) <= kLarge) || !(std::fabs(ray.d[i]) <= kLarge)) return false;
  }
  return !std::isnan(ray.tmax) && ray.tmax >= 0.f;
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

// A packet of rays as Embree's RTCRay16; the ids let the filter find each lane's filter.
void fill_packet(const RayPacket& rays, RTCRay16& r) {
  constexpr size_t bytes = sizeof(float) * RayPacket::kLanes;
  std::memcpy(r.org_x, rays.ox, bytes);
  std::memcpy(r.org_y, rays.oy, bytes);
  std::memcpy(r.org_z, rays.oz, bytes);
  std::memcpy(r.dir_x, rays.dx, bytes);
  std::memcpy(r.dir_y, rays.dy, bytes);
  std::memcpy(r.dir_z, rays.dz, bytes);
  std::memcpy(r.tnear, rays.tmin, bytes);
  std::memcpy(r.tfar, rays.tmax, bytes);
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    r.time[i] = 0.f;
    r.mask[i] = 0xffffffffu;
    r.id[i] = static_cast<unsigned>(i);
    r.flags[i] = 0;
  }
}

// Embree's lane masks (-1: trace) for the active lanes whose rays it accepts (embree_accepts);
// false when none.
bool packet_valid(const RayPacket& rays, int* valid) {
  constexpr float kLarge = 1.844e18f;
  int any = 0;
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    // Without branches, so the loop vectorizes; a NaN tmax fails tmax >= 0.
    const int ok = (std::fabs(rays.ox[i]) <= kLarge) & (std::fabs(rays.oy[i]) <= kLarge) &
                   (std::fabs(rays.oz[i]) <= kLarge) & (std::fabs(rays.dx[i]) <= kLarge) &
                   (std::fabs(rays.dy[i]) <= kLarge) & (std::fabs(rays.dz[i]) <= kLarge) & (rays.tmax[i] >= 0.f) &
                   (rays.active[i] != 0);
    valid[i] = -ok;
    any |= ok;
  }
  return any != 0;
}

}  // namespace

struct EmbreeAccel::Impl {
  DeviceHandle device;
  SceneHandle scene;
  // rtcIntersect16 and rtcOccluded16 need a CPU (and an Embree build) with AVX-512: elsewhere
  // packets are traced lane by lane, with the same results.
  bool packets16 = false;
};

EmbreeAccel::EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                         bool robust, bool packets)
    : impl_(std::make_unique<Impl>()) {
  impl_->device.reset(rtcNewDevice(nullptr));
  if (!impl_->device) throw std::runtime_error("could not create an Embree device");
  RTCDevice device = impl_->device.get();
  impl_->packets16 = packets && rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_NATIVE_RAY16_SUPPORTED) != 0;
  impl_->scene.reset(rtcNewScene(device));
  RTCScene scene = impl_->scene.get();
  rtcSetSceneBuildQuality(scene, RTC_BUILD_QUALITY_HIGH);
#if DUALIGHT_EMBREE4
  const int filter_flag = RTC_SCENE_FLAG_FILTER_FUNCTION_IN_ARGUMENTS;
#else
  const int filter_flag = RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION;
#endif
  rtcSetSceneFlags(scene, static_cast<RTCSceneFlags>(filter_flag | (robust ? RTC_SCENE_FLAG_ROBUST : 0)));

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
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  check_device(device, "scene commit");
}

EmbreeAccel::~EmbreeAccel() = default;

RayHit EmbreeAccel::intersect(const Ray& ray) const {
  if (!embree_accepts(ray)) return RayHit{};
  RTCRayHit rh;
  fill_ray(ray, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
#if DUALIGHT_EMBREE4
  rtcIntersect1(impl_->scene.get(), &rh);
#else
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect1(impl_->scene.get(), &ctx, &rh);
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

void EmbreeAccel::intersect(const RayPacket& rays, HitPacket& hits) const {
  alignas(64) int valid[RayPacket::kLanes];
  for (uint32_t& p : hits.prim) p = RayHit::kNoHit;
  if (!impl_->packets16) {
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      if (rays.active[i] == 0) continue;
      const RayHit h = intersect(rays.ray(i));
      hits.t[i] = h.t, hits.u[i] = h.u, hits.v[i] = h.v, hits.prim[i] = h.prim;
    }
    return;
  }
  if (!packet_valid(rays, valid)) return;
  alignas(64) RTCRayHit16 rh;
  fill_packet(rays, rh.ray);
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
#if DUALIGHT_EMBREE4
  rtcIntersect16(valid, impl_->scene.get(), &rh);
#else
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  rtcIntersect16(valid, impl_->scene.get(), &ctx, &rh);
#endif
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    if (valid[i] == 0 || rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
    hits.t[i] = rh.ray.tfar[i];
    hits.u[i] = rh.hit.u[i];
    hits.v[i] = rh.hit.v[i];
    hits.prim[i] = rh.hit.primID[i];
  }
}

void EmbreeAccel::occluded(const RayPacket& rays, const HitFilter* const* filters, int32_t* blocked) const {
  alignas(64) int valid[RayPacket::kLanes];
  // Rays Embree would not accept count as occluded, as in occluded() above.
  for (int i = 0; i < RayPacket::kLanes; ++i) blocked[i] = rays.active[i] != 0 ? 1 : 0;
  if (!impl_->packets16) {
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      if (rays.active[i] != 0) blocked[i] = occluded(rays.ray(i), filters != nullptr ? filters[i] : nullptr) ? 1 : 0;
    }
    return;
  }
  if (!packet_valid(rays, valid)) return;
  alignas(64) RTCRay16 r;
  fill_packet(rays, r);
  FilterContext fc{};
  fc.lane_filters = filters;
#if DUALIGHT_EMBREE4
  RTCOccludedArguments args = occluded_arguments(fc, filters != nullptr);
  rtcOccluded16(valid, impl_->scene.get(), &r, &args);
#else
  init_context(fc, filters != nullptr);
  rtcOccluded16(valid, impl_->scene.get(), &fc.context, &r);
#endif
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    if (valid[i] != 0) blocked[i] = r.tfar[i] < 0.f ? 1 : 0;
  }
}

}  // namespace dualight
