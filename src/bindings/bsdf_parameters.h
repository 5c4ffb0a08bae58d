// The BSDFs beyond Lambertian, mirror and smooth glass, built from Mitsuba 3's parameters and
// checked before anything is made: each throws py::value_error naming the parameter and the
// range the float32 core can hold.
#pragma once
#include <array>
#include <string>

#include "bindings/materials.h"
#include "bindings/numpy_util.h"

namespace dualight::bindings {

using Rgb = std::array<float, 3>;

// "beckmann" or "ggx"; alpha_u == alpha_v for an isotropic surface.
Microfacet checked_microfacet(const std::string& distribution, float alpha_u, float alpha_v);

Conductor checked_conductor(const Rgb& eta, const Rgb& k, const Rgb& specular_reflectance, bool two_sided);
RoughConductor checked_rough_conductor(const Microfacet& d, const Rgb& eta, const Rgb& k,
                                       const Rgb& specular_reflectance, bool two_sided);
ThinDielectric checked_thin_dielectric(float eta);
RoughDielectric checked_rough_dielectric(const Microfacet& d, float eta);
Plastic checked_plastic(const Rgb& diffuse_reflectance, const Rgb& specular_reflectance, float eta, bool nonlinear,
                        bool two_sided);
RoughPlastic checked_rough_plastic(const Microfacet& d, const Rgb& diffuse_reflectance,
                                   const Rgb& specular_reflectance, float eta, bool nonlinear, bool two_sided);

// Binds the constructors above as static methods of the Python class `Bsdf`.
void bind_bsdf_parameters(py::class_<BsdfObject>& cls);

}  // namespace dualight::bindings
