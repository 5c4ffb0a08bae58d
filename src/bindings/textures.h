// Textures as Python sees them (dualight._core.Texture), shared by the texture binding and the
// scene binding (which takes them per material).
#pragma once
#include <string>

#include "materials/textured_bsdf.h"

namespace dualight::bindings {

struct TextureObject {
  Texture texture;
};

// A BSDF parameter by Mitsuba's name (reflectance, diffuse_reflectance, specular_reflectance,
// alpha, alpha_u, alpha_v); py::value_error for any other.
BsdfParameter bsdf_parameter(const std::string& name);

}  // namespace dualight::bindings
