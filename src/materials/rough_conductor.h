// Rough conductor, as Mitsuba 3's `roughconductor`: the Torrance-Sparrow microfacet reflection
// F D G / (4 cos_o cos_i) with the conductor's Fresnel term, Beckmann or GGX normals (isotropic
// or anisotropic), sampled by visible normals [Walter et al. 2007; Heitz and d'Eon 2014].
// Reflects on its front (z > 0) only unless `two_sided`. Symmetric: the same in both
// transport modes.
#pragma once
#include "core/sampling.h"
#include "materials/bsdf_flags.h"
#include "materials/bsdf_sample.h"
#include "materials/fresnel.h"
#include "materials/lobe_choice.h"
#include "materials/microfacet.h"

namespace dualight {

struct RoughConductor {
  Microfacet distribution;
  Color eta{0.f}, k{1.f};
  Color specular_reflectance{1.f};
  bool two_sided = false;
};

constexpr BsdfFlags flags(const RoughConductor&) { return BsdfFlags::Glossy | BsdfFlags::Reflection; }
inline Color diffuse_reflectance(const RoughConductor&) { return Color(0.f); }

Color eval_f(const RoughConductor& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
float pdf_w(const RoughConductor& b, const Vec3& wo_in, const Vec3& wi_in, TransportMode);
bool sample(const RoughConductor& b, const Vec3& wo_in, Point2 u, TransportMode, BsdfSample& s);
inline DeltaLobe delta_lobe(const RoughConductor&, const Vec3&, const Vec3&) { return {}; }
inline bool delta_direction(const RoughConductor&, const Vec3&, bool, Vec3&) { return false; }

}  // namespace dualight
