// dualight._testing's path-space MLT hooks (moved from src/bindings/mlt.cpp): the bootstrap's
// complete-path contribution and densities against BDPT's (bootstrap_checks.h), chains of a single
// mutation with the correct or a broken acceptance, and the mutations' densities (mlt_checks.h).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "bindings/render_result.h"
#include "hooks/bootstrap_checks.h"
#include "hooks/mlt_checks.h"

namespace dualight::bindings {

namespace {

TransitionRatio transition_ratio_of(const std::string& name) {
  if (name == "used") return TransitionRatio::Used;
  if (name == "ignored") return TransitionRatio::Ignored;
  if (name == "inverted") return TransitionRatio::Inverted;
  throw py::value_error("transition_ratio must be 'used', 'ignored' or 'inverted'");
}

}  // namespace

void bind_mlt_hooks(py::module_& m) {
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
