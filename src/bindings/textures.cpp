// dualight._core.Texture: bitmap and checkerboard textures, checked on construction, and their
// vectorised lookups (for tests and for radiosity's per-patch means).
#include "bindings/textures.h"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <array>
#include <cmath>

#include "bindings/numpy_util.h"
#include "film/image_io.h"

namespace dualight::bindings {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

UvTransform uv_transform(const std::array<float, 6>& m) {
  UvTransform t;
  for (int i = 0; i < 6; ++i) {
    if (!std::isfinite(m[i])) throw py::value_error("to_uv must be 6 finite numbers (a 2x3 affine matrix)");
    t.m[i] = m[i];
  }
  return t;
}

TextureObject make_bitmap(const FloatArray& texels, const std::string& wrap, const std::string& filter,
                          const std::array<float, 6>& to_uv) {
  if (texels.ndim() != 3 || (texels.shape(2) != 1 && texels.shape(2) != 3) || texels.shape(0) < 1 ||
      texels.shape(1) < 1) {
    throw py::value_error("bitmap texels must have shape (height, width, 1 or 3) with height, width >= 1");
  }
  if (static_cast<uint64_t>(texels.size()) > kMaxImageValues) throw py::value_error("bitmap is too large");
  BitmapTexture b;
  if (wrap == "repeat") b.wrap = WrapMode::Repeat;
  else if (wrap == "mirror") b.wrap = WrapMode::Mirror;
  else if (wrap == "clamp") b.wrap = WrapMode::Clamp;
  else throw py::value_error("wrap_mode must be 'repeat', 'mirror' or 'clamp', got '" + wrap + "'");
  if (filter == "bilinear") b.filter = TextureFilter::Bilinear;
  else if (filter == "nearest") b.filter = TextureFilter::Nearest;
  else throw py::value_error("filter_type must be 'bilinear' or 'nearest', got '" + filter + "'");
  b.to_uv = uv_transform(to_uv);
  auto t = std::make_shared<Texels>();
  t->height = static_cast<int>(texels.shape(0));
  t->width = static_cast<int>(texels.shape(1));
  t->channels = static_cast<int>(texels.shape(2));
  t->values.assign(texels.data(), texels.data() + texels.size());
  for (const float x : t->values) {
    if (!std::isfinite(x)) throw py::value_error("bitmap texels must be finite");
  }
  b.texels = std::move(t);
  return {b};
}

// f(texture, uv) for each row of an (N, 2) array of (u, v).
template <class F>
std::vector<float> per_uv(const TextureObject& t, const FloatArray& uv_in, int width, F f) {
  const std::vector<float> uv = rows_of(uv_in, 2, "uv");
  const size_t n = uv.size() / 2;
  std::vector<float> out(n * width);
  py::gil_scoped_release release;
  for (size_t i = 0; i < n; ++i) f(t.texture, Point2{uv[2 * i], uv[2 * i + 1]}, &out[i * width]);
  return out;
}

}  // namespace

BsdfParameter bsdf_parameter(const std::string& name) {
  if (name == "reflectance") return BsdfParameter::Reflectance;
  if (name == "diffuse_reflectance") return BsdfParameter::DiffuseReflectance;
  if (name == "specular_reflectance") return BsdfParameter::SpecularReflectance;
  if (name == "alpha") return BsdfParameter::Alpha;
  if (name == "alpha_u") return BsdfParameter::AlphaU;
  if (name == "alpha_v") return BsdfParameter::AlphaV;
  throw py::value_error("no texturable BSDF parameter '" + name + "'");
}

void bind_textures(py::module_& m) {
  py::class_<TextureObject>(m, "Texture", "A bitmap or checkerboard texture (Mitsuba 3's semantics).")
      .def_static("bitmap", &make_bitmap, py::arg("texels"), py::kw_only(), py::arg("wrap_mode") = "repeat",
                  py::arg("filter_type") = "bilinear",
                  py::arg("to_uv") = std::array<float, 6>{1.f, 0.f, 0.f, 0.f, 1.f, 0.f},
                  "Linear texels (height, width, 1 or 3), row 0 at v = 0.")
      .def_static(
          "checkerboard",
          [](const std::array<float, 3>& c0, const std::array<float, 3>& c1, const std::array<float, 6>& to_uv) {
            return TextureObject{CheckerboardTexture{{c0[0], c0[1], c0[2]}, {c1[0], c1[1], c1[2]}, uv_transform(to_uv)}};
          },
          py::arg("color0"), py::arg("color1"), py::kw_only(),
          py::arg("to_uv") = std::array<float, 6>{1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
      .def(
          "eval",
          [](const TextureObject& t, const FloatArray& uv) {
            std::vector<float> out = per_uv(t, uv, 3, [](const Texture& x, Point2 p, float* o) {
              const Color c = eval_rgb(x, p);
              o[0] = c.x, o[1] = c.y, o[2] = c.z;
            });
            const auto n = static_cast<py::ssize_t>(out.size() / 3);
            return to_numpy(std::move(out), {n, 3});
          },
          py::arg("uv"), "RGB at each row (u, v) of an (N, 2) array: (N, 3).")
      .def(
          "eval_scalar",
          [](const TextureObject& t, const FloatArray& uv) {
            std::vector<float> out =
                per_uv(t, uv, 1, [](const Texture& x, Point2 p, float* o) { o[0] = eval_scalar(x, p); });
            const auto n = static_cast<py::ssize_t>(out.size());
            return to_numpy(std::move(out), {n});
          },
          py::arg("uv"), "The value a roughness takes at each row (u, v): (N,).")
      .def_property_readonly("mean", [](const TextureObject& t) {
        const Color c = mean_rgb(t.texture);
        return std::array<float, 3>{c.x, c.y, c.z};
      });
}

}  // namespace dualight::bindings
