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
