// Setting a BSDF's parameters from textures (textured_bsdf.h): one overload per member of the
// variant that has texturable parameters; the others have none.
#include "materials/textured_bsdf.h"

#include <algorithm>

namespace dualight {

namespace {

// The parameter's place in each member, or false where the member has no such parameter.
struct Setter {
  BsdfParameter p;
  const Texture& t;
  Point2 uv;

  Color rgb() const { return eval_rgb(t, uv); }
  float alpha() const { return std::max(eval_scalar(t, uv), kMinAlpha); }
  bool set_roughness(Microfacet& d) const {
    if (p == BsdfParameter::Alpha || p == BsdfParameter::AlphaU) d.alpha_u = alpha();
    if (p == BsdfParameter::Alpha || p == BsdfParameter::AlphaV) d.alpha_v = alpha();
    return p == BsdfParameter::Alpha || p == BsdfParameter::AlphaU || p == BsdfParameter::AlphaV;
  }
  bool set_colour(BsdfParameter which, Color& c) const {
    if (p != which) return false;
    c = rgb();
    return true;
  }

  bool operator()(Lambertian& b) const { return set_colour(BsdfParameter::Reflectance, b.albedo); }
  bool operator()(Mirror& b) const { return set_colour(BsdfParameter::SpecularReflectance, b.reflectance); }
  bool operator()(Conductor& b) const {
    return set_colour(BsdfParameter::SpecularReflectance, b.specular_reflectance);
  }
  bool operator()(RoughConductor& b) const {
    return set_colour(BsdfParameter::SpecularReflectance, b.specular_reflectance) || set_roughness(b.distribution);
  }
  bool operator()(RoughDielectric& b) const { return set_roughness(b.distribution); }
  bool operator()(Plastic& b) const {
    return set_colour(BsdfParameter::DiffuseReflectance, b.diffuse_reflectance) ||
           set_colour(BsdfParameter::SpecularReflectance, b.specular_reflectance);
  }
  // Rough plastic's roughness is a number in Mitsuba (its coat tables depend on it).
  bool operator()(RoughPlastic& b) const {
    return set_colour(BsdfParameter::DiffuseReflectance, b.diffuse_reflectance) ||
           set_colour(BsdfParameter::SpecularReflectance, b.specular_reflectance);
  }
  bool operator()(Dielectric&) const { return false; }
  bool operator()(ThinDielectric&) const { return false; }
};

}  // namespace

bool has_parameter(const Bsdf& b, BsdfParameter p) {
  Bsdf copy = b;
  const Texture probe = CheckerboardTexture{};
  return std::visit(Setter{p, probe, Point2{0.f, 0.f}}, copy);
}

Bsdf textured_bsdf(const Bsdf& b, const std::vector<TextureSlot>& slots, Point2 uv) {
  Bsdf out = b;
  for (const TextureSlot& s : slots) std::visit(Setter{s.parameter, s.texture, uv}, out);
  return out;
}

}  // namespace dualight
