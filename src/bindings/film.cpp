#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/typing.h>

#include "bindings/numpy_util.h"
#include "bindings/render_result.h"
#include "film/film.h"
#include "film/image_io.h"

namespace dualight::bindings {

namespace {

template <class T>
std::vector<T> flat_of(const py::handle& value, size_t size, const char* name) {
  const auto a = py::array_t<T, py::array::c_style | py::array::forcecast>::ensure(value);
  if (!a || static_cast<size_t>(a.size()) != size) {
    throw py::value_error(std::string("accumulators: ") + name + " must have " + std::to_string(size) +
                          " elements");
  }
  return std::vector<T>(a.data(), a.data() + a.size());
}

// A Python str of `text`, with bytes that are not UTF-8 replaced by U+FFFD.
py::str utf8_or_replaced(const std::string& text) {
  PyObject* decoded = PyUnicode_DecodeUTF8(text.data(), static_cast<Py_ssize_t>(text.size()), "replace");
  if (decoded == nullptr) throw py::error_already_set();
  return py::reinterpret_steal<py::str>(decoded);
}

}  // namespace

void bind_film(py::module_& m) {
  m.attr("BLOCK_SPP") = kBlockSpp;
  py::class_<Film>(m, "Film",
                   "A film's totals, to merge the tasks of a split render: add each task's accumulators "
                   "(render_*(..., accumulators=True)) in block order, then read mean() and variance(), "
                   "computed as a single render computes them.")
      .def(py::init<int, int>(), py::arg("width"), py::arg("height"))
      .def(
          "add_accumulators",
          [](Film& film, const py::dict& d) {
            const size_t n = film.pixel_count();
            FilmAccumulators a;
            a.sum = flat_of<double>(d["sum"], 3 * n, "sum");
            a.sum_sq = flat_of<double>(d["sum_sq"], 3 * n, "sum_sq");
            a.count = flat_of<uint32_t>(d["count"], n, "count");
            if (!d["splat_sum"].is_none()) {
              a.splat_sum = flat_of<double>(d["splat_sum"], 3 * n, "splat_sum");
              a.splat_sum_sq = flat_of<double>(d["splat_sum_sq"], 3 * n, "splat_sum_sq");
            }
            a.light_paths = d["light_paths"].cast<uint64_t>();
            film.add_accumulators(a);
          },
          py::arg("accumulators"))
      .def("accumulators", [](const Film& film) { return accumulators_dict(film); })
      .def("mean", [](const Film& film) { return to_numpy(film.mean(), {film.height(), film.width(), 3}); })
      .def("variance",
           [](const Film& film) { return to_numpy(film.variance_of_mean(), {film.height(), film.width(), 3}); })
      .def("counts", [](const Film& film) { return to_numpy(film.sample_counts(), {film.height(), film.width()}); })
      .def_property_readonly("light_paths", &Film::light_paths);
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
        // Attributes written by other programs need not be UTF-8: undecodable bytes become
        // U+FFFD instead of a UnicodeDecodeError that names no file.
        py::typing::Dict<py::str, py::str> metadata;
        for (const auto& [key, value] : img.metadata) metadata[utf8_or_replaced(key)] = utf8_or_replaced(value);
        return py::make_tuple(pixels, metadata, img.low_dynamic_range);
      },
      py::arg("path"), "Reads an image: (H x W x C float32 pixels, metadata dict, is_low_dynamic_range).");
}

}  // namespace dualight::bindings
