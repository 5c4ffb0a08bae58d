// dualight._core: the compiled core. Each area binds itself in its own file.
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace dualight::bindings {
void bind_geometry(py::module_& m);
void bind_materials(py::module_& m);
void bind_textures(py::module_& m);
void bind_emitters(py::module_& m);
void bind_film(py::module_& m);
void bind_pathspace(py::module_& m);
void bind_mlt(py::module_& m);
void bind_chain_split(py::module_& m);
void bind_radiosity(py::module_& m);
void bind_guiding(py::module_& m);
}  // namespace dualight::bindings

PYBIND11_MODULE(_core, m) {
  m.doc() = "dualight's compiled core; use the `dualight` package instead of this module.";
  dualight::bindings::bind_geometry(m);
  dualight::bindings::bind_materials(m);
  dualight::bindings::bind_textures(m);
  dualight::bindings::bind_emitters(m);
  dualight::bindings::bind_film(m);
  dualight::bindings::bind_pathspace(m);
  dualight::bindings::bind_mlt(m);
  dualight::bindings::bind_chain_split(m);
  dualight::bindings::bind_radiosity(m);
  dualight::bindings::bind_guiding(m);
}
