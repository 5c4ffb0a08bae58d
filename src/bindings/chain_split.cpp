// The MLT methods in the three parts of pathspace/chain_split.h, for renders whose chains run as
// tasks elsewhere (python/dualight/executor.py): start_chains, run_chains on ranges of chains,
// finish_chains. ChainStartUp and ChainPart pickle to bytes, so they travel to other processes
// and machines.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <functional>
#include <string>
#include <vector>

#include "bindings/interruptible.h"
#include "bindings/render_result.h"
#include "core/stopwatch.h"
#include "pathspace/chain_split.h"
#include "pathspace/mlt.h"
#include "pathspace/pssmlt.h"

namespace dualight::bindings {

namespace {

// Parts from other processes, each checked against the start-up (itself checked against the
// options first) before they merge: a sum of corrupt parts can look sound (two negative sums
// wrap around to a positive one).
template <class Options>
ChainPart merged(const ChainStartUp& start, const std::vector<const ChainPart*>& parts, const Options& options,
                 const PinholeCamera& camera, ChainStartUpShape (*shape)(const Options&, size_t)) {
  const size_t pixels = static_cast<size_t>(camera.width()) * camera.height();
  check_chain_start_up(start, pixels, shape(options, pixels));
  ChainPart all;
  for (const ChainPart* p : parts) {
    check_chain_part(start, *p, 3 * pixels);
    all.merge(*p);
  }
  return all;
}

// start_chains, run_chains and finish_chains for one method's options type.
template <class Options, class StartUp, class Chains, class Finish>
void bind_method(py::module_& m, const StartUp& start_up, const Chains& chains, const Finish& finish,
                 ChainStartUpShape (*shape)(const Options&, size_t)) {
  m.def(
      "start_chains",
      [start_up](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const Options& options,
                 const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        const std::function<double()> elapsed = Stopwatch();
        auto run = run_interruptible([&] { return start_up(*scene, camera, options, control, elapsed); }, control,
                                     progress);
        // Another exception than Ctrl-C's is raised here with the partial result on it.
        if (run.raised) finished(run, py::cast(std::move(run.result)));
        return std::move(run.result);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(),
      "The start-up of an MLT render (direct light, pilot, bootstrap, chain starts), run once; "
      "its `cancelled` is True after Ctrl-C.");
  m.def(
      "run_chains",
      [chains](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const Options& options,
               const ChainStartUp& start, uint64_t first_chain, uint64_t chain_count, const py::object& progress) {
        check_emitters(*scene);
        if (first_chain + chain_count > start.chains() || first_chain + chain_count < first_chain) {
          throw py::value_error("chains [" + std::to_string(first_chain) + ", " +
                                std::to_string(first_chain + chain_count) + ") are not all in the start-up's " +
                                std::to_string(start.chains()));
        }
        RenderControl control;
        const std::function<double()> elapsed = Stopwatch();
        auto run = run_interruptible(
            [&] {
              ChainPart part = chains(*scene, camera, options, start, first_chain, chain_count, control, elapsed);
              part.stats.seconds = elapsed();
              return part;
            },
            control, progress);
        // Another exception than Ctrl-C's is raised here with the partial result on it.
        if (run.raised) finished(run, py::cast(std::move(run.result)));
        return std::move(run.result);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("start"), py::arg("first_chain"),
      py::arg("chain_count"), py::arg("progress") = py::none(),
      "Chains [first_chain, first_chain + chain_count) of a start-up; its `interrupted` is True after Ctrl-C.");
  m.def(
      "finish_chains",
      [finish, shape](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const Options& options,
                      const ChainStartUp& start, const std::vector<const ChainPart*>& parts, bool keyboard_interrupt) {
        return finish(*scene, camera, options, start, merged(start, parts, options, camera, shape),
                      keyboard_interrupt);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("start"), py::arg("parts"),
      py::arg("keyboard_interrupt") = false,
      "The render's result dict (as render_mlt / render_pssmlt) from its start-up and chain parts, given in "
      "chain order; stats.seconds is the start-up's plus the parts' (the caller knows the wall time).");
}

template <class T>
void bind_pickle(py::class_<T>& c, T (*from_bytes)(const std::string&)) {
  c.def(py::pickle([](const T& v) { return py::bytes(to_bytes(v)); },
                   [from_bytes](const py::bytes& b) { return from_bytes(std::string(b)); }));
}

}  // namespace

void bind_chain_split(py::module_& m) {
  py::class_<ChainStartUp> start(m, "ChainStartUp",
                                 "What every chain of an MLT render needs: direct light, bootstrap, b, chain starts "
                                 "(picklable).");
  start.def_property_readonly("chains", &ChainStartUp::chains, "Chains in all populations.")
      .def_property_readonly("populations", [](const ChainStartUp& s) { return s.populations.size(); })
      .def_property_readonly("b", [](const ChainStartUp& s) { return s.mlt.b_splatted; },
                             "The bootstrap's normalisation (sum over populations).")
      .def_property_readonly("cancelled", [](const ChainStartUp& s) { return s.cancelled; })
      .def_property_readonly("seconds", [](const ChainStartUp& s) { return s.stats.seconds; })
      .def("for_chains", &ChainStartUp::for_chains, py::arg("first_chain"), py::arg("chain_count"),
           "A copy holding only what chains [first_chain, first_chain + chain_count) need (smaller to send).");
  bind_pickle<ChainStartUp>(start, &start_up_from_bytes);

  py::class_<ChainPart> part(m, "ChainPart", "What a range of chains produced (picklable).");
  part.def_property_readonly("first_chain", [](const ChainPart& p) { return p.first_chain; })
      .def_property_readonly("chains", [](const ChainPart& p) { return p.chains; })
      .def_property_readonly("mutations", [](const ChainPart& p) { return p.stats.samples; })
      .def_property_readonly("rays", [](const ChainPart& p) { return p.stats.rays; })
      .def_property_readonly("seconds", [](const ChainPart& p) { return p.stats.seconds; })
      .def_property_readonly("interrupted", [](const ChainPart& p) { return p.stats.interrupted; });
  bind_pickle<ChainPart>(part, &part_from_bytes);

  bind_method<PssmltOptions>(
      m, &pssmlt_start_up, &pssmlt_chains,
      [](const Scene&, const PinholeCamera& camera, const PssmltOptions& options, const ChainStartUp& s,
         const ChainPart& p, bool keyboard_interrupt) {
        MltResult r = pssmlt_finish(s, p, options, camera);
        r.stats.seconds = s.stats.seconds + p.stats.seconds;
        return pssmlt_result_dict(std::move(r), camera, options, keyboard_interrupt);
      },
      &pssmlt_start_up_shape);
  bind_method<MltOptions>(
      m, &mlt_start_up, &mlt_chains,
      [](const Scene& scene, const PinholeCamera& camera, const MltOptions& options, const ChainStartUp& s,
         const ChainPart& p, bool keyboard_interrupt) {
        PathMltResult r = mlt_finish(scene, s, p, options, camera);
        r.result.stats.seconds = s.stats.seconds + p.stats.seconds;
        return path_mlt_result_dict(std::move(r), camera, options, keyboard_interrupt);
      },
      &mlt_start_up_shape);
}

}  // namespace dualight::bindings
