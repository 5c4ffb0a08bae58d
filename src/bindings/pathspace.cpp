#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings/interruptible.h"
#include "bindings/render_result.h"
#include "bindings/numpy_util.h"
#include "core/sampler.h"
#include "pathspace/bdpt.h"
#include "pathspace/light_tracer.h"
#include "pathspace/path_tracer.h"
#include "pathspace/pssmlt.h"
#include "pathspace/ray_benchmark.h"

namespace dualight::bindings {

void bind_pathspace(py::module_& m) {
  py::enum_<SamplerType>(m, "SamplerType")
      .value("independent", SamplerType::Independent)
      .value("sobol", SamplerType::Sobol);

  py::class_<PathTracerOptions>(m, "PathTracerOptions", "Options of the path tracer (keywords only).")
      .def_readwrite("first_sample", &PathTracerOptions::first_sample,
                     "First sample index rendered (one task of a split render; see Film).")
      .def_readwrite("skip_unneeded", &PathTracerOptions::skip_unneeded,
                     "Skip work the scene makes pointless (default True); False does it all.")
      .def(py::init([](uint32_t spp, int max_depth, int rr_depth, uint64_t seed, int threads, double time_limit,
                       SamplerType sampler) {
             check_common(spp, max_depth, rr_depth, threads, time_limit);
             return PathTracerOptions{{spp, max_depth, rr_depth, seed, threads, time_limit, sampler}};
           }),
           py::kw_only(), py::arg("spp") = 64, py::arg("max_depth") = -1, py::arg("rr_depth") = 5,
           py::arg("seed") = 0, py::arg("threads") = 0, py::arg("time_limit") = 0.0,
           py::arg("sampler") = SamplerType::Independent)
      .def_readonly("sampler", &PathTracerOptions::sampler)
      .def_readonly("spp", &PathTracerOptions::spp)
      .def_readonly("max_depth", &PathTracerOptions::max_depth)
      .def_readonly("rr_depth", &PathTracerOptions::rr_depth)
      .def_readonly("seed", &PathTracerOptions::seed)
      .def_readonly("threads", &PathTracerOptions::threads)
      .def_readonly("time_limit", &PathTracerOptions::time_limit);

  m.def(
      "render_path",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const PathTracerOptions& options,
         const py::object& progress, bool accumulators) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_path(*scene, camera, options, control); }, control,
                                     progress);
        return result_dict(std::move(run.result), run.keyboard_interrupt, accumulators);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("accumulators") = false,
      "Path-traces the scene; returns dict(mean, variance, counts, stats, keyboard_interrupt). "
      "progress(done, total) is called about every 100 ms.");

  py::enum_<MisHeuristic>(m, "MisHeuristic")
      .value("power", MisHeuristic::Power)
      .value("balance", MisHeuristic::Balance);

  py::class_<LightTracerOptions>(m, "LightTracerOptions", "Options of the light tracer (keywords only).")
      .def_readwrite("first_sample", &LightTracerOptions::first_sample,
                     "First sample index rendered (one task of a split render; see Film).")
      .def_readwrite("skip_unneeded", &LightTracerOptions::skip_unneeded,
                     "Skip work the scene makes pointless (default True); False does it all.")
      .def(py::init([](uint32_t spp, int max_depth, int rr_depth, uint64_t seed, int threads, double time_limit,
                       SamplerType sampler) {
             check_common(spp, max_depth, rr_depth, threads, time_limit);
             return LightTracerOptions{{spp, max_depth, rr_depth, seed, threads, time_limit, sampler}};
           }),
           py::kw_only(), py::arg("spp") = 64, py::arg("max_depth") = -1, py::arg("rr_depth") = 5,
           py::arg("seed") = 0, py::arg("threads") = 0, py::arg("time_limit") = 0.0,
           py::arg("sampler") = SamplerType::Independent);

  py::class_<BdptOptions>(m, "BdptOptions", "Options of bidirectional path tracing (keywords only).")
      .def_readwrite("first_sample", &BdptOptions::first_sample,
                     "First sample index rendered (one task of a split render; see Film).")
      .def_readwrite("skip_unneeded", &BdptOptions::skip_unneeded,
                     "Skip work the scene makes pointless (default True); False does it all.")
      .def(py::init([](uint32_t spp, int max_depth, int rr_depth, uint64_t seed, int threads, double time_limit,
                       SamplerType sampler, MisHeuristic heuristic, bool strategy_images) {
             check_common(spp, max_depth, rr_depth, threads, time_limit);
             if (strategy_images && max_depth < 0) {
               throw py::value_error("strategy_images needs a bounded max_depth (>= 1)");
             }
             return BdptOptions{{spp, max_depth, rr_depth, seed, threads, time_limit, sampler}, heuristic,
                                strategy_images};
           }),
           py::kw_only(), py::arg("spp") = 64, py::arg("max_depth") = -1, py::arg("rr_depth") = 5,
           py::arg("seed") = 0, py::arg("threads") = 0, py::arg("time_limit") = 0.0,
           py::arg("sampler") = SamplerType::Independent, py::arg("heuristic") = MisHeuristic::Power,
           py::arg("strategy_images") = false);

  m.def(
      "render_light",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const LightTracerOptions& options,
         const py::object& progress, bool accumulators) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_light(*scene, camera, options, control); }, control,
                                     progress);
        return result_dict(std::move(run.result), run.keyboard_interrupt, accumulators);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("accumulators") = false,
      "Light-traces the scene (spp x pixels particles); returns dict(mean, variance, counts, light_paths, "
      "stats, keyboard_interrupt).");

  m.def(
      "render_bdpt",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const BdptOptions& options,
         const py::object& progress, bool accumulators) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_bdpt(*scene, camera, options, control); }, control,
                                     progress);
        const Film& film = run.result.film;
        py::dict strategies;
        if (options.strategy_images) {
          const auto pairs = bdpt_strategies(options.max_depth);
          for (size_t layer = 0; layer < pairs.size(); ++layer) {
            strategies[py::make_tuple(pairs[layer].first, pairs[layer].second)] =
                to_numpy(film.layer_mean(layer), {film.height(), film.width(), 3});
          }
        }
        py::dict d = result_dict(std::move(run.result), run.keyboard_interrupt, accumulators);
        d["strategies"] = strategies;
        return d;
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("accumulators") = false,
      "Bidirectional path tracing; returns dict(mean, variance, counts, light_paths, stats, strategies, "
      "keyboard_interrupt); strategies maps (s, t) to MIS-weighted images when asked for.");

  py::class_<PssmltOptions>(m, "PssmltOptions", "Options of primary-sample-space MLT (keywords only).")
      .def_readwrite("skip_unneeded", &PssmltOptions::skip_unneeded,
                     "Skip work the scene makes pointless (default True); False does it all.")
      .def(py::init([](uint32_t mutations_per_pixel, int max_depth, int rr_depth, uint64_t seed, int threads,
                       double time_limit, uint32_t bootstrap, uint32_t chains, float sigma,
                       float large_step_probability, bool large_step_mis, MisHeuristic heuristic,
                       uint32_t direct_spp, bool multiplexed) {
             check_common(mutations_per_pixel, max_depth, rr_depth, threads, time_limit);
             if (bootstrap < 1) throw py::value_error("bootstrap must be >= 1");
             if (chains < 1) throw py::value_error("chains must be >= 1");
             if (!(sigma > 0.f && sigma < 1.f)) throw py::value_error("sigma must be in (0, 1)");
             if (!(large_step_probability >= 0.f && large_step_probability <= 1.f)) {
               throw py::value_error("large_step_probability must be in [0, 1]");
             }
             if (multiplexed && max_depth < 1) {
               throw py::value_error("multiplexed MLT needs a bounded max_depth >= 1 (chains per path length)");
             }
             PssmltOptions o;
             static_cast<EstimatorOptions&>(o) = {mutations_per_pixel, max_depth, rr_depth, seed, threads,
                                                  time_limit, SamplerType::Independent};
             o.bootstrap = bootstrap;
             o.chains = chains;
             o.sigma = sigma;
             o.large_step_probability = large_step_probability;
             o.large_step_mis = large_step_mis;
             o.heuristic = heuristic;
             o.direct_spp = direct_spp;
             o.multiplexed = multiplexed;
             return o;
           }),
           py::kw_only(), py::arg("mutations_per_pixel") = 64, py::arg("max_depth") = -1, py::arg("rr_depth") = 5,
           py::arg("seed") = 0, py::arg("threads") = 0, py::arg("time_limit") = 0.0, py::arg("bootstrap") = 100000,
           py::arg("chains") = 256, py::arg("sigma") = 0.01f, py::arg("large_step_probability") = 0.3f,
           py::arg("large_step_mis") = PssmltOptions{}.large_step_mis, py::arg("heuristic") = MisHeuristic::Power,
           py::arg("direct_spp") = 128, py::arg("multiplexed") = false);

  m.def(
      "render_pssmlt",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const PssmltOptions& options,
         const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_pssmlt(*scene, camera, options, control); }, control,
                                     progress);
        return pssmlt_result_dict(std::move(run.result), camera, options, run.keyboard_interrupt);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      "Primary-sample-space MLT over BDPT; returns dict(mean, variance=None, light_paths (= mutations), stats, "
      "keyboard_interrupt); stats has b, b_ci95, mutations and acceptance rates, and when multiplexed "
      "b_per_depth, b_per_depth_ci95 and mutations_per_depth (indexed by path length).");

  m.def(
      "cast_random_rays",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, uint64_t n_rays, uint64_t seed,
         int threads) {
        RayCastStats s;
        {
          py::gil_scoped_release release;
          s = cast_random_rays(*scene, camera, n_rays, seed, threads);
        }
        py::dict d;
        d["rays"] = s.rays;
        d["hits"] = s.hits;
        d["seconds"] = s.seconds;
        d["rays_per_second"] = s.seconds > 0 ? static_cast<double>(s.rays) / s.seconds : 0.0;
        return d;
      },
      py::arg("scene"), py::arg("camera"), py::arg("n_rays"), py::arg("seed") = 0, py::arg("threads") = 0,
      "Embree-only cast of incoherent rays (no shading): the ray-tracing limit for this scene.");
}

}  // namespace dualight::bindings
