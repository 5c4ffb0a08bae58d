#include "geometry/embree_accel.h"

#include <cmath>
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

// Embree hands the query context to the filter callback: our filter rides behind it.
struct FilterContext {
  QueryContext context;
  const HitFilter* filter;
};

void filter_callback(const RTCFilterFunctionNArguments* args) {
  const auto* fc = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const uint32_t prim = RTCHitN_primID(args->hit, args->N, i);
    const float t = RTCRayN_tfar(args->ray, args->N, i);  // the candidate hit's distance
    if (fc->filter->ignore(fc->filter->user, prim, t)) args->valid[i] = 0;
  }
}

}  // namespace

struct EmbreeAccel::Impl {
  DeviceHandle device;
  SceneHandle scene;
};

EmbreeAccel::EmbreeAccel(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                         bool robust)
    : impl_(std::make_unique<Impl>()) {
  impl_->device.reset(rtcNewDevice(nullptr));
  if (!impl_->device) throw std::runtime_error("could not create an Embree device");
  RTCDevice device = impl_->device.get();
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
  rtcInitRayQueryContext(&fc.context);
  RTCOccludedArguments args;
  rtcInitOccludedArguments(&args);
  args.context = &fc.context;
  if (filter != nullptr) {
    // Embree 4 runs an argument filter only when the query asks for it on every geometry.
    args.filter = filter_callback;
    args.flags = static_cast<RTCRayQueryFlags>(args.flags | RTC_RAY_QUERY_FLAG_INVOKE_ARGUMENT_FILTER);
    args.feature_mask = static_cast<RTCFeatureFlags>(RTC_FEATURE_FLAG_ALL);
  }
  rtcOccluded1(impl_->scene.get(), &r, &args);
#else
  rtcInitIntersectContext(&fc.context);
  if (filter != nullptr) fc.context.filter = filter_callback;
  rtcOccluded1(impl_->scene.get(), &fc.context, &r);
#endif
  // Embree signals occlusion by setting tfar to -inf.
  return r.tfar < 0.f;
}

}  // namespace dualight
