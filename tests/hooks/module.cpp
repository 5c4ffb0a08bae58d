// dualight._testing: the hooks the Python tests call into the C++ core (checks that recompute
// what an estimator cached, chains with a broken acceptance as negative controls, sampler points),
// kept out of the shipped dualight._core as pbrt-v4 keeps pbrt_test apart. Built only with
// -DDUALIGHT_TESTING=ON (make install); it shares _core's types (Scene, PinholeCamera, options).
#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace dualight::bindings {
void bind_pathspace_hooks(py::module_& m);
void bind_mlt_hooks(py::module_& m);
}  // namespace dualight::bindings

PYBIND11_MODULE(_testing, m) {
  m.doc() = "dualight's test hooks (built with DUALIGHT_TESTING=ON); not part of the package's API.";
  py::module_::import("dualight._core");  // registers the types the hooks take
  dualight::bindings::bind_pathspace_hooks(m);
  dualight::bindings::bind_mlt_hooks(m);
}
