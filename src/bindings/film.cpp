#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings/numpy_util.h"
#include "film/image_io.h"

namespace dualight::bindings {

void bind_film(py::module_& m) {
  m.def(
      "write_image",
      [](const std::string& path, const py::array_t<float, py::array::c_style | py::array::forcecast>& pixels,
         const ImageMetadata& metadata) {
        if (pixels.ndim() != 3) throw py::value_error("pixels must be H x W x C");
        const auto h = static_cast<int>(pixels.shape(0)), w = static_cast<int>(pixels.shape(1));
        const auto c = static_cast<int>(pixels.shape(2));
        const float* data = pixels.data();
        py::gil_scoped_release release;
        write_image(path, w, h, c, data, metadata);
      },
      py::arg("path"), py::arg("pixels"), py::arg("metadata") = ImageMetadata{},
      "Writes an H x W x C float image; 8-bit formats expect values already in [0, 1].");
  m.def(
      "read_image",
      [](const std::string& path) {
        LoadedImage img;
        {
          py::gil_scoped_release release;
          img = read_image(path);
        }
        auto pixels = to_numpy(std::move(img.pixels), {img.height, img.width, img.channels});
        return py::make_tuple(pixels, img.metadata, img.low_dynamic_range);
      },
      py::arg("path"), "Reads an image: (H x W x C float32 pixels, metadata dict, is_low_dynamic_range).");
}

}  // namespace dualight::bindings
