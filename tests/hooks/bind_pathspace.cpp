// dualight._testing's path and sampler hooks (moved from src/bindings/pathspace.cpp): verify()
// over random camera and light subpaths, and the points a sampler gives one pixel.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "bindings/numpy_util.h"
#include "core/sampler.h"
#include "geometry/scene.h"
#include "pathspace/path.h"
#include "pathspace/subpath.h"

namespace dualight::bindings {

void bind_pathspace_hooks(py::module_& m) {
  m.def(
      "verify_random_subpaths",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, uint32_t count, int max_depth,
         uint64_t seed) {
        PathCheck worst;
        TraceCounters rays;
        uint64_t vertices = 0, off = 0;
        Path path;
        const WalkLimits limits{max_depth, 1 << 30};  // no Russian roulette: beta is recomputable
        for (uint32_t i = 0; i < count; ++i) {
          IndependentSampler sampler(seed, 0, i);
          const bool from_camera = (i & 1u) == 0;
          if (from_camera) {
            const Point2 u = sampler.next_2d();
            camera_subpath(*scene, camera, u.u * camera.width(), u.v * camera.height(), sampler, limits, path,
                           rays);
          } else {
            light_subpath(*scene, sampler, limits, path, rays);
          }
          const PathCheck c = verify(camera, path, from_camera);
          worst.pdf_fwd = std::max(worst.pdf_fwd, c.pdf_fwd);
          worst.pdf_rev = std::max(worst.pdf_rev, c.pdf_rev);
          worst.beta = std::max(worst.beta, c.beta);
          vertices += c.vertices;
          off += c.off;
        }
        py::dict d;
        d["pdf_fwd"] = worst.pdf_fwd;
        d["pdf_rev"] = worst.pdf_rev;
        d["beta"] = worst.beta;
        d["vertices"] = vertices;
        d["off"] = off;
        return d;
      },
      py::arg("scene"), py::arg("camera"), py::arg("count"), py::arg("max_depth") = 8, py::arg("seed") = 0,
      "Builds `count` camera and light subpaths and recomputes their cached densities and throughputs "
      "(verify()); returns the largest relative differences.");

  m.def(
      "sampler_points",
      [](SamplerType type, uint64_t seed, uint64_t pixel, uint32_t count, uint32_t dimensions_2d) {
        std::vector<float> out;
        out.reserve(static_cast<size_t>(count) * dimensions_2d * 2);
        for (uint32_t i = 0; i < count; ++i) {
          IndependentSampler independent(seed, pixel, i);
          SobolSampler sobol(seed, pixel, i);
          for (uint32_t d = 0; d < dimensions_2d; ++d) {
            const Point2 p = type == SamplerType::Sobol ? sobol.next_2d() : independent.next_2d();
            out.push_back(p.u);
            out.push_back(p.v);
          }
        }
        return to_numpy(std::move(out), {static_cast<py::ssize_t>(count), dimensions_2d, 2});
      },
      py::arg("sampler"), py::arg("seed"), py::arg("pixel"), py::arg("count"), py::arg("dimensions_2d"),
      "The 2D samples a sampler gives one pixel: count x dimensions_2d x 2 (for tests and plots).");
}

}  // namespace dualight::bindings
