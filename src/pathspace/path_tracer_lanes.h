// The path tracer in lanes: the camera paths of a batch of pixel samples (up to 256, whole rows
// of a tile at one or more sample indices: pixel_driver.h) advance together, their rays traced as
// Embree packets and their shading computed in SIMD lanes (core/lanes.h: sixteen at a time with
// AVX-512, eight with AVX2, four with SSE2); a lane whose path ends takes the batch's next sample.
// Compiled for each instruction set and chosen at run time by what the CPU supports (AVX-512,
// else AVX2: see choose_path_lanes). As in Mitsuba 3's vectorised variants, lanes are paths, not
// rays of one path.
//
// Each lane computes exactly what the scalar path tracer (path_tracer.cpp) computes for its
// sample: the same sampler (seed, pixel, sample index), the same numbers drawn in the same
// order, the same IEEE operations in the same order (no fused multiply-add), Embree's packet
// hits (the same as its single-ray hits) and the same exact visibility test. So the image is the
// scalar tracer's, bit for bit, on every instruction set; tests hold it to that.
//
// It covers unguided renders of triangles (flat, or with vertex normals interpolated lane by
// lane): Lambertian, mirror and smooth dielectric materials and untextured area, point, spot,
// directional and constant environment emitters run lane-wide; every other BSDF and textured
// materials lane by lane through the scalar code, and so do the light samples and emission of
// every other emitter (environment maps, textured area lights; next_event.h), on any share of
// the scene: the packets still pay (choose_path_lanes).
// render_path falls back to the scalar tracer elsewhere (stats "lanes": "off" then).
#pragma once
#include <immintrin.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/sampler.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "pathspace/next_event.h"
#include "pathspace/path_tracer.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/render_stats.h"

namespace dualight {

// What the kernel gathers per triangle and per emitter, in one place each, copied from the scene
// with the values the scalar tracer reads.
// The BSDFs the lanes compute lane-wide, each as the scalar member does; kLaneOther: any other
// member, or a textured material, evaluated lane by lane by the scalar code itself.
constexpr int32_t kLaneLambertian = 0, kLaneMirror = 1, kLaneDielectric = 2, kLaneOther = 3;
// A triangle in one cache line (at 72 bytes each row spanned two): a hit's gathers touch one line
// per lane. On the caustic box (40972 triangles, a 2.6 MB table) the first of them still waits
// for memory, 3 % of the render's time: the row's latency, which one line or two both pay.
struct alignas(64) LaneTriangle {
  float p[3][3];      // corners
  float n[3];         // unit geometric normal (the shading normal too, unless smooth)
  float albedo[3];    // the Lambertian's albedo, the mirror's reflectance, the dielectric's eta (in [0])
  // (emitter + 1) << 3 | smooth << 2 | bsdf: emitter the index into Scene::emitters() (-1: none),
  // smooth 1 where the triangle interpolates vertex normals (Scene::shading_normal), bsdf
  // kLaneLambertian, kLaneMirror, kLaneDielectric or kLaneOther.
  int32_t packed;
  static constexpr uint32_t kMaxEmitters = (1u << 28) - 1;  // what `packed` holds
};
static_assert(sizeof(LaneTriangle) == 64);
// The most triangles whose rows' offsets (in floats) the gathers' 32-bit indices reach.
constexpr size_t kMaxLaneTriangles = INT32_MAX / (sizeof(LaneTriangle) / 4);
// The emitters the lanes sample lane-wide, each as the scalar member does; kLaneScalarEmitter:
// any other (an environment, a textured area emitter), sampled lane by lane by the scalar code
// (next_event.h).
constexpr int32_t kLaneAreaEmitter = 0, kLanePointEmitter = 1, kLaneSpotEmitter = 2, kLaneDirectionalEmitter = 3,
                  kLaneConstantEmitter = 4, kLaneScalarEmitter = -1;
struct LaneEmitter {
  float p[3][3];       // area: corners; point, spot: p[0] the position
  float n[3];          // area: the normal; directional: the direction towards the light
  float Le[3];         // area, constant: radiance; point, spot: intensity; directional: irradiance
  float pdf_a;         // area: pmf / area, as AreaEmitter's pdf_Le_position rounds it; constant: pdf_Li's
                       // density (pmf / (4 pi)); else the pmf
  float center[3];     // directional, constant: the scene's bounding sphere (reach_beyond)
  float radius;
  uint32_t prim;
  int32_t kind;        // kLaneAreaEmitter, kLanePointEmitter, ... or kLaneScalarEmitter
};

struct PathLanesScene {
  const Scene* scene = nullptr;
  const PinholeCamera* camera = nullptr;
  const PathTracerOptions* options = nullptr;
  std::vector<LaneTriangle> triangles;
  std::vector<LaneEmitter> emitters;
  // Scene::emitter_choice_ends where there are at most kCountedEmitters (the kernel counts the
  // ends a sample passes), else empty (it searches lane by lane).
  static constexpr size_t kCountedEmitters = 32;
  std::vector<float> emitter_ends;
  bool smooth = false;  // some triangle interpolates vertex normals
  const Emitter* environment = nullptr;  // Scene::environment()
  int32_t constant_environment = -1;     // its index into emitters where it is a constant one, else -1
};

// Traces the pixel samples [0, n) (pixel_driver.h's batch estimate): a lane that ends its path
// takes the next sample (path regeneration [Novák et al. 2010]), so the lanes stay busy while
// path lengths differ; values[i]: sample i's radiance estimate.
template <class Sampler>
using TracePathLanes = void (*)(const PathLanesScene& ps, uint64_t seed, int film_width, const PixelSample* samples,
                                size_t n, TraceCounters& counters, Color* values);

struct PathLanesKernels {
  const char* isa = nullptr;  // "sse2", "avx2", "avx512"
  TracePathLanes<IndependentSampler> independent = nullptr;
  TracePathLanes<SobolSampler> sobol = nullptr;
};
// One per instruction set (path_tracer_lanes_<isa>.cpp).
PathLanesKernels path_lanes_kernels_sse2();
PathLanesKernels path_lanes_kernels_avx2();
PathLanesKernels path_lanes_kernels_avx512();

// The kernels options.lanes names (Auto: AVX-512, else AVX2, where the CPU runs it, for scenes
// of lane-wide materials only), or none (Off, a guided render, a scene the lanes do not cover,
// Auto on other materials or on a CPU without AVX2: why_not says which). Throws
// std::invalid_argument for an instruction set this CPU lacks.
struct PathLanesChoice {
  std::optional<PathLanesKernels> kernels;
  std::string why_not;
};
PathLanesChoice choose_path_lanes(const Scene& scene, const PathTracerOptions& options);

// The tables the kernel gathers from (scene, camera and options must outlive it).
PathLanesScene path_lanes_scene(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options);

}  // namespace dualight
