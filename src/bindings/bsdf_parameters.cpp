// Checked construction of the glossy, conductor, thin-glass and plastic BSDFs from Mitsuba 3's
// parameters (names, defaults and meaning as its plugin documentation), bound as static
// methods of dualight._core.Bsdf.
#include "bindings/bsdf_parameters.h"

#include <pybind11/stl.h>

#include <cmath>

namespace dualight::bindings {

namespace {

std::string str(float v) { return std::to_string(v); }

float checked_range(const char* name, float v, float lo, float hi) {
  if (!(std::isfinite(v) && v >= lo && v <= hi)) {
    throw py::value_error(std::string(name) + " must be finite and in [" + str(lo) + ", " + str(hi) + "], got " + str(v));
  }
  return v;
}
Color checked_rgb(const char* name, const Rgb& c, float lo, float hi) {
  return {checked_range(name, c[0], lo, hi), checked_range(name, c[1], lo, hi), checked_range(name, c[2], lo, hi)};
}
// A relative IOR: Fresnel squares it in float32, and 1 makes the interface vanish.
float checked_eta(float eta) {
  checked_range("ior", eta, 1e-3f, 1e3f);
  if (eta == 1.f) throw py::value_error("ior must differ from 1 (an index-matched interface scatters nothing)");
  return eta;
}
// A conductor's complex IOR and reflectance scale.
void check_metal(const Rgb& eta, const Rgb& k, const Rgb& specular_reflectance) {
  checked_rgb("conductor eta", eta, 0.f, 1e3f);
  checked_rgb("conductor k", k, 0.f, 1e3f);
  checked_rgb("specular_reflectance", specular_reflectance, 0.f, 1.f);
}
Color rgb(const Rgb& c) { return {c[0], c[1], c[2]}; }

}  // namespace

Microfacet checked_microfacet(const std::string& distribution, float alpha_u, float alpha_v) {
  MicrofacetType type;
  if (distribution == "beckmann") {
    type = MicrofacetType::Beckmann;
  } else if (distribution == "ggx") {
    type = MicrofacetType::GGX;
  } else {
    throw py::value_error("distribution must be 'beckmann' or 'ggx', got '" + distribution + "'");
  }
  return make_microfacet(type, checked_range("alpha_u", alpha_u, 0.f, 1e3f), checked_range("alpha_v", alpha_v, 0.f, 1e3f));
}

Conductor checked_conductor(const Rgb& eta, const Rgb& k, const Rgb& specular_reflectance, bool two_sided) {
  check_metal(eta, k, specular_reflectance);
  return {rgb(eta), rgb(k), rgb(specular_reflectance), two_sided};
}
RoughConductor checked_rough_conductor(const Microfacet& d, const Rgb& eta, const Rgb& k,
                                       const Rgb& specular_reflectance, bool two_sided) {
  check_metal(eta, k, specular_reflectance);
  return {d, rgb(eta), rgb(k), rgb(specular_reflectance), two_sided};
}
ThinDielectric checked_thin_dielectric(float eta) { return {checked_eta(eta)}; }
RoughDielectric checked_rough_dielectric(const Microfacet& d, float eta) { return {d, checked_eta(eta)}; }
Plastic checked_plastic(const Rgb& diffuse_reflectance, const Rgb& specular_reflectance, float eta, bool nonlinear,
                        bool two_sided) {
  return {checked_rgb("diffuse_reflectance", diffuse_reflectance, 0.f, 1.f),
          checked_rgb("specular_reflectance", specular_reflectance, 0.f, 1.f), checked_eta(eta), nonlinear, two_sided};
}
RoughPlastic checked_rough_plastic(const Microfacet& d, const Rgb& diffuse_reflectance,
                                   const Rgb& specular_reflectance, float eta, bool nonlinear, bool two_sided) {
  if (d.alpha_u != d.alpha_v) throw py::value_error("roughplastic needs an isotropic distribution (alpha_u == alpha_v)");
  return make_rough_plastic(d, checked_rgb("diffuse_reflectance", diffuse_reflectance, 0.f, 1.f),
                            checked_rgb("specular_reflectance", specular_reflectance, 0.f, 1.f), checked_eta(eta),
                            nonlinear, two_sided);
}

void bind_bsdf_parameters(py::class_<BsdfObject>& cls) {
  const Rgb one{1.f, 1.f, 1.f}, zero{0.f, 0.f, 0.f}, half{0.5f, 0.5f, 0.5f};
  cls.def_static(
         "conductor",
         [](const Rgb& eta, const Rgb& k, const Rgb& s, bool two) { return BsdfObject{checked_conductor(eta, k, s, two)}; },
         py::kw_only(), py::arg("eta") = zero, py::arg("k") = one, py::arg("specular_reflectance") = one,
         py::arg("two_sided") = false,
         "Mitsuba's `conductor`: a smooth metal with complex IOR eta + i k (eta 0, k 1: a perfect mirror).")
      .def_static(
          "rough_conductor",
          [](const std::string& dist, float au, float av, const Rgb& eta, const Rgb& k, const Rgb& s, bool two) {
            return BsdfObject{checked_rough_conductor(checked_microfacet(dist, au, av), eta, k, s, two)};
          },
          py::kw_only(), py::arg("distribution") = "beckmann", py::arg("alpha_u") = 0.1f, py::arg("alpha_v") = 0.1f,
          py::arg("eta") = zero, py::arg("k") = one, py::arg("specular_reflectance") = one, py::arg("two_sided") = false,
          "Mitsuba's `roughconductor` (microfacet metal).")
      .def_static(
          "thin_dielectric", [](float eta) { return BsdfObject{checked_thin_dielectric(eta)}; }, py::kw_only(),
          py::arg("ior") = 1.5046f, "Mitsuba's `thindielectric` (a pane: reflection or straight through).")
      .def_static(
          "rough_dielectric",
          [](const std::string& dist, float au, float av, float eta) {
            return BsdfObject{checked_rough_dielectric(checked_microfacet(dist, au, av), eta)};
          },
          py::kw_only(), py::arg("distribution") = "beckmann", py::arg("alpha_u") = 0.1f, py::arg("alpha_v") = 0.1f,
          py::arg("ior") = 1.5046f, "Mitsuba's `roughdielectric` (frosted glass; ior = interior / exterior).")
      .def_static(
          "plastic",
          [](const Rgb& d, const Rgb& s, float eta, bool nl, bool two) {
            return BsdfObject{checked_plastic(d, s, eta, nl, two)};
          },
          py::kw_only(), py::arg("diffuse_reflectance") = half, py::arg("specular_reflectance") = one,
          py::arg("ior") = 1.49f, py::arg("nonlinear") = false, py::arg("two_sided") = false,
          "Mitsuba's `plastic` (diffuse base under a smooth coat).")
      .def_static(
          "rough_plastic",
          [](const std::string& dist, float alpha, const Rgb& d, const Rgb& s, float eta, bool nl, bool two) {
            return BsdfObject{checked_rough_plastic(checked_microfacet(dist, alpha, alpha), d, s, eta, nl, two)};
          },
          py::kw_only(), py::arg("distribution") = "beckmann", py::arg("alpha") = 0.1f,
          py::arg("diffuse_reflectance") = half, py::arg("specular_reflectance") = one, py::arg("ior") = 1.49f,
          py::arg("nonlinear") = false, py::arg("two_sided") = false,
          "Mitsuba's `roughplastic` (diffuse base under a rough coat; isotropic).");
}

}  // namespace dualight::bindings
