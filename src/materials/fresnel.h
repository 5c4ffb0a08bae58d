// Smooth-interface optics shared by the BSDFs: the unpolarised Fresnel reflectance of a
// dielectric interface [pbrt-v4 sec. 9.3; Veach 1997, sec. 5.2] and mirror reflection in the
// local frame (z along the normal).
#pragma once
#include <algorithm>
#include <cmath>

#include "core/vec3.h"

namespace dualight {

inline bool same_hemisphere(const Vec3& a, const Vec3& b) { return a.z * b.z > 0.f; }

inline Vec3 reflect_local(const Vec3& w) { return {-w.x, -w.y, w.z}; }

// Unpolarised Fresnel reflectance of a smooth interface. cos_i is the cosine of the incident
// direction with the normal (negative: arriving from the interior); eta = interior / exterior IOR.
struct Fresnel {
  float R;          // reflectance (1 under total internal reflection)
  float cos_t;      // |cosine| of the refracted direction
  float eta_ratio;  // IOR on the refracted side / IOR on the incident side
};
inline Fresnel fresnel_dielectric(float cos_i, float eta) {
  const float eta_ratio = cos_i >= 0.f ? eta : 1.f / eta;
  const float ci = std::min(std::abs(cos_i), 1.f);
  const float sin2_t = (1.f - ci * ci) / (eta_ratio * eta_ratio);
  if (sin2_t >= 1.f) return {1.f, 0.f, eta_ratio};
  const float ct = std::sqrt(1.f - sin2_t);
  const float rs = (ci - eta_ratio * ct) / (ci + eta_ratio * ct);
  const float rp = (eta_ratio * ci - ct) / (eta_ratio * ci + ct);
  return {0.5f * (rs * rs + rp * rp), ct, eta_ratio};
}

}  // namespace dualight
