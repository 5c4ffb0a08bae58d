// Path-space MLT (Veach): options and the renderer (its test hooks: tests/hooks/bind_mlt.cpp).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings/interruptible.h"
#include "bindings/render_result.h"
#include "pathspace/mlt.h"

namespace dualight::bindings {

void bind_mlt(py::module_& m) {
  OptionsClass<MltOptions> mlt(m, "MltOptions", "Options of path-space Metropolis light transport.");
  add_estimator_fields(mlt, "mutations_per_pixel", "Mutations per pixel; 0 = until time_limit.");
  mlt.field("bootstrap", &MltOptions::bootstrap, "BDPT samples that estimate b and start the chains.", bootstrap_range())
      .field("chains", &MltOptions::chains, "Markov chains.", chain_range())
      .field("heuristic", &MltOptions::heuristic, "MIS heuristic of the bootstrap samples and the direct light.")
      .field("direct_spp", &MltOptions::direct_spp,
             "BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.")
      .field("bidirectional", &MltOptions::bidirectional, "Selection weight of the bidirectional mutation.",
             above(0, "(the other mutations alone do not reach every path)"))
      .field("lens_subpath", &MltOptions::lens_subpath, "Selection weight; 0 disables it.", at_least(0))
      .field("lens_perturbation", &MltOptions::lens_perturbation, "Selection weight; 0 disables it.", at_least(0))
      .field("caustic_perturbation", &MltOptions::caustic_perturbation, "Selection weight; 0 disables it.",
             at_least(0))
      .field("multi_chain_perturbation", &MltOptions::multi_chain_perturbation, "Selection weight; 0 disables it.",
             at_least(0))
      .field("lens_radius_min", &MltOptions::lens_radius_min,
             "Smallest film offset of the lens and multi-chain perturbations, in pixels.", above(0))
      .field("lens_radius_max", &MltOptions::lens_radius_max,
             "Largest film offset, in pixels; 0 = a tenth of the film's width.", at_least(0))
      .field("angle_min", &MltOptions::angle_min,
             "Smallest angular offset of the caustic and multi-chain perturbations, in radians.", above(0))
      .field("angle_max", &MltOptions::angle_max, "Largest angular offset, in radians.", strictly_within(0, 3.14159))
      .choice("importance", &MltOptions::importance,
              "The chains' target: image luminance (Veach), or luminance over the square root of a smoothed "
              "pilot estimate of the pixel's brightness (mlt_importance.h).",
              Names<MltImportance>{{"luminance", MltImportance::Luminance}, {"flattened", MltImportance::Flattened}})
      .bind();

  m.def(
      "render_mlt",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options,
         const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_mlt(*scene, camera, options, control); }, control,
                                     progress);
        return finished(run, path_mlt_result_dict(std::move(run.result), camera, options, run.keyboard_interrupt));
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      "Path-space MLT (Veach); returns dict(mean, variance=None, light_paths (= mutations), stats, keyboard_interrupt); "
      "stats has b, b_ci95, mutations, acceptance rates and per mutation type counts.");
}

}  // namespace dualight::bindings
