// Radiosity: form factors and their options, the system M = I - diag(rho) F with its direct and
// stepped solvers, and hierarchical radiosity (bindings/options.h binds the options).
#include <optional>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "bindings/interruptible.h"
#include "bindings/numpy_util.h"
#include "bindings/options.h"
#include "geometry/camera_hits.h"
#include "radiosity/direct_irradiance.h"
#include "radiosity/form_factors.h"
#include "radiosity/hierarchical.h"
#include "radiosity/solve_direct.h"
#include "radiosity/solve_gathering.h"
#include "radiosity/solve_shooting.h"

namespace dualight::bindings {

namespace {

using DoubleArray = py::array_t<double, py::array::c_style | py::array::forcecast>;

std::vector<double> n_by_3(const DoubleArray& a, size_t n, const char* name) {
  if (a.ndim() != 2 || a.shape(1) != 3 || static_cast<size_t>(a.shape(0)) != n) {
    throw py::value_error(std::string(name) + " must have shape (" + std::to_string(n) + ", 3)");
  }
  return std::vector<double>(a.data(), a.data() + a.size());
}

py::array_t<double> as_n_by_3(std::vector<double> v) {
  const auto n = static_cast<py::ssize_t>(v.size() / 3);
  return to_numpy(std::move(v), {n, 3});
}

py::dict step_dict(const SolverStep& s) {
  py::dict d;
  d["iteration"] = s.iteration;
  d["residual"] = s.residual;
  d["seconds"] = s.seconds;
  return d;
}

SystemSide side_of(bool dual) { return dual ? SystemSide::Dual : SystemSide::Primal; }

// The fields both radiosity options have: the visibility rays' seed and threads, and skipping.
template <class T>
void add_visibility_fields(OptionsClass<T>& o) {
  o.field("seed", &T::seed, "Seed of the visibility rays.")
      .field("threads", &T::threads, "Worker threads; 0 = all cores.", at_least(0))
      .field("skip_unneeded", &T::skip_unneeded, "Skip visibility rays in a convex enclosure; False traces them all.");
}

// Binds a stepped solver: step() with the GIL released, solution, residual, iteration.
template <class Solver, class... Extra>
py::class_<Solver> bind_stepped(py::module_& m, const char* name, const char* doc) {
  py::class_<Solver> cls(m, name, doc);
  cls.def("step",
          [](Solver& s) {
            SolverStep st;
            {
              py::gil_scoped_release release;
              st = s.step();
            }
            return step_dict(st);
          })
      .def_property_readonly("solution", [](const Solver& s) { return as_n_by_3(s.solution()); })
      .def_property_readonly("residual", &Solver::residual)
      .def_property_readonly("iteration", &Solver::iteration);
  return cls;
}

}  // namespace

void bind_radiosity(py::module_& m) {
  m.attr("MAX_DIRECT_PATCHES") = kMaxDirectPatches;
  m.def(
      "point_polygon_form_factor",
      [](const std::array<float, 3>& x, const std::array<float, 3>& n,
         const py::array_t<float, py::array::c_style | py::array::forcecast>& polygon) {
        const std::vector<float> p = rows_of(polygon, 3, "polygon");
        std::vector<Vec3> poly;
        for (size_t k = 0; k < p.size(); k += 3) poly.emplace_back(p[k], p[k + 1], p[k + 2]);
        return point_polygon_form_factor(Vec3(x[0], x[1], x[2]), Vec3(n[0], n[1], n[2]), poly);
      },
      py::arg("point"), py::arg("normal"), py::arg("polygon"),
      "Unoccluded form factor from a differential area to a planar convex polygon (3-8 vertices) "
      "whose right-hand-rule normal faces the point; 0 if it faces away.");

  OptionsClass<FormFactorOptions> form_factor_options(m, "FormFactorOptions", "Options of compute_form_factors.");
  form_factor_options
      .field("quadrature", &FormFactorOptions::quadrature,
             "Points on the receiving patch: 1 (centroid), 3 (degree 2) or 7 (degree 5).")
      .field("shadow_rays", &FormFactorOptions::shadow_rays,
             "Visibility rays per quadrature point and source patch; 0 = no occlusion test.", at_least(0))
      .field("min_value", &FormFactorOptions::min_value, "Entries below this are dropped (0 keeps every non-zero).",
             at_least(0));
  add_visibility_fields(form_factor_options);
  form_factor_options.bind();

  py::class_<FormFactorMatrices, std::shared_ptr<FormFactorMatrices>>(m, "FormFactors",
                                                                      "Sparse form factors F (CSR) and F^T.")
      .def_property_readonly("n", [](const FormFactorMatrices& f) { return f.F.n; })
      .def_property_readonly("nonzeros", [](const FormFactorMatrices& f) { return f.F.nonzeros(); })
      // Views into the C++ arrays (no copy); they keep the matrices alive.
      .def_property_readonly("indptr", [](py::object self) {
        const auto& f = self.cast<const FormFactorMatrices&>();
        return py::array_t<uint64_t>(static_cast<py::ssize_t>(f.F.indptr.size()), f.F.indptr.data(), self);
      })
      .def_property_readonly("indices", [](py::object self) {
        const auto& f = self.cast<const FormFactorMatrices&>();
        return py::array_t<uint32_t>(static_cast<py::ssize_t>(f.F.indices.size()), f.F.indices.data(), self);
      })
      .def_property_readonly("values", [](py::object self) {
        const auto& f = self.cast<const FormFactorMatrices&>();
        return py::array_t<float>(static_cast<py::ssize_t>(f.F.values.size()), f.F.values.data(), self);
      })
      .def(
          "checks",
          [](const FormFactorMatrices& f, const py::array_t<double, py::array::c_style | py::array::forcecast>& areas) {
            if (areas.ndim() != 1 || static_cast<size_t>(areas.shape(0)) != f.F.n) {
              throw py::value_error("areas must have one entry per patch");
            }
            const std::vector<double> a(areas.data(), areas.data() + areas.size());
            FormFactorMatrices::Checks c;
            {
              py::gil_scoped_release release;
              c = f.checks(a);
            }
            py::dict d;
            d["reciprocity_max_relative_error"] = c.reciprocity_max;
            d["reciprocity_mean_relative_error"] = c.reciprocity_mean;
            d["row_sum_min"] = c.row_sum_min;
            d["row_sum_max"] = c.row_sum_max;
            d["row_sum_mean"] = c.row_sum_mean;
            return d;
          },
          py::arg("areas"), "Reciprocity A_i F_ij = A_j F_ji and row-sum (closure) summaries.")
      .def("row_sums", [](const FormFactorMatrices& f) {
        std::vector<double> s(f.F.n);
        for (uint32_t i = 0; i < f.F.n; ++i) s[i] = f.F.row_sum(i);
        return to_numpy(std::move(s), {static_cast<py::ssize_t>(f.F.n)});
      })
      .def_static(
          "from_csr",
          [](uint32_t n, const py::array_t<uint64_t, py::array::c_style | py::array::forcecast>& indptr,
             const py::array_t<uint32_t, py::array::c_style | py::array::forcecast>& indices,
             const py::array_t<float, py::array::c_style | py::array::forcecast>& values) {
            CsrMatrix F;
            F.n = n;
            F.indptr.assign(indptr.data(), indptr.data() + indptr.size());
            F.indices.assign(indices.data(), indices.data() + indices.size());
            F.values.assign(values.data(), values.data() + values.size());
            if (F.indptr.size() != n + 1 || F.indptr.back() != F.indices.size() || F.indices.size() != F.values.size()) {
              throw py::value_error("inconsistent CSR arrays");
            }
            for (const uint32_t j : F.indices) {
              if (j >= n) throw py::value_error("CSR column index out of range");
            }
            return std::make_shared<FormFactorMatrices>(std::move(F));
          },
          py::arg("n"), py::arg("indptr"), py::arg("indices"), py::arg("values"));

  m.def(
      "compute_form_factors",
      [](std::shared_ptr<const Scene> patches, const FormFactorOptions& options, const py::object& progress,
         const std::optional<py::array_t<uint8_t, py::array::c_style | py::array::forcecast>>& scatters,
         const std::optional<py::array_t<uint8_t, py::array::c_style | py::array::forcecast>>& receivers) {
        std::optional<FormFactorRows> rows;
        if (scatters) {
          const size_t n = patches->triangle_count();
          rows.emplace();
          if (scatters->ndim() != 1 || static_cast<size_t>(scatters->size()) != n) {
            throw py::value_error("scatters needs one entry per patch");
          }
          rows->scatters.assign(scatters->data(), scatters->data() + n);
          if (receivers) {
            if (receivers->ndim() != 1 || static_cast<size_t>(receivers->size()) != n) {
              throw py::value_error("receivers needs one entry per patch");
            }
            rows->receivers.assign(receivers->data(), receivers->data() + n);
          }
        } else if (receivers) {
          throw py::value_error("receivers needs scatters too");
        }
        RenderControl control;
        FormFactorStats stats;
        auto run = run_interruptible(
            [&] {
              return std::make_shared<FormFactorMatrices>(
                  compute_form_factors(*patches, options, control, stats, rows ? &*rows : nullptr));
            },
            control, progress);
        if (run.keyboard_interrupt) {  // rows are missing: no partial matrix is worth keeping
          PyErr_SetNone(PyExc_KeyboardInterrupt);
          throw py::error_already_set();
        }
        finished(run, py::none());  // another exception from a signal handler or the callback
        py::dict s;
        s["pairs_tested"] = stats.pairs_tested;
        s["pairs_facing"] = stats.pairs_facing;
        s["rays"] = stats.rays;
        s["rays_skipped"] = stats.rays_skipped;
        s["rows_computed"] = stats.rows_computed;
        s["rows_skipped"] = patches->triangle_count() - stats.rows_computed;
        s["important_patches"] = stats.important;
        s["seconds"] = stats.seconds;
        s["rays_per_second"] = stats.seconds > 0 ? static_cast<double>(stats.rays) / stats.seconds : 0.0;
        return py::make_tuple(run.result, s);
      },
      py::arg("patches"), py::arg("options"), py::arg("progress") = py::none(), py::kw_only(),
      py::arg("scatters") = py::none(), py::arg("receivers") = py::none(),
      "Form factors between the triangles of `patches` (one patch each): (FormFactors, stats). Every row, or with "
      "scatters (rho > 0 per patch) only rows of patches that reflect, and with receivers (R > 0 per patch) only "
      "those of non-zero importance for that view (form_factors.h).");


  m.def(
      "direct_irradiance",
      [](std::shared_ptr<const Scene> patches, int points_per_axis, int env_strata, uint64_t seed, int threads,
         const py::object& progress) {
        if (points_per_axis < 1 || points_per_axis > 64) throw py::value_error("points_per_axis must be in [1, 64]");
        if (env_strata < 1 || env_strata > 64) throw py::value_error("env_strata must be in [1, 64]");
        RenderControl control;
        auto run = run_interruptible(
            [&] { return direct_irradiance(*patches, points_per_axis, env_strata, seed, threads, control); }, control,
            progress);
        if (run.keyboard_interrupt) {  // patches are missing: nothing worth keeping
          PyErr_SetNone(PyExc_KeyboardInterrupt);
          throw py::error_already_set();
        }
        finished(run, py::none());
        py::array_t<double> out({static_cast<py::ssize_t>(run.result.size()), py::ssize_t{3}});
        auto o = out.mutable_unchecked<2>();
        for (size_t k = 0; k < run.result.size(); ++k) {
          for (int c = 0; c < 3; ++c) o(static_cast<py::ssize_t>(k), c) = run.result[k][c];
        }
        return out;
      },
      py::arg("patches"), py::arg("points_per_axis") = 4, py::arg("env_strata") = 8, py::arg("seed") = 0,
      py::arg("threads") = 0, py::arg("progress") = py::none(),
      "Mean irradiance (N, 3) over each patch of `patches` (one triangle each) from its point, spot and directional "
      "lights and its environment (env_strata^2 pairs of directions per point), with visibility, at the centroids "
      "of an n x n split of the patch (radiosity/direct_irradiance.h).");

  py::class_<RadiositySystem, std::shared_ptr<RadiositySystem>>(m, "RadiositySystem",
                                                                "M = I - diag(rho) F for 3 channels.")
      .def(py::init([](std::shared_ptr<const FormFactorMatrices> f, const DoubleArray& reflectance,
                       const py::array_t<double, py::array::c_style | py::array::forcecast>& areas) {
             const size_t n = f->F.n;
             if (areas.ndim() != 1 || static_cast<size_t>(areas.shape(0)) != n) {
               throw py::value_error("areas must have shape (" + std::to_string(n) + ",)");
             }
             return std::make_shared<RadiositySystem>(f, n_by_3(reflectance, n, "reflectance"),
                                                      std::vector<double>(areas.data(), areas.data() + n));
           }),
           py::arg("form_factors"), py::arg("reflectance"), py::arg("areas"))
      .def_property_readonly("size", &RadiositySystem::size)
      .def(
          "residual",
          [](const RadiositySystem& s, const DoubleArray& x, const DoubleArray& b, bool dual) {
            return s.relative_residual(side_of(dual), n_by_3(x, s.size(), "x"), n_by_3(b, s.size(), "b"));
          },
          py::arg("x"), py::arg("b"), py::arg("dual") = false, "max |b - M x| / max |b| (M^T when dual).");

  bind_stepped<JacobiSolver>(m, "JacobiSolver", "Jacobi sweeps (gathering); dual=True solves M^T x = b.")
      .def(py::init([](std::shared_ptr<const RadiositySystem> s, const DoubleArray& rhs, bool dual, int threads) {
             return JacobiSolver(s, side_of(dual), n_by_3(rhs, s->size(), "rhs"), threads);
           }),
           py::arg("system"), py::arg("rhs"), py::arg("dual") = false, py::arg("threads") = 0);
  bind_stepped<GaussSeidelSolver>(m, "GaussSeidelSolver", "Gauss-Seidel sweeps (gathering).")
      .def(py::init([](std::shared_ptr<const RadiositySystem> s, const DoubleArray& rhs, bool dual) {
             return GaussSeidelSolver(s, side_of(dual), n_by_3(rhs, s->size(), "rhs"));
           }),
           py::arg("system"), py::arg("rhs"), py::arg("dual") = false);
  bind_stepped<SouthwellSolver>(m, "SouthwellSolver", "Southwell / progressive refinement (shooting).")
      .def(py::init([](std::shared_ptr<const RadiositySystem> s, const DoubleArray& rhs, bool dual,
                       uint32_t shots_per_step) {
             return SouthwellSolver(s, side_of(dual), n_by_3(rhs, s->size(), "rhs"), shots_per_step);
           }),
           py::arg("system"), py::arg("rhs"), py::arg("dual") = false, py::arg("shots_per_step") = 0)
      .def_property_readonly("unshot", [](const SouthwellSolver& s) { return as_n_by_3(s.unshot()); })
      .def_property_readonly("ambient", &SouthwellSolver::ambient)
      .def_property_readonly("shots", &SouthwellSolver::shots);

  py::class_<DirectSolver>(m, "DirectSolver", "Dense LU per channel; solves M x = b and M^T x = b.")
      .def(py::init([](std::shared_ptr<const RadiositySystem> s, int threads, const py::object& progress) {
             // The dense factorisation takes seconds at thousands of patches: interruptible.
             RenderControl control;
             auto run =
                 run_interruptible([&] { return std::make_unique<DirectSolver>(s, threads, &control); }, control, progress);
             if (run.keyboard_interrupt) {
               PyErr_SetNone(PyExc_KeyboardInterrupt);
               throw py::error_already_set();
             }
             finished(run, py::none());  // a factorisation cut short is unusable: nothing to keep
             return std::move(run.result);
           }),
           py::arg("system"), py::arg("threads") = 0, py::arg("progress") = py::none())
      .def(
          "solve",
          [](const DirectSolver& d, const DoubleArray& rhs, bool dual) {
            std::vector<double> b(rhs.data(), rhs.data() + rhs.size());
            std::vector<double> x;
            {
              py::gil_scoped_release release;
              x = d.solve(side_of(dual), b);
            }
            return as_n_by_3(std::move(x));
          },
          py::arg("rhs"), py::arg("dual") = false)
      .def_property_readonly("factor_seconds", &DirectSolver::factor_seconds);

  py::enum_<RefinementOracle>(m, "RefinementOracle")
      .value("bf", RefinementOracle::BF)
      .value("importance", RefinementOracle::Importance);

  OptionsClass<HierarchicalOptions> hierarchical_options(m, "HierarchicalOptions", "Options of HierarchicalSolver.");
  hierarchical_options
      .field("oracle", &HierarchicalOptions::oracle, "Which links to refine: by BF or by importance.")
      .field("epsilon", &HierarchicalOptions::epsilon,
             "Refinement threshold, relative: of the brightest emission (BF) or of the measurement (importance).",
             above(0))
      .field("min_area", &HierarchicalOptions::min_area,
             "Elements are not split below this area; 0 = 1e-4 of the largest input triangle.", at_least(0))
      .field("shadow_rays", &HierarchicalOptions::shadow_rays,
             "Visibility rays per receiver quadrature point (7 per link) and per estimate (2).", at_least(0))
      .field("sweeps", &HierarchicalOptions::sweeps, "Gauss-Seidel sweeps per step at most.", at_least(1))
      .field("tolerance", &HierarchicalOptions::tolerance, "Relative change per sweep that ends a step's sweeps.",
             above(0))
      .field("max_links", &HierarchicalOptions::max_links, "Refinement stops before exceeding this many links.",
             at_least(1));
  add_visibility_fields(hierarchical_options);
  hierarchical_options.bind();

  py::class_<HierarchicalSolver>(m, "HierarchicalSolver",
                                 "Hierarchical radiosity and importance (HSA91, SAS92); stepped.")
      .def(py::init([](std::shared_ptr<const Scene> scene,
                       const py::array_t<uint32_t, py::array::c_style | py::array::forcecast>& prim,
                       const py::array_t<float, py::array::c_style | py::array::forcecast>& b1,
                       const py::array_t<float, py::array::c_style | py::array::forcecast>& b2, double weight,
                       const HierarchicalOptions& options, const py::object& progress, const py::object& albedo) {
             if (prim.size() != b1.size() || prim.size() != b2.size()) {
               throw py::value_error("receiver arrays differ in length");
             }
             std::vector<Color> rho;
             if (!albedo.is_none()) {
               const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(albedo);
               if (!a || a.ndim() != 2 || a.shape(1) != 3 || static_cast<size_t>(a.shape(0)) != scene->triangle_count()) {
                 throw py::value_error("albedo must be an array of shape (triangles, 3)");
               }
               rho.reserve(scene->triangle_count());
               for (py::ssize_t t = 0; t < a.shape(0); ++t) rho.emplace_back(a.at(t, 0), a.at(t, 1), a.at(t, 2));
             }
             ReceiverSamples r{std::vector<uint32_t>(prim.data(), prim.data() + prim.size()),
                               std::vector<float>(b1.data(), b1.data() + b1.size()),
                               std::vector<float>(b2.data(), b2.data() + b2.size()), weight};
             // The initial linking is O(triangles^2): interruptible, with progress per triangle.
             RenderControl control;
             auto run = run_interruptible(
                 [&] { return std::make_unique<HierarchicalSolver>(*scene, std::move(r), options, &control, rho); },
                 control, progress);
             if (run.keyboard_interrupt) {
               PyErr_SetNone(PyExc_KeyboardInterrupt);
               throw py::error_already_set();
             }
             finished(run, py::none());  // a solver cut short is incomplete: nothing to keep
             return std::move(run.result);
           }),
           py::arg("scene"), py::arg("receiver_prim"), py::arg("receiver_b1"), py::arg("receiver_b2"),
           py::arg("receiver_weight"), py::arg("options"), py::arg("progress") = py::none(),
           py::arg("albedo") = py::none(), py::keep_alive<1, 2>())
      .def(
          "step",
          [](HierarchicalSolver& solver, const py::object& progress) {
            RenderControl control;
            auto run = run_interruptible([&] { return solver.step(&control); }, control, progress);
            if (run.keyboard_interrupt) {
              PyErr_SetNone(PyExc_KeyboardInterrupt);
              throw py::error_already_set();
            }
            finished(run, py::none());  // the hierarchy keeps what the step refined
            const HierarchicalStep& st = run.result;
            py::dict d;
            d["iteration"] = st.iteration;
            d["elements"] = st.elements;
            d["leaves"] = st.leaves;
            d["links"] = st.links;
            d["links_refined"] = st.links_refined;
            d["rays"] = st.rays;
            d["rays_skipped"] = st.rays_skipped;
            d["memory_bytes"] = st.memory_bytes;
            d["residual"] = st.residual;
            d["seconds"] = st.seconds;
            d["converged"] = st.converged;
            d["link_limit"] = st.link_limit;
            return d;
          },
          py::arg("progress") = py::none())
      .def("leaves",
           [](const HierarchicalSolver& solver) {
             const auto leaves = solver.leaves();
             const auto n = static_cast<py::ssize_t>(leaves.size());
             std::vector<float> v(9 * leaves.size());
             std::vector<uint32_t> root(leaves.size());
             std::vector<double> area(leaves.size()), B(3 * leaves.size()), W(3 * leaves.size()),
                 E(3 * leaves.size()), R(leaves.size()), density(leaves.size());
             for (size_t k = 0; k < leaves.size(); ++k) {
               const auto& l = leaves[k];
               for (int c = 0; c < 3; ++c) {
                 v[9 * k + 3 * c] = l.v[c].x;
                 v[9 * k + 3 * c + 1] = l.v[c].y;
                 v[9 * k + 3 * c + 2] = l.v[c].z;
                 B[3 * k + c] = l.B[c];
                 W[3 * k + c] = l.W[c];
                 E[3 * k + c] = l.E[c];
               }
               root[k] = l.root;
               area[k] = l.area;
               R[k] = l.R;
               density[k] = l.link_density;
             }
             py::dict d;
             d["vertices"] = to_numpy(std::move(v), {n, 3, 3});
             d["root"] = to_numpy(std::move(root), {n});
             d["area"] = to_numpy(std::move(area), {n});
             d["B"] = to_numpy(std::move(B), {n, 3});
             d["W"] = to_numpy(std::move(W), {n, 3});
             d["E"] = to_numpy(std::move(E), {n, 3});
             d["R"] = to_numpy(std::move(R), {n});
             d["link_density"] = to_numpy(std::move(density), {n});
             return d;
           })
      .def("links",
           [](const HierarchicalSolver& solver) {
             const auto links = solver.links();
             const auto n = static_cast<py::ssize_t>(links.size());
             std::vector<uint32_t> rr(links.size()), sr(links.size());
             std::vector<float> rc(3 * links.size()), sc(3 * links.size()), F(links.size());
             for (size_t k = 0; k < links.size(); ++k) {
               rr[k] = links[k].receiver_root;
               sr[k] = links[k].source_root;
               F[k] = links[k].F;
               for (int c = 0; c < 3; ++c) {
                 rc[3 * k + c] = links[k].receiver_centroid[c];
                 sc[3 * k + c] = links[k].source_centroid[c];
               }
             }
             py::dict d;
             d["receiver_root"] = to_numpy(std::move(rr), {n});
             d["source_root"] = to_numpy(std::move(sr), {n});
             d["receiver_centroid"] = to_numpy(std::move(rc), {n, 3});
             d["source_centroid"] = to_numpy(std::move(sc), {n, 3});
             d["F"] = to_numpy(std::move(F), {n});
             return d;
           })
      .def("measurements",
           [](const HierarchicalSolver& solver) {
             double p[3], d[3];
             solver.measurements(p, d);
             return py::make_tuple(std::array<double, 3>{p[0], p[1], p[2]}, std::array<double, 3>{d[0], d[1], d[2]});
           })
      .def_property_readonly("total_rays", &HierarchicalSolver::total_rays)
      .def_property_readonly("total_rays_skipped", &HierarchicalSolver::total_rays_skipped)
      .def("link_coverage_error", &HierarchicalSolver::link_coverage_error, py::arg("only_facing_roots") = true,
           "Largest |covered / area - 1| of any root as seen from any leaf (0: no source missed or doubled).");

  m.def(
      "trace_camera_hits",
      [](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, int samples_per_axis, uint64_t seed,
         int threads) {
        CameraHits h;
        {
          py::gil_scoped_release release;
          h = trace_camera_hits(*scene, camera, samples_per_axis, seed, threads);
        }
        return py::make_tuple(to_numpy(std::move(h.prim), {h.height, h.width, h.samples}),
                              to_numpy(std::move(h.barycentric), {h.height, h.width, h.samples, 2}));
      },
      py::arg("scene"), py::arg("camera"), py::arg("samples_per_axis") = 2, py::arg("seed") = 0,
      py::arg("threads") = 0,
      "Triangle hit by each stratified camera sample, (H x W x S int32, -1 = miss) and its barycentrics.");
}

}  // namespace dualight::bindings
