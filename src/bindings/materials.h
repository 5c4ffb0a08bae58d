// BSDFs built from the Python description's arrays, shared by the scene binding (one BSDF per
// mesh) and the BSDF test binding.
#pragma once
#include <cstdint>
#include <type_traits>
#include <variant>

#include "materials/bsdf.h"

namespace dualight::bindings {

// A BSDF's kind as Python passes it; the value is the alternative's index in `Bsdf`.
enum class BsdfKind : uint32_t {
  Lambertian = 0,
  Mirror = 1,
  Dielectric = 2,
  Conductor = 3,
  RoughConductor = 4,
  ThinDielectric = 5,
  RoughDielectric = 6,
  Plastic = 7,
  RoughPlastic = 8,
};
static_assert(std::is_same_v<std::variant_alternative_t<0, Bsdf>, Lambertian> &&
                  std::is_same_v<std::variant_alternative_t<1, Bsdf>, Mirror> &&
                  std::is_same_v<std::variant_alternative_t<2, Bsdf>, Dielectric> &&
                  std::is_same_v<std::variant_alternative_t<8, Bsdf>, RoughPlastic> &&
                  std::variant_size_v<Bsdf> == 9,
              "BsdfKind values must follow the order of Bsdf's alternatives");

// `reflectance` is the Lambertian albedo or the mirror's reflectance (ignored by a dielectric),
// `ior` the dielectric's interior IOR (ignored by the others). Throws py::value_error naming
// the problem: an unknown kind, a reflectance outside [0, 1], an IOR that is not finite and > 0.
Bsdf make_bsdf(uint32_t kind, const Color& reflectance, float ior);

// The bound class `Bsdf` (pybind11/stl.h converts std::variant by value, so it wraps the
// variant): one BSDF made with its own keywords, which the scene binding also takes as a list,
// so a BSDF's parameters are bound in one place.
struct BsdfObject {
  Bsdf bsdf;
};

}  // namespace dualight::bindings
