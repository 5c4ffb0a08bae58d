// Materials: BSDF construction for the scene binding, and a vectorised view of single BSDFs in
// their local frame (z = the geometric normal) so Python tests can check sampling, densities and
// Fresnel against independent references.
#include "bindings/materials.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "bindings/bsdf_parameters.h"
#include "bindings/numpy_util.h"

namespace dualight::bindings {

Bsdf make_bsdf(uint32_t kind, const Color& reflectance, float ior) {
  const auto check_reflectance = [&](const char* what) {
    for (const float c : {reflectance.x, reflectance.y, reflectance.z}) {
      if (!(c >= 0.f && c <= 1.f)) {
        throw py::value_error(std::string(what) + " must be finite and in [0, 1], got " + std::to_string(c));
      }
    }
  };
  switch (static_cast<BsdfKind>(kind)) {
    case BsdfKind::Lambertian:
      check_reflectance("diffuse reflectance");
      return Lambertian{reflectance};
    case BsdfKind::Mirror:
      check_reflectance("mirror reflectance");
      return Mirror{reflectance};
    case BsdfKind::Dielectric:
      if (!(std::isfinite(ior) && ior > 0.f)) {
        throw py::value_error("dielectric ior must be finite and > 0, got " + std::to_string(ior));
      }
      return Dielectric{ior};
    default:
      break;
  }
  if (kind >= std::variant_size_v<Bsdf>) throw py::value_error("unknown BSDF kind " + std::to_string(kind));
  throw py::value_error("BSDF kind " + std::to_string(kind) +
                        " is not made from (reflectance, ior): 0 lambertian, 1 mirror and 2 dielectric are; "
                        "use the Bsdf.conductor, ... constructors for the others");
}

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

std::vector<std::string> flag_names(BsdfFlags f) {
  std::vector<std::string> names;
  for (const auto& [flag, name] : {std::pair{BsdfFlags::Diffuse, "diffuse"}, std::pair{BsdfFlags::Glossy, "glossy"},
                                   std::pair{BsdfFlags::Specular, "specular"},
                                   std::pair{BsdfFlags::Reflection, "reflection"},
                                   std::pair{BsdfFlags::Transmission, "transmission"}}) {
    if (has_any(f, flag)) names.emplace_back(name);
  }
  return names;
}

Vec3 row3(const std::vector<float>& a, size_t i) { return {a[3 * i], a[3 * i + 1], a[3 * i + 2]}; }

// Two (N, 3) direction arrays of equal length, or a py::value_error naming the mismatch.
size_t direction_pairs(const std::vector<float>& a, const std::vector<float>& b) {
  if (a.size() != b.size()) throw py::value_error("wo and wi must have the same number of rows");
  return a.size() / 3;
}

}  // namespace

