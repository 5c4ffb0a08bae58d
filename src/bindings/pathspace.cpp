// The path tracer, the light tracer, BDPT and PSSMLT: their options (bindings/options.h) and
// renderers, and checks for tests and plots (subpath densities, sampler points, ray casts).
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

  py::enum_<Strategies>(m, "Strategies")
      .value("mis", Strategies::Mis)
      .value("bsdf", Strategies::Bsdf)
      .value("light", Strategies::Light);

  py::enum_<LaneIsa>(m, "LaneIsa")
      .value("auto", LaneIsa::Auto)
      .value("off", LaneIsa::Off)
      .value("sse2", LaneIsa::Sse2)
      .value("avx2", LaneIsa::Avx2)
      .value("avx512", LaneIsa::Avx512);

  OptionsClass<PathTracerOptions> path(m, "PathTracerOptions", "Options of the path tracer.");
  add_pixel_fields(path, "Samples per pixel; 0 = until time_limit.");
  path.field("strategies", &PathTracerOptions::strategies,
             "mis: light and BSDF sampling combined by MIS; bsdf or light: that strategy alone "
             "(the other only where it alone can find the light).");
  path.field("lanes", &PathTracerOptions::lanes,
             "auto: a tile row's paths at a time in SIMD lanes where the CPU runs AVX-512 or AVX2 and "
             "the render is unguided (materials other than untextured diffuse, mirror or smooth glass, and "
             "emitters other than untextured area emitters, lane by lane); off: one path at a time; sse2, "
             "avx2 or avx512: that build. The image is the same, bit for bit.");
  add_guiding_fields(path);
  path.bind();

  m.def(
      "render_path",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const PathTracerOptions& options,
         const py::object& progress, bool accumulators) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_path(*scene, camera, options, control); }, control,
                                     progress);
        return finished(run, result_dict(std::move(run.result), run.keyboard_interrupt, accumulators));
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("accumulators") = false,
      "Path-traces the scene; returns dict(mean, variance, counts, stats, keyboard_interrupt). "
      "progress(done, total) is called about every 100 ms.");

  py::enum_<MisHeuristic>(m, "MisHeuristic")
      .value("power", MisHeuristic::Power)
      .value("balance", MisHeuristic::Balance);

  OptionsClass<LightTracerOptions> light(m, "LightTracerOptions", "Options of the light tracer.");
  add_pixel_fields(light, "Particles per pixel (spp x pixels particles in all); 0 = until time_limit.");
  add_guiding_fields(light);
  light.bind();

  OptionsClass<BdptOptions> bdpt(m, "BdptOptions", "Options of bidirectional path tracing.");
  add_pixel_fields(bdpt, "Samples per pixel; 0 = until time_limit.");
  bdpt.field("heuristic", &BdptOptions::heuristic, "How the strategies' samples are weighted (MIS).")
      .field("strategies", &BdptOptions::strategies,
             "mis: every strategy by MIS; bsdf: the fewest light vertices (s = 0) that can sample "
             "each path; light: s = 1 first, then s = 0, 2, 3, ...")
      .field("strategy_images", &BdptOptions::strategy_images,
             "Also an image per strategy (s, t), MIS-weighted; they sum to the image (needs a bounded max_depth).")
      .field("light_pool", &BdptOptions::light_pool,
             "Each connection (s >= 2, t >= 2) takes the light subpath of another pixel of its group of "
             "light_pool pixels (same tile row, same sample index), a different one per strategy; 1: the "
             "sample's own (classic BDPT). Guided BDPT uses 1.",
             within(1, kBdptLightPoolMax));
  add_guiding_fields(bdpt);
  bdpt.bind();

  m.def(
      "render_light",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const LightTracerOptions& options,
         const py::object& progress, bool accumulators) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_light(*scene, camera, options, control); }, control,
                                     progress);
        return finished(run, result_dict(std::move(run.result), run.keyboard_interrupt, accumulators));
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
        return finished(run, d);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      py::arg("accumulators") = false,
      "Bidirectional path tracing; returns dict(mean, variance, counts, light_paths, stats, strategies, "
      "keyboard_interrupt); strategies maps (s, t) to MIS-weighted images when asked for.");

  OptionsClass<PssmltOptions> pssmlt(m, "PssmltOptions",
                                      "Options of primary-sample-space MLT (and multiplexed MLT).");
  add_estimator_fields(pssmlt, "mutations_per_pixel", "Mutations per pixel; 0 = until time_limit.");
  pssmlt.field("bootstrap", &PssmltOptions::bootstrap,
               "Independent samples that estimate b (per path length when multiplexed) and start the chains.",
               bootstrap_range())
      .field("chains", &PssmltOptions::chains, "Markov chains.", chain_range())
      .field("sigma", &PssmltOptions::sigma, "Deviation of a small step, per random number.", strictly_within(0, 1))
      .field("large_step_probability", &PssmltOptions::large_step_probability,
             "Probability that a mutation is a large step (fresh numbers).", within(0, 1))
      .field("large_step_mis", &PssmltOptions::large_step_mis,
             "Kelemen's MIS: large steps' proposals also count as independent samples.")
      .field("heuristic", &PssmltOptions::heuristic, "BDPT's MIS heuristic (bootstrap, chains, direct light).")
      .field("direct_spp", &PssmltOptions::direct_spp,
             "BDPT samples per pixel of the paths of 1 and 2 segments, left out of the chains; 0 keeps them in.")
      .field("multiplexed", &PssmltOptions::multiplexed,
             "Multiplexed MLT: chains per path length, each sample one BDPT strategy (needs a bounded max_depth).")
      .bind();

  m.def(
      "render_pssmlt",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const PssmltOptions& options,
         const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible([&] { return render_pssmlt(*scene, camera, options, control); }, control,
                                     progress);
        return finished(run, pssmlt_result_dict(std::move(run.result), camera, options, run.keyboard_interrupt));
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
