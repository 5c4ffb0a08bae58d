// Smooth-interface optics shared by the BSDFs: the unpolarised Fresnel reflectance of a
// dielectric interface [pbrt-v4 sec. 9.3; Veach 1997, sec. 5.2] and of a conductor (complex
// IOR eta + i k) [Born and Wolf, sec. 14.2; the real-arithmetic form of Mitsuba 3 and pbrt-v3],
// the hemispherical average of the dielectric one [Egan and Hilgeman 1973; d'Eon and Irving
// 2011, the fits Mitsuba 3 uses], and reflection and refraction about a (micro)normal in the
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

// Unpolarised Fresnel reflectance of a conductor with complex IOR eta + i k (relative to the
// exterior), per RGB channel, at incident cosine cos_i >= 0. eta 0, k 1 reflects everything.
inline float fresnel_conductor(float cos_i, float eta, float k) {
  const float c2 = cos_i * cos_i, s2 = 1.f - c2, s4 = s2 * s2;
  const float t1 = eta * eta - k * k - s2;
  const float a2b2 = std::sqrt(std::max(0.f, t1 * t1 + 4.f * k * k * eta * eta));
  const float a = std::sqrt(std::max(0.f, 0.5f * (a2b2 + t1)));
  const float t2 = a2b2 + c2, t3 = 2.f * cos_i * a;
  const float rs = (t2 - t3) / (t2 + t3);
  const float t4 = a2b2 * c2 + s4, t5 = t3 * s2;
  const float rp = rs * (t4 - t5) / (t4 + t5);
  return 0.5f * (rs + rp);
}
inline Color fresnel_conductor(float cos_i, const Color& eta, const Color& k) {
  return {fresnel_conductor(cos_i, eta.x, k.x), fresnel_conductor(cos_i, eta.y, k.y),
          fresnel_conductor(cos_i, eta.z, k.z)};
}

// Fresnel reflectance averaged over the cosine-weighted hemisphere of incident directions, for
// light inside a medium of relative IOR 1 / eta (plastic's internal reflection).
inline float fresnel_diffuse_reflectance(float eta) {
  const float inv = 1.f / eta;
  if (eta < 1.f) return 0.0636f * inv + eta * (eta * -1.4399f + 0.7099f) + 0.6681f;
  float p = -1.36881f;
  for (const float c : {4.98554f, -7.80989f, 6.75335f, -3.4793f, 0.919317f}) p = c + p * inv;
  return p;
}

// Reflection of w about the unit (micro)normal m.
inline Vec3 reflect_about(const Vec3& w, const Vec3& m) { return m * (2.f * dot(w, m)) - w; }

// Refraction of w through the microfacet with normal m (m.z > 0), given the Fresnel terms of
// cos_i = dot(w, m); the caller checks F.R < 1.
inline Vec3 refract_about(const Vec3& w, const Vec3& m, float cos_i, const Fresnel& F) {
  const float eta_ti = 1.f / F.eta_ratio;
  const float cos_t = cos_i > 0.f ? -F.cos_t : F.cos_t;
  return m * (cos_i * eta_ti + cos_t) - w * eta_ti;
}

}  // namespace dualight
