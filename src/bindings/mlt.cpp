// Path-space MLT (Veach): options and the renderer (its test hooks: tests/hooks/bind_mlt.cpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings/interruptible.h"
#include "bindings/render_result.h"
#include "pathspace/mlt.h"

namespace dualight::bindings {

void bind_mlt(py::module_& m) {
  py::class_<MltOptions>(m, "MltOptions", "Options of path-space Metropolis light transport (keywords only).")
      .def_readwrite("skip_unneeded", &MltOptions::skip_unneeded,
                     "Skip work the scene makes pointless (default True); False does it all.")
      .def(py::init([](uint32_t mutations_per_pixel, int max_depth, int rr_depth, uint64_t seed, int threads,
                       double time_limit, uint32_t bootstrap, uint32_t chains, MisHeuristic heuristic,
                       uint32_t direct_spp, float bidirectional, float lens_subpath, float lens_perturbation,
                       float caustic_perturbation, float multi_chain_perturbation, float lens_radius_min,
                       float lens_radius_max, float angle_min, float angle_max, const std::string& importance) {
             check_common(mutations_per_pixel, max_depth, rr_depth, threads, time_limit);
             if (bootstrap < 1) throw py::value_error("bootstrap must be >= 1");
             if (chains < 1) throw py::value_error("chains must be >= 1");
             for (const float w : {bidirectional, lens_subpath, lens_perturbation, caustic_perturbation,
                                   multi_chain_perturbation}) {
               if (!(w >= 0.f && std::isfinite(w))) throw py::value_error("mutation weights must be finite and >= 0");
             }
             if (!(bidirectional > 0.f)) {
               throw py::value_error("bidirectional must be > 0: the other mutations alone do not reach every path");
             }
             if (!(lens_radius_min > 0.f) || !(lens_radius_max >= 0.f) ||
                 (lens_radius_max > 0.f && lens_radius_max <= lens_radius_min)) {
               throw py::value_error("need 0 < lens_radius_min < lens_radius_max (pixels; lens_radius_max 0 = auto)");
             }
             if (!(angle_min > 0.f && angle_max > angle_min && angle_max < 3.14159f)) {
               throw py::value_error("need 0 < angle_min < angle_max < pi (radians)");
             }
             if (importance != "luminance" && importance != "flattened") {
               throw py::value_error("importance must be 'luminance' or 'flattened', not '" + importance + "'");
             }
             MltOptions o;
             o.importance = importance == "flattened" ? MltImportance::Flattened : MltImportance::Luminance;
             static_cast<EstimatorOptions&>(o) = {mutations_per_pixel, max_depth, rr_depth, seed, threads,
                                                  time_limit, SamplerType::Independent};
             o.bootstrap = bootstrap;
             o.chains = chains;
             o.heuristic = heuristic;
             o.direct_spp = direct_spp;
             o.bidirectional = bidirectional;
             o.lens_subpath = lens_subpath;
             o.lens_perturbation = lens_perturbation;
             o.caustic_perturbation = caustic_perturbation;
             o.multi_chain_perturbation = multi_chain_perturbation;
             o.lens_radius_min = lens_radius_min;
             o.lens_radius_max = lens_radius_max;
             o.angle_min = angle_min;
             o.angle_max = angle_max;
             return o;
           }),
           py::kw_only(), py::arg("mutations_per_pixel") = 64, py::arg("max_depth") = -1, py::arg("rr_depth") = 5,
           py::arg("seed") = 0, py::arg("threads") = 0, py::arg("time_limit") = 0.0, py::arg("bootstrap") = 100000,
           py::arg("chains") = 256, py::arg("heuristic") = MisHeuristic::Power, py::arg("direct_spp") = 128,
           py::arg("bidirectional") = 1.f, py::arg("lens_subpath") = 0.25f, py::arg("lens_perturbation") = 1.f,
           py::arg("caustic_perturbation") = 1.f, py::arg("multi_chain_perturbation") = 1.f,
           py::arg("lens_radius_min") = 0.1f, py::arg("lens_radius_max") = 0.f, py::arg("angle_min") = 1e-4f,
           py::arg("angle_max") = 0.1f, py::arg("importance") = "luminance");

  m.def(
      "render_mlt",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options,
         const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_mlt(*scene, camera, options, control); }, control,
                                     progress);
        return path_mlt_result_dict(std::move(run.result), camera, options, run.keyboard_interrupt);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      "Path-space MLT (Veach); returns dict(mean, variance=None, light_paths (= mutations), stats, keyboard_interrupt); "
      "stats has b, b_ci95, mutations, acceptance rates and per mutation type counts.");
}

}  // namespace dualight::bindings
