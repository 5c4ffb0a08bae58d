// What BSDFs with more than one lobe share: picking a lobe with the first random number and
// reusing what is left of it [pbrt-v3 sec. 14.1.1], so sampling needs two numbers per bounce
// whatever the BSDF; and, for the BSDFs that reflect on their front only (Mitsuba 3's
// conductors and plastics), the `twosided` wrapper that mirrors the back onto the front.
#pragma once
#include <algorithm>

#include "core/vec3.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"

namespace dualight {

// True with probability p; u is then rescaled to a fresh uniform number on [0, 1).
inline bool choose_lobe(float& u, float p) {
  constexpr float kBelowOne = 0x1.fffffep-1f;
  if (u < p) {
    u = std::min(u / p, kBelowOne);
    return true;
  }
  u = std::min((u - p) / (1.f - p), kBelowOne);
  return false;
}

// Brings wo to the front (z > 0) of a one-sided reflector: false when it is behind and the
// BSDF is not two-sided (it reflects nothing there). `flipped` says to mirror wi back.
inline bool to_front(bool two_sided, Vec3& wo, bool& flipped) {
  flipped = false;
  if (wo.z > 0.f) return true;
  if (!two_sided || !(wo.z < 0.f)) return false;
  wo.z = -wo.z;
  flipped = true;
  return true;
}

// The pair (wo, wi) seen from the front of a one-sided reflector; false where it reflects
// nothing (wo behind a one-sided surface, or wi on the other side of wo).
inline bool pair_to_front(bool two_sided, Vec3& wo, Vec3& wi) {
  bool flipped = false;
  if (!to_front(two_sided, wo, flipped)) return false;
  if (flipped) wi.z = -wi.z;
  return wi.z > 0.f;
}

// The mirror direction of a one-sided reflector's Dirac lobe (Conductor, Plastic): false for
// a refraction or when wo is behind a one-sided surface.
inline bool front_mirror_direction(bool two_sided, const Vec3& wo, bool refraction, Vec3& wi) {
  Vec3 o = wo;
  bool flipped = false;
  if (refraction || !to_front(two_sided, o, flipped)) return false;
  wi = reflect_local(wo);
  return true;
}

// Completes a sample in a non-Dirac direction wi from the BSDF's own eval_f and pdf_w (its
// density over all its lobes), so weight and density agree with them by construction.
template <class B>
bool finish_sample(const B& b, const Vec3& wo, const Vec3& wi, TransportMode mode, BsdfSample& s) {
  s.wi = wi;
  s.pdf_w = pdf_w(b, wo, wi, mode);
  if (!(s.pdf_w > 0.f)) return false;
  s.weight = eval_f(b, wo, wi, mode) * (std::abs(wi.z) / s.pdf_w);
  s.delta = false;
  return true;
}

}  // namespace dualight
