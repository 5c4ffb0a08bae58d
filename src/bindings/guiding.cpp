// Guides for Python (guiding/): train one, radiance from camera paths or importance from light
// paths, and ask it for densities, samples and its subdivisions, to test and to draw it.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>
#include <memory>

#include "bindings/interruptible.h"
#include "bindings/numpy_util.h"
#include "bindings/render_result.h"
#include "pathspace/bdpt.h"
#include "pathspace/light_tracer.h"
#include "pathspace/path_tracer.h"

namespace dualight::bindings {

namespace {

struct Guide {
  std::shared_ptr<const SdTree> tree;
  GuidingStats stats;
};

using Rows = py::array_t<float, py::array::c_style | py::array::forcecast>;

const SdTree& tree_of(const Guide& g) {
  if (!g.tree) throw py::value_error("the guide is empty: training ended before its first iteration");
  return *g.tree;
}

Vec3 row3(const std::vector<float>& v, size_t i) { return {v[3 * i], v[3 * i + 1], v[3 * i + 2]}; }

size_t matched_rows(const std::vector<float>& a, const std::vector<float>& b, int cols_b, const char* name_b) {
  const size_t n = a.size() / 3;
  if (b.size() / cols_b != n) throw py::value_error(std::string(name_b) + " must have as many rows as points");
  return n;
}

// pdf(points, directions): each direction's solid-angle density at its point (0 where the leaf is empty).
py::array_t<float> guide_pdf(const Guide& g, const Rows& points, const Rows& directions) {
  const SdTree& tree = tree_of(g);
  const std::vector<float> p = rows_of(points, 3, "points"), d = rows_of(directions, 3, "directions");
  const size_t n = matched_rows(p, d, 3, "directions");
  std::vector<float> out(n);
  for (size_t i = 0; i < n; ++i) {
    const Vec3 w = row3(d, i);
    const float len = length(w);
    if (!(len > 0.f) || !std::isfinite(len)) throw py::value_error("directions must be finite and non-zero");
    out[i] = tree.at(row3(p, i)).directions.pdf_w(w / len);
  }
  return to_numpy(std::move(out), {static_cast<py::ssize_t>(n)});
}

// sample(points, u): a direction from each point's leaf for u in [0, 1)^2 (NaN where the leaf is empty).
py::array_t<float> guide_sample(const Guide& g, const Rows& points, const Rows& u) {
  const SdTree& tree = tree_of(g);
  const std::vector<float> p = rows_of(points, 3, "points"), uv = rows_of(u, 2, "u");
  const size_t n = matched_rows(p, uv, 2, "u");
  std::vector<float> out(3 * n, std::numeric_limits<float>::quiet_NaN());
  for (size_t i = 0; i < n; ++i) {
    const float u0 = uv[2 * i], u1 = uv[2 * i + 1];
    if (!(u0 >= 0.f && u0 < 1.f && u1 >= 0.f && u1 < 1.f)) throw py::value_error("u must lie in [0, 1)");
    const DirectionalQuadtree& d = tree.at(row3(p, i)).directions;
    if (d.empty()) continue;
    const Vec3 w = d.sample({u0, u1});
    out[3 * i] = w.x;
    out[3 * i + 1] = w.y;
    out[3 * i + 2] = w.z;
  }
  return to_numpy(std::move(out), {static_cast<py::ssize_t>(n), 3});
}

// The spatial leaves: dict(lo, hi, directional_nodes, total, bsdf_fraction).
py::dict guide_leaves(const Guide& g) {
  const SdTree& tree = tree_of(g);
  const std::vector<SdTree::LeafBox> boxes = tree.leaf_boxes();
  std::vector<float> lo, hi, total, fraction;
  std::vector<uint32_t> nodes;
  for (const SdTree::LeafBox& b : boxes) {
    lo.insert(lo.end(), {b.lo.x, b.lo.y, b.lo.z});
    hi.insert(hi.end(), {b.hi.x, b.hi.y, b.hi.z});
    nodes.push_back(static_cast<uint32_t>(tree.leaf(b.leaf).directions.node_count()));
    total.push_back(tree.leaf(b.leaf).directions.total());
    fraction.push_back(tree.leaf(b.leaf).bsdf_fraction);
  }
  const py::ssize_t n = static_cast<py::ssize_t>(boxes.size());
  py::dict d;
  d["lo"] = to_numpy(std::move(lo), {n, 3});
  d["hi"] = to_numpy(std::move(hi), {n, 3});
  d["directional_nodes"] = to_numpy(std::move(nodes), {n});
  d["total"] = to_numpy(std::move(total), {n});
  d["bsdf_fraction"] = to_numpy(std::move(fraction), {n});
  return d;
}

// The quadtree of the leaf holding `point`: rows (u0, v0, size, density on the square) of its leaf cells.
py::array_t<float> guide_directional(const Guide& g, float x, float y, float z) {
  const DirectionalQuadtree& d = tree_of(g).at({x, y, z}).directions;
  std::vector<float> rows;
  if (!d.empty()) {
    struct Item {
      uint32_t node;
      float u0, v0, size, density;
    };
    std::vector<Item> stack{{0, 0.f, 0.f, 1.f, 1.f}};
    while (!stack.empty()) {
      const Item it = stack.back();
      stack.pop_back();
      const DirectionalQuadtree::Node& n = d.nodes()[it.node];
      for (int q = 0; q < 4; ++q) {
        const float half = 0.5f * it.size;
        const float u0 = it.u0 + ((q & 1) ? half : 0.f), v0 = it.v0 + ((q & 2) ? half : 0.f);
        const float density = it.density * n.density[q];  // as pdf_square multiplies them
        if (n.child[q] != 0) {
          stack.push_back({n.child[q], u0, v0, half, density});
        } else {
          rows.insert(rows.end(), {u0, v0, half, density});
        }
      }
    }
  }
  const py::ssize_t n = static_cast<py::ssize_t>(rows.size() / 4);
  return to_numpy(std::move(rows), {n, 4});
}

template <class Options, class Train>
void def_training(py::module_& m, const char* name, const Train& train, const char* doc) {
  m.def(
      name,
      [train](std::shared_ptr<const Scene> scene, const PinholeCamera& camera, const Options& options,
              const py::object& progress) {
        check_emitters(*scene);
        RenderControl control;
        auto run = run_interruptible(
            [&] {
              TrainedGuide t = train(*scene, camera, options, control);
              return Guide{std::move(t.tree), t.stats};
            },
            control, progress);
        py::dict d;
        d["guide"] = py::cast(std::move(run.result));
        d["keyboard_interrupt"] = run.keyboard_interrupt;
        return finished(run, d);
      },
      py::arg("scene"), py::arg("camera"), py::arg("options"), py::arg("progress") = py::none(), doc);
}

// A guide built from records given as rows (x, y, z, wx, wy, wz, value): value is the incident
// quantity along the unit direction w over the density w was drawn with (guide_record.h). Every
// leaf samples the guide with probability 1 - bsdf_fraction (nothing judges a first guide).
// The most records guide_from_records takes (and solution_records makes: MAX_GUIDE_RECORDS).
constexpr py::ssize_t kMaxRecords = py::ssize_t(1) << 24;

Guide guide_from_records(const Scene& scene, const Rows& rows, const SdTreeSettings& settings) {
  if (rows.ndim() != 2 || rows.shape(1) != 7) throw py::value_error("records must have shape (N, 7)");
  if (rows.shape(0) < 1 || rows.shape(0) > kMaxRecords) {
    throw py::value_error("records must number 1 to 2^24, got " + std::to_string(rows.shape(0)));
  }
  if (!(settings.bsdf_fraction >= 0.f && settings.bsdf_fraction <= 1.f)) {
    throw py::value_error("bsdf_fraction must be in [0, 1]");
  }
  if (!(settings.rho > 0.f && settings.rho < 1.f)) throw py::value_error("rho must be in (0, 1)");
  if (settings.spatial_threshold < 1) throw py::value_error("spatial_threshold must be >= 1");
  const std::vector<float> r = rows_of(rows, 7, "records");
  const size_t n = r.size() / 7;
  GuideRecords records(n);
  for (size_t i = 0; i < n; ++i) {
    const float* x = &r[7 * i];
    const Vec3 w{x[3], x[4], x[5]};
    const float len = length(w);
    for (int k = 0; k < 7; ++k) {
      if (!std::isfinite(x[k])) throw py::value_error("records must be finite (row " + std::to_string(i) + ")");
    }
    if (!(len > 0.f) || !(x[6] >= 0.f)) {
      throw py::value_error("records need non-zero directions and values >= 0 (row " + std::to_string(i) + ")");
    }
    records[i] = {{x[0], x[1], x[2]}, direction_to_square(w / len), x[6], x[6], 0.f, 1.f};
  }
  Vec3 lo, hi;
  guide_bounds(scene, lo, hi);
  Guide g;
  {
    py::gil_scoped_release release;  // sorting and building (well under a second for 2^20 records)
    g.tree = std::make_shared<const SdTree>(records, lo, hi, settings);
  }
  g.stats.records = n;
  g.stats.spatial_leaves = g.tree->leaves();
  g.stats.directional_nodes = g.tree->directional_nodes();
  g.tree->bsdf_fractions(g.stats.bsdf_fraction, g.stats.bsdf_fraction_min, g.stats.bsdf_fraction_max);
  return g;
}

// options with start guides (null: none) for its training's first iteration.
template <class Options>
void def_with_guide_start(py::module_& m) {
  m.def(
      "with_guide_start",
      [](Options o, const Guide* radiance, const Guide* importance) {
        o.guide_start_radiance = radiance != nullptr ? radiance->tree : nullptr;
        o.guide_start_importance = importance != nullptr ? importance->tree : nullptr;
        return o;
      },
      py::arg("options"), py::arg("radiance").none(true), py::arg("importance").none(true),
      "A copy of options whose guide training starts from these guides (None: from BSDF sampling).");
}

}  // namespace

void bind_guiding(py::module_& m) {
  py::class_<Guide>(m, "Guide",
                    "A trained SD-tree guide (guiding/sd_tree.h): a spatial binary tree with a quadtree of "
                    "directions in each leaf.")
      .def("pdf", &guide_pdf, py::arg("points"), py::arg("directions"),
           "Solid-angle density of each direction (N, 3) at its point (N, 3); 0 where the leaf learnt nothing.")
      .def("sample", &guide_sample, py::arg("points"), py::arg("u"),
           "A unit direction per point (N, 3) from u (N, 2) in [0, 1); NaN where the leaf learnt nothing.")
      .def("leaves", &guide_leaves, "The spatial leaves: dict(lo, hi, directional_nodes, total, bsdf_fraction).")
      .def("directional", &guide_directional, py::arg("x"), py::arg("y"), py::arg("z"),
           "The quadtree at a point: rows (u0, v0, size, density on the unit square); u = (cos theta + 1) / 2, "
           "v = phi / (2 pi); solid-angle density = density / (4 pi).")
      .def_property_readonly("stats", [](const Guide& g) { return guiding_dict(g.stats); })
      .def_property_readonly("empty", [](const Guide& g) { return !g.tree; });

  m.attr("MAX_GUIDE_RECORDS") = kMaxRecords;
  m.def(
      "guide_from_records",
      [](std::shared_ptr<const Scene> scene, const Rows& records, float bsdf_fraction, uint32_t spatial_threshold,
         float rho) {
        SdTreeSettings settings;
        settings.learn_bsdf_fraction = false;
        settings.bsdf_fraction = bsdf_fraction;
        settings.spatial_threshold = spatial_threshold;
        settings.rho = rho;
        return guide_from_records(*scene, records, settings);
      },
      py::arg("scene"), py::arg("records"), py::arg("bsdf_fraction") = 0.5f, py::arg("spatial_threshold") = 1000u,
      py::arg("rho") = 0.01f,
      "A guide over the scene's box from records (N, 7): x, y, z, wx, wy, wz, value (the incident quantity "
      "over the density the direction was drawn with), sampled with probability 1 - bsdf_fraction in every leaf.");
  def_with_guide_start<PathTracerOptions>(m);
  def_with_guide_start<LightTracerOptions>(m);
  def_with_guide_start<BdptOptions>(m);
  def_training<PathTracerOptions>(m, "train_radiance_guide", &train_radiance_guide,
                                  "Trains the radiance guide the path tracer would (options.guiding need not be set); returns "
                                  "dict(guide, keyboard_interrupt).");
  def_training<LightTracerOptions>(m, "train_importance_guide", &train_importance_guide,
                                   "Trains the importance guide the light tracer would; returns dict(guide, keyboard_interrupt).");
}

}  // namespace dualight::bindings
