// dualight._core.Emitter: point and spot lights (lights/point_emitter.h, lights/spot_emitter.h),
// checked before they are built. Area emitters come from the meshes' emission instead.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>
#include <string>

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

Color intensity_of(const std::array<double, 3>& a) {
  for (const double x : a) {
    if (!(x >= 0.0) || !std::isfinite(x) || x > 1e30) throw py::value_error("intensity must be finite and >= 0 (at most 1e30)");
  }
  return {static_cast<float>(a[0]), static_cast<float>(a[1]), static_cast<float>(a[2])};
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
  py::class_<EmitterObject>(m, "Emitter", "An emitter without a surface (built by dualight.PointLight, SpotLight).")
      .def_static(
          "point",
          [](const std::array<double, 3>& position, const std::array<double, 3>& intensity) {
            return EmitterObject{PointEmitter{finite_vec3(position, "position"), intensity_of(intensity)}};
          },
          py::arg("position"), py::arg("intensity"), "Isotropic point light: intensity in W/sr per channel.")
      .def_static("spot", &spot, py::arg("position"), py::arg("direction"), py::arg("intensity"),
                  py::arg("cutoff_angle"), py::arg("beam_width"),
                  "Spot light (Mitsuba 3's spot): angles in degrees, intensity on the axis in W/sr.")
      .def_property_readonly("power", [](const EmitterObject& e) { return power(e.emitter); },
                             "Flux / pi (the weight of the scene's light choice).");
}

}  // namespace dualight::bindings
