// Shading normals [Veach 1997, sec. 5.3; pbrt-v4 sec. 13.x "Shading normals"; Mitsuba 3's
// ptracer]. The BSDF is evaluated in the frame of the shading normal ns (vertex normals
// interpolated), while geometry terms, pdf conversions and ray offsets keep the geometric
// normal ng. As a BSDF of the geometric surface it is
//   f_s(w_light -> w_eye) = f(w_light -> w_eye) |w_light . ns| / |w_light . ng|,
// the measurement's light-side cosine becoming the shading one. That f_s is not symmetric, so
// importance transport, whose path arrives from the light side (wo) and scatters towards the
// eye (wi), needs its adjoint: a walk's weight f_s |wi . ng| / pdf is f |wi . ns| / pdf in
// radiance mode (as on flat surfaces) and that times
//   |wo . ns| |wi . ng| / (|wo . ng| |wi . ns|)                          [Veach 1997, eq. 5.20]
// in importance mode. Without it the light tracer, BDPT and MLT disagree with the path tracer on
// smooth meshes. Where ns = ng (flat triangles) both factors are exactly 1 and are skipped, so
// flat scenes render bit for bit as before.
#pragma once
#include <cmath>

#include "core/vec3.h"
#include "materials/bsdf_sample.h"

namespace dualight {

inline bool is_flat(const Vec3& ng, const Vec3& ns) { return ng.x == ns.x && ng.y == ns.y && ng.z == ns.z; }

// f_s / f, for the light-side direction w_light (world, unit).
inline float shading_ratio(const Vec3& ng, const Vec3& ns, const Vec3& w_light) {
  if (is_flat(ng, ns)) return 1.f;
  const float cos_g = std::abs(dot(w_light, ng));
  return cos_g > 0.f ? std::abs(dot(w_light, ns)) / cos_g : 0.f;
}

// The factor turning a sampled weight f |wi . ns| / pdf into f_s |wi . ng| / pdf, for a path that
// arrived along wo and scatters along wi (world, unit) in `mode`.
inline float walk_weight_correction(const Vec3& ng, const Vec3& ns, const Vec3& wo, const Vec3& wi,
                                    TransportMode mode) {
  if (mode == TransportMode::Radiance || is_flat(ng, ns)) return 1.f;
  const float den = std::abs(dot(wo, ng)) * std::abs(dot(wi, ns));
  return den > 0.f ? std::abs(dot(wo, ns)) * std::abs(dot(wi, ng)) / den : 0.f;
}

// Whether a scattered direction wi (world, unit; local_z its z in the shading frame) leaves by the
// front of the geometric surface, the side its ray starts from. On flat triangles the local z
// decides, as it always did; with shading normals the two sides can differ.
inline bool leaves_front(const Vec3& ng, const Vec3& ns, const Vec3& wi, float local_z) {
  return (is_flat(ng, ns) ? local_z : dot(wi, ng)) > 0.f;
}

}  // namespace dualight
