// BSDF parameters given by textures (Mitsuba 3 lets a texture stand for any of them): a material
// lists which parameter of its BSDF each texture drives, and a surface point's BSDF is the
// material's with those parameters looked up at the point's (u, v). Roughness takes the
// texture's scalar value (texture.h, eval_scalar), colours its RGB.
#pragma once
#include <cstdint>
#include <vector>

#include "materials/bsdf.h"
#include "materials/texture.h"

namespace dualight {

// Mitsuba's names: `reflectance` (diffuse), `diffuse_reflectance` and `specular_reflectance`
// (plastics; a conductor's and a mirror's colour), `alpha` (both roughnesses), `alpha_u`,
// `alpha_v`.
enum class BsdfParameter : uint8_t { Reflectance, DiffuseReflectance, SpecularReflectance, Alpha, AlphaU, AlphaV };

struct TextureSlot {
  BsdfParameter parameter;
  Texture texture;
};

// Whether b has the parameter (the scene refuses a texture for one it does not have).
bool has_parameter(const Bsdf& b, BsdfParameter p);
// b with every slot's parameter set from its texture at uv.
Bsdf textured_bsdf(const Bsdf& b, const std::vector<TextureSlot>& slots, Point2 uv);

}  // namespace dualight
