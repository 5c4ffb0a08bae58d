// dualight._core.Emitter: point, spot and directional lights and constant and image-based
// environments (lights/*_emitter.h), checked before they are built. Area emitters come from the
// meshes' emission instead.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "bindings/emitters.h"

namespace py = pybind11;

namespace dualight::bindings {

namespace {

Vec3 finite_vec3(const std::array<double, 3>& a, const char* name) {
  for (const double x : a) {
    if (!std::isfinite(x) || std::abs(x) > 1e30) throw py::value_error(std::string(name) + " must be finite (|x| <= 1e30)");
  }
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}

Color rgb_of(const std::array<double, 3>& a, const char* name) {
  for (const double x : a) {
    if (!(x >= 0.0) || !std::isfinite(x) || x > 1e30) {
      throw py::value_error(std::string(name) + " must be finite and >= 0 (at most 1e30)");
    }
  }
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
}
Color intensity_of(const std::array<double, 3>& a) { return rgb_of(a, "intensity"); }

Vec3 nonzero_direction(const std::array<double, 3>& a) {
  const Vec3 d = finite_vec3(a, "direction");
  if (!(length(d) > 0.f) || !std::isfinite(length(d))) throw py::value_error("direction must be non-zero");
  return d;
}

// The map's frame from a 3 x 3 rotation (row-major): its columns are the map's axes in the world.
Frame rotation_frame(const std::array<double, 9>& m) {
  const Vec3 s(static_cast<float>(m[0]), static_cast<float>(m[3]), static_cast<float>(m[6]));
  const Vec3 t(static_cast<float>(m[1]), static_cast<float>(m[4]), static_cast<float>(m[7]));
  const Vec3 n(static_cast<float>(m[2]), static_cast<float>(m[5]), static_cast<float>(m[8]));
  const bool unit = std::abs(dot(s, s) - 1.f) < 1e-4f && std::abs(dot(t, t) - 1.f) < 1e-4f && std::abs(dot(n, n) - 1.f) < 1e-4f;
  const bool orthogonal = std::abs(dot(s, t)) < 1e-4f && std::abs(dot(s, n)) < 1e-4f && std::abs(dot(t, n)) < 1e-4f;
  if (!unit || !orthogonal || !(dot(cross(s, t), n) > 0.f)) {
    throw py::value_error("to_world must be a rotation (orthonormal, determinant 1)");
  }
  return {s, t, n};
}

EmitterObject envmap(const py::array_t<float, py::array::c_style | py::array::forcecast>& rgb, double scale,
                     const std::array<double, 9>& to_world) {
  if (rgb.ndim() != 3 || rgb.shape(2) != 3 || rgb.shape(0) < 1 || rgb.shape(1) < 1) {
    throw py::value_error("environment map data must have shape (height, width, 3)");
  }
  if (rgb.shape(0) > 65536 || rgb.shape(1) > 65536) throw py::value_error("environment map is larger than 65536 pixels");
  if (!(scale >= 0.0) || !std::isfinite(scale) || scale > 1e30) {
    throw py::value_error("scale must be finite and >= 0 (at most 1e30)");
  }
  const Frame frame = rotation_frame(to_world);
  const std::vector<float> values(rgb.data(), rgb.data() + rgb.size());
  try {
    auto map = std::make_shared<const EnvironmentMap>(static_cast<uint32_t>(rgb.shape(1)),
                                                      static_cast<uint32_t>(rgb.shape(0)), values,
                                                      static_cast<float>(scale), frame);
    return {EnvmapEmitter{std::move(map), {}}};
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
}

EmitterObject spot(const std::array<double, 3>& position, const std::array<double, 3>& direction,
                   const std::array<double, 3>& intensity, double cutoff_angle, double beam_width) {
  const Vec3 p = finite_vec3(position, "position");
  const Vec3 axis = finite_vec3(direction, "direction");
  if (!(length(axis) > 0.f)) throw py::value_error("direction must be non-zero");
  if (!(cutoff_angle > 0.0 && cutoff_angle <= 180.0)) throw py::value_error("cutoff_angle must lie in (0, 180] degrees");
  if (!(beam_width >= 0.0 && beam_width <= cutoff_angle)) {
    throw py::value_error("beam_width must lie in [0, cutoff_angle] degrees");
  }
  constexpr double kRadians = 3.14159265358979323846 / 180.0;
  return {make_spot(p, axis, intensity_of(intensity), static_cast<float>(cutoff_angle * kRadians),
                    static_cast<float>(beam_width * kRadians))};
}

}  // namespace

void bind_emitters(py::module_& m) {
  py::class_<EmitterObject>(m, "Emitter", "An emitter without a surface (built by dualight.PointLight, SpotLight, DirectionalLight, ConstantEnvironment, EnvironmentMap).")
      .def_static(
          "point",
          [](const std::array<double, 3>& position, const std::array<double, 3>& intensity) {
            return EmitterObject{PointEmitter{finite_vec3(position, "position"), intensity_of(intensity)}};
          },
          py::arg("position"), py::arg("intensity"), "Isotropic point light: intensity in W/sr per channel.")
      .def_static(
          "directional",
          [](const std::array<double, 3>& direction, const std::array<double, 3>& irradiance) {
            return EmitterObject{make_directional(nonzero_direction(direction), rgb_of(irradiance, "irradiance"))};
          },
          py::arg("direction"), py::arg("irradiance"),
          "Directional light: irradiance in W/m^2 per channel, travelling along direction.")
      .def_static(
          "constant",
          [](const std::array<double, 3>& radiance) { return EmitterObject{ConstantEmitter{rgb_of(radiance, "radiance"), {}}}; },
          py::arg("radiance"), "Constant environment: radiance from every direction.")
      .def_static("envmap", &envmap, py::arg("rgb"), py::arg("scale"), py::arg("to_world"),
                  "Latitude-longitude environment (Mitsuba 3's envmap conventions): rgb (height, width, 3) "
                  "linear radiance, scale, to_world a 3 x 3 rotation (row-major).")
      .def_static("spot", &spot, py::arg("position"), py::arg("direction"), py::arg("intensity"),
                  py::arg("cutoff_angle"), py::arg("beam_width"),
                  "Spot light (Mitsuba 3's spot): angles in degrees, intensity on the axis in W/sr.")
      .def_property_readonly("power", [](const EmitterObject& e) { return power(e.emitter); },
                             "Flux / pi (the weight of the scene's light choice; for emitters at infinity, "
                             "over a unit bounding sphere until a scene holds them).");
}

}  // namespace dualight::bindings
