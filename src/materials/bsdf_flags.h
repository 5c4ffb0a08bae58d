// What a BSDF is, as it reports itself (pbrt-v4's BxDFFlags, Mitsuba 3's BSDFFlags): which
// lobes it has (diffuse, glossy, specular = Dirac) and on which side (reflection,
// transmission). Callers decide through these flags, never by asking for a concrete type, so a
// new BSDF is its own struct with its flags and maths, and every estimator treats it right.
#pragma once
#include <cstdint>

namespace dualight {

enum class BsdfFlags : uint8_t {
  None = 0,
  Reflection = 1 << 0,
  Transmission = 1 << 1,
  Diffuse = 1 << 2,
  Glossy = 1 << 3,
  Specular = 1 << 4,  // Dirac lobes: only sampling finds their directions
  DiffuseReflection = Diffuse | Reflection,
  SpecularReflection = Specular | Reflection,
  SpecularTransmission = Specular | Transmission,
};

constexpr BsdfFlags operator|(BsdfFlags a, BsdfFlags b) {
  return static_cast<BsdfFlags>(static_cast<uint8_t>(a) | static_cast<uint8_t>(b));
}
constexpr bool has_any(BsdfFlags f, BsdfFlags of) { return (static_cast<uint8_t>(f) & static_cast<uint8_t>(of)) != 0; }

// Only Dirac lobes: a connection (shadow ray, light sample) to this BSDF carries nothing.
constexpr bool is_delta(BsdfFlags f) {
  return has_any(f, BsdfFlags::Specular) && !has_any(f, BsdfFlags::Diffuse | BsdfFlags::Glossy);
}
// Some Dirac lobe (MLT's caustic and multi-chain perturbations need one in the scene).
constexpr bool has_specular(BsdfFlags f) { return has_any(f, BsdfFlags::Specular); }
// Dirac lobes beside non-Dirac ones (smooth plastic's coat over its base): a vertex is specular
// or not by the lobe a path takes there, not by its BSDF.
constexpr bool mixes_delta(BsdfFlags f) {
  return has_any(f, BsdfFlags::Specular) && has_any(f, BsdfFlags::Diffuse | BsdfFlags::Glossy);
}
// Light passes to the other side of the surface.
constexpr bool has_transmission(BsdfFlags f) { return has_any(f, BsdfFlags::Transmission); }
// Only diffuse reflection: what radiosity can solve (view-independent outgoing radiance).
constexpr bool is_diffuse_reflector(BsdfFlags f) {
  return has_any(f, BsdfFlags::Diffuse) &&
         !has_any(f, BsdfFlags::Glossy | BsdfFlags::Specular | BsdfFlags::Transmission);
}

}  // namespace dualight
