// Moving C++ buffers into numpy arrays without copying, and reading numpy arrays checked.
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace dualight::bindings {

namespace py = pybind11;

// The array takes ownership of the vector's buffer through a capsule: no copy.
template <class T>
py::array_t<T> to_numpy(std::vector<T>&& data, std::vector<py::ssize_t> shape) {
  auto owner = std::make_unique<std::vector<T>>(std::move(data));
  T* ptr = owner->data();
  py::capsule capsule(owner.get(), [](void* p) { delete static_cast<std::vector<T>*>(p); });
  owner.release();  // now owned by the capsule
  return py::array_t<T>(shape, ptr, capsule);
}

// Copies an (N, cols) array into a flat vector, with a clear error naming the argument.
template <class T>
std::vector<T> rows_of(const py::array_t<T, py::array::c_style | py::array::forcecast>& a, int cols,
                       const char* name) {
  if (a.ndim() != 2 || a.shape(1) != cols) {
    throw py::value_error(std::string(name) + " must have shape (N, " + std::to_string(cols) + ")");
  }
  return std::vector<T>(a.data(), a.data() + a.size());
}

}  // namespace dualight::bindings
