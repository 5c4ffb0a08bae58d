// Path-space MLT (Veach): options, the renderer, and test hooks: the complete-path contribution
// and densities against BDPT's, chains of a single mutation and the mutations' densities
// (mlt_checks.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings/interruptible.h"
#include "bindings/render_result.h"
#include "pathspace/mlt.h"
#include "pathspace/mlt_checks.h"

namespace dualight::bindings {

namespace {

TransitionRatio transition_ratio_of(const std::string& name) {
  if (name == "used") return TransitionRatio::Used;
  if (name == "ignored") return TransitionRatio::Ignored;
  if (name == "inverted") return TransitionRatio::Inverted;
  throw py::value_error("transition_ratio must be 'used', 'ignored' or 'inverted'");
}

}  // namespace

void bind_mlt(py::module_& m) {
  OptionsClass<MltOptions> mlt(m, "MltOptions", "Options of path-space Metropolis light transport.");
  add_estimator_fields(mlt, "mutations_per_pixel", "Mutations per pixel; 0 = until time_limit.");
  mlt.field("bootstrap", &MltOptions::bootstrap, "BDPT samples that estimate b and start the chains.", at_least(1))
      .field("chains", &MltOptions::chains, "Markov chains.", at_least(1))
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
        return path_mlt_result_dict(std::move(run.result), camera, options, run.keyboard_interrupt);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      "Path-space MLT (Veach); returns dict(mean, variance=None, light_paths (= mutations), stats, keyboard_interrupt); "
      "stats has b, b_ci95, mutations, acceptance rates and per mutation type counts.");

  m.def(
      "check_mlt_bootstrap_paths",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options, size_t count) {
        std::vector<StrategyCheck> checks;
        {
          py::gil_scoped_release release;
          checks = check_bootstrap_paths(*scene, camera, options, count);
        }
        py::list out;
        for (const StrategyCheck& c : checks) out.append(py::make_tuple(c.s, c.t, c.bdpt, c.recomputed));
        return out;
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("count"),
      "For tests: (s, t, BDPT's unweighted luminance estimate, the same from the complete path's f*/p) for every "
      "strategy of `count` bootstrap samples.");

  m.def(
      "check_mlt_single_mutation",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options,
         const std::string& mutation, const std::string& transition_ratio) {
        check_emitters(*scene);
        const TransitionRatio ratio = transition_ratio_of(transition_ratio);
        PathMltResult run;
        {
          py::gil_scoped_release release;
          run = render_single_mutation(*scene, camera, options, mutation, ratio);
        }
        const std::vector<MutationStats> mutations = run.mutations;
        py::dict d = mlt_result_dict(std::move(run.result), camera.width(), camera.height(), options.direct_spp,
                                     false);
        py::dict stats = d["stats"];
        stats["mutation_types"] = mutation_stats_dict(mutations);
        return d;
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("mutation"),
      py::arg("transition_ratio") = "used",
      "For tests: MLT whose chains use only `mutation` (bidirectional included: a chain that is not ergodic "
      "but keeps f invariant), staying put on paths it does not suit. transition_ratio 'ignored' or 'inverted' "
      "breaks the acceptance on purpose (a negative control). Returns render_mlt's dict.");

  m.def(
      "check_mlt_perturbation_densities",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options,
         const std::string& mutation, size_t samples, size_t proposals, double film_step, double angle_step) {
        std::vector<DensityCheck> checks;
        {
          py::gil_scoped_release release;
          checks = check_perturbation_densities(*scene, camera, options, mutation, samples, proposals, film_step,
                                                angle_step);
        }
        py::list out;
        for (const DensityCheck& c : checks) {
          out.append(py::make_tuple(c.block, c.specular, c.reported, c.measured, c.cos_end));
        }
        return out;
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("mutation"), py::arg("samples"),
      py::arg("proposals"), py::arg("film_step") = 0.02, py::arg("angle_step") = 1e-3,
      "For tests: (block, specular vertices, reported density, finite-difference density, |cos| at the moved "
      "vertex) per block of each comparable perturbation proposal (mlt_checks.h).");

  m.def(
      "check_mlt_bidirectional_density",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const MltOptions& options, int vertex,
         size_t proposals, size_t region_points) {
        BidirectionalCheck c;
        {
          py::gil_scoped_release release;
          c = check_bidirectional_density(*scene, camera, options, vertex, proposals, region_points);
        }
        py::dict d;
        d["area"] = c.area;
        d["area_se"] = c.area_se;
        d["proposals"] = c.proposals;
        d["inv_t"] = c.inv_t;
        d["move"] = c.move;
        d["pdf_light"] = c.pdf_light;
        d["pdf_eye"] = c.pdf_eye;
        d["cos"] = c.cos;
        return d;
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("vertex"), py::arg("proposals"),
      py::arg("region_points") = 200000,
      "For tests: bidirectional proposals that regenerate x_vertex only, from one path (mlt_checks.h); the sum "
      "of inv_t over `proposals` estimates the region's `area`.");
}

}  // namespace dualight::bindings
