// Smooth conductor (metal), as Mitsuba 3's `conductor`: one Dirac lobe, the mirror direction,
// weighted by the conductor's Fresnel reflectance for complex IOR eta + i k and by
// `specular_reflectance` [pbrt-v4 sec. 9.4]. Reflects on its front (z > 0) only unless
// `two_sided` (Mitsuba's `twosided` around it). eta 0, k 1 is Mitsuba's material "none", a
// perfect mirror.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/lobe_choice.h"

namespace dualight {

struct Conductor {
  Color eta{0.f}, k{1.f};
  Color specular_reflectance{1.f};
  bool two_sided = false;
};

constexpr BsdfFlags flags(const Conductor&) { return BsdfFlags::SpecularReflection; }
inline Color diffuse_reflectance(const Conductor&) { return Color(0.f); }

inline Color eval_f(const Conductor&, const Vec3&, const Vec3&, TransportMode) { return Color(0.f); }
inline float pdf_w(const Conductor&, const Vec3&, const Vec3&, TransportMode) { return 0.f; }

inline bool sample(const Conductor& b, const Vec3& wo_in, Point2, TransportMode, BsdfSample& s) {
  Vec3 wo = wo_in;
  bool flipped = false;
  if (!to_front(b.two_sided, wo, flipped)) return false;
  s.wi = reflect_local(wo_in);
  s.pdf_w = 1.f;
  s.weight = fresnel_conductor(wo.z, b.eta, b.k) * b.specular_reflectance;
  s.delta = true;
  return true;
}
inline DeltaLobe delta_lobe(const Conductor& b, const Vec3& wo, const Vec3& wi) {
  DeltaLobe lobe;
  Vec3 o = wo, i = wi;
  lobe.refraction = !same_hemisphere(wo, wi);
  if (!pair_to_front(b.two_sided, o, i)) return lobe;
  lobe.coef = fresnel_conductor(o.z, b.eta, b.k) * b.specular_reflectance;
  lobe.prob = 1.f;
  return lobe;
}
inline bool delta_direction(const Conductor& b, const Vec3& wo, bool refraction, Vec3& wi) {
  return front_mirror_direction(b.two_sided, wo, refraction, wi);
}

}  // namespace dualight