void bind_materials(py::module_& m) {
  py::enum_<BsdfKind>(m, "BsdfKind", "Kinds of BSDF; the values index the arrays of Scene(kind=...).")
      .value("lambertian", BsdfKind::Lambertian)
      .value("mirror", BsdfKind::Mirror)
      .value("dielectric", BsdfKind::Dielectric)
      .value("conductor", BsdfKind::Conductor)
      .value("rough_conductor", BsdfKind::RoughConductor)
      .value("thin_dielectric", BsdfKind::ThinDielectric)
      .value("rough_dielectric", BsdfKind::RoughDielectric)
      .value("plastic", BsdfKind::Plastic)
      .value("rough_plastic", BsdfKind::RoughPlastic);

  py::enum_<TransportMode>(m, "TransportMode", "Which quantity a path carries (radiance from lights, importance from the camera).")
      .value("radiance", TransportMode::Radiance)
      .value("importance", TransportMode::Importance);

  py::class_<BsdfObject> bsdf_class(m, "Bsdf",
                   "One BSDF in its local frame (z = geometric normal, the exterior side for a dielectric); "
                   "vectorised for tests. Directions point away from the surface.");
  bsdf_class
      .def(py::init([](BsdfKind kind, const std::array<float, 3>& reflectance, float ior) {
             return BsdfObject{
                 make_bsdf(static_cast<uint32_t>(kind), {reflectance[0], reflectance[1], reflectance[2]}, ior)};
           }),
           py::arg("kind"), py::kw_only(), py::arg("reflectance") = std::array<float, 3>{1.f, 1.f, 1.f},
           py::arg("ior") = 1.5f)
      .def_property_readonly("kind", [](const BsdfObject& b) { return static_cast<BsdfKind>(b.bsdf.index()); })
      .def_property_readonly("is_delta", [](const BsdfObject& b) { return is_delta(b.bsdf); })
      .def_property_readonly(
          "is_diffuse_reflector", [](const BsdfObject& b) { return is_diffuse_reflector(flags(b.bsdf)); },
          "Only diffuse reflection: what radiosity can solve.")
      .def_property_readonly("flags", [](const BsdfObject& b) { return flag_names(flags(b.bsdf)); },
                             "What the BSDF is, as it reports itself: a subset of diffuse, glossy, "
                             "specular (Dirac lobes), reflection, transmission.")
      .def(
          "sample",
          [](const BsdfObject& b, const FloatArray& wo_in, const FloatArray& u_in, TransportMode mode) {
            const std::vector<float> wo = rows_of(wo_in, 3, "wo");
            const std::vector<float> u = rows_of(u_in, 2, "u");
            const size_t n = wo.size() / 3;
            if (u.size() / 2 != n) throw py::value_error("wo and u must have the same number of rows");
            std::vector<float> wi(3 * n, 0.f), weight(3 * n, 0.f), pdf(n, 0.f);
            std::vector<uint8_t> delta(n, 0), valid(n, 0);
            {
              py::gil_scoped_release release;
              for (size_t i = 0; i < n; ++i) {
                BsdfSample s;
                if (!sample(b.bsdf, row3(wo, i), {u[2 * i], u[2 * i + 1]}, mode, s)) continue;
                valid[i] = 1;
                delta[i] = s.delta ? 1 : 0;
                pdf[i] = s.pdf_w;
                for (int k = 0; k < 3; ++k) {
                  wi[3 * i + k] = s.wi[k];
                  weight[3 * i + k] = s.weight[k];
                }
              }
            }
            const auto N = static_cast<py::ssize_t>(n);
            py::dict d;
            d["wi"] = to_numpy(std::move(wi), {N, 3});
            d["weight"] = to_numpy(std::move(weight), {N, 3});
            d["pdf_w"] = to_numpy(std::move(pdf), {N});
            d["delta"] = to_numpy(std::move(delta), {N}).attr("astype")("bool");
            d["valid"] = to_numpy(std::move(valid), {N}).attr("astype")("bool");
            return d;
          },
          py::arg("wo"), py::arg("u"), py::arg("mode") = TransportMode::Radiance,
          "Sample wi for each row of wo (N, 3) with random numbers u (N, 2): a dict of wi (N, 3), "
          "weight = f |cos wi| / pdf (N, 3), pdf_w (N,) (the lobe's probability when delta), delta (N,) "
          "and valid (N,), False where sampling failed (the other fields are then 0).")
      .def(
          "eval_f",
          [](const BsdfObject& b, const FloatArray& wo_in, const FloatArray& wi_in, TransportMode mode) {
            const std::vector<float> wo = rows_of(wo_in, 3, "wo"), wi = rows_of(wi_in, 3, "wi");
            const size_t n = direction_pairs(wo, wi);
            std::vector<float> f(3 * n);
            for (size_t i = 0; i < n; ++i) {
              const Color c = eval_f(b.bsdf, row3(wo, i), row3(wi, i), mode);
              for (int k = 0; k < 3; ++k) f[3 * i + k] = c[k];
            }
            return to_numpy(std::move(f), {static_cast<py::ssize_t>(n), 3});
          },
          py::arg("wo"), py::arg("wi"), py::arg("mode") = TransportMode::Radiance,
          "The BSDF value f(wo, wi) (N, 3); 0 for delta BSDFs.")
      .def(
          "pdf_w",
          [](const BsdfObject& b, const FloatArray& wo_in, const FloatArray& wi_in, TransportMode mode) {
            const std::vector<float> wo = rows_of(wo_in, 3, "wo"), wi = rows_of(wi_in, 3, "wi");
            const size_t n = direction_pairs(wo, wi);
            std::vector<float> p(n);
            for (size_t i = 0; i < n; ++i) p[i] = pdf_w(b.bsdf, row3(wo, i), row3(wi, i), mode);
            return to_numpy(std::move(p), {static_cast<py::ssize_t>(n)});
          },
          py::arg("wo"), py::arg("wi"), py::arg("mode") = TransportMode::Radiance,
          "Solid-angle density (N,) of sample() producing wi given wo; 0 for delta BSDFs.");
  bind_bsdf_parameters(bsdf_class);

  m.def(
      "fresnel_dielectric",
      [](const FloatArray& cos_i, float eta) {
        if (cos_i.ndim() != 1) throw py::value_error("cos_i must be one-dimensional");
        const auto n = static_cast<size_t>(cos_i.size());
        std::vector<float> R(n), cos_t(n), eta_ratio(n);
        for (size_t i = 0; i < n; ++i) {
          const Fresnel F = fresnel_dielectric(cos_i.data()[i], eta);
          R[i] = F.R;
          cos_t[i] = F.cos_t;
          eta_ratio[i] = F.eta_ratio;
        }
        const auto N = static_cast<py::ssize_t>(n);
        return py::make_tuple(to_numpy(std::move(R), {N}), to_numpy(std::move(cos_t), {N}),
                              to_numpy(std::move(eta_ratio), {N}));
      },
      py::arg("cos_i"), py::arg("eta"),
      "Unpolarised Fresnel reflectance of a smooth interface with eta = interior / exterior IOR; cos_i < 0 "
      "arrives from the interior. Returns (R, |cos_t|, eta_ratio = IOR of the refracted side / incident side).");
}

}  // namespace dualight::bindings
