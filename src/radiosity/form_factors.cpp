#include "radiosity/form_factors.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/stopwatch.h"
#include "radiosity/diffuse_only.h"

namespace dualight {

namespace {

// Double-precision vectors: the contour formula subtracts nearly equal angles near shared edges.
struct D3 {
  double x, y, z;
};
D3 to_d3(const Vec3& v) { return {v.x, v.y, v.z}; }
D3 sub(const D3& a, const D3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
D3 add_scaled(const D3& a, const D3& d, double t) { return {a.x + t * d.x, a.y + t * d.y, a.z + t * d.z}; }
double dot3(const D3& a, const D3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
D3 cross3(const D3& a, const D3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double norm3(const D3& a) { return std::sqrt(dot3(a, a)); }

constexpr int kMaxClipped = 16;  // a triangle clipped by one plane has at most 4 vertices

// Lambert's contour integral over a polygon entirely on the non-negative side of x's tangent plane.
double contour_integral(const D3& x, const D3& n, const D3* poly, int m) {
  double sum = 0.0;
  for (int k = 0; k < m; ++k) {
    const D3 r0 = sub(poly[k], x), r1 = sub(poly[(k + 1) % m], x);
    const D3 c = cross3(r0, r1);
    const double len = norm3(c);
    if (!(len > 0.0)) continue;  // a degenerate edge (zero length or through x) adds nothing
    const double gamma = std::atan2(len, dot3(r0, r1));
    sum += gamma * dot3(n, c) / len;
  }
  return std::abs(sum) / (2.0 * M_PI);
}

// Clips a convex polygon to dot(n, p - x) >= 0 (Sutherland-Hodgman against one plane).
int clip_to_half_space(const D3& x, const D3& n, const D3* in, int m, D3* out) {
  int count = 0;
  for (int k = 0; k < m; ++k) {
    const D3& a = in[k];
    const D3& b = in[(k + 1) % m];
    const double da = dot3(n, sub(a, x)), db = dot3(n, sub(b, x));
    if (da >= 0.0) out[count++] = a;
    if ((da > 0.0 && db < 0.0) || (da < 0.0 && db > 0.0)) out[count++] = add_scaled(a, sub(b, a), da / (da - db));
  }
  return count;
}

// Whether some corner lies in front of the plane through p with normal n (any length) by more
// than float rounding: 1e-6 (about 8 float ulps) of the largest coordinate involved. Exactly
// coplanar is not enough: the corners of a coincident or overlapping coplanar patch are rounded a
// hair off the plane, and the contour integral of a coplanar polygon around x is the whole
// hemisphere, F = 1 (found by fuzzing: duplicated triangles gave form-factor rows summing to 4,
// then negative or infinite radiosity). A patch that close to the plane is seen at a grazing
// angle unless it is as close to x as the rounding itself.
double max_abs(const D3& a) { return std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)}); }
bool corner_in_front(const D3& p, const D3& n, const D3* corners) {
  constexpr double kRounding = 1e-6;
  const double scale = std::max({max_abs(p), max_abs(corners[0]), max_abs(corners[1]), max_abs(corners[2])});
  const double threshold = kRounding * scale * norm3(n);
  for (int c = 0; c < 3; ++c) {
    if (dot3(n, sub(corners[c], p)) > threshold) return true;
  }
  return false;
}

double form_factor_to_polygon(const D3& x, const D3& n, const D3* poly, int m) {
  const D3 source_normal = cross3(sub(poly[1], poly[0]), sub(poly[2], poly[0]));
  if (!(dot3(source_normal, sub(x, poly[0])) > 0.0)) return 0.0;  // x behind or in the source's plane
  D3 clipped[kMaxClipped];
  const int count = clip_to_half_space(x, n, poly, m, clipped);
  return count < 3 ? 0.0 : contour_integral(x, n, clipped, count);
}

}  // namespace

const std::vector<QuadraturePoint>& triangle_rule(int order) {
  static const std::vector<QuadraturePoint> one = {{1.0 / 3, 1.0 / 3, 1.0 / 3, 1.0}};
  static const std::vector<QuadraturePoint> three = {  // degree 2 (Strang-Fix)
      {2.0 / 3, 1.0 / 6, 1.0 / 6, 1.0 / 3}, {1.0 / 6, 2.0 / 3, 1.0 / 6, 1.0 / 3}, {1.0 / 6, 1.0 / 6, 2.0 / 3, 1.0 / 3}};
  static const std::vector<QuadraturePoint> seven = [] {  // degree 5 (Radon)
    const double s = std::sqrt(15.0);
    const double a = (6.0 - s) / 21.0, b = (6.0 + s) / 21.0;
    const double wa = (155.0 - s) / 1200.0, wb = (155.0 + s) / 1200.0;
    return std::vector<QuadraturePoint>{{1.0 / 3, 1.0 / 3, 1.0 / 3, 9.0 / 40}, {a, a, 1 - 2 * a, wa},
                                        {a, 1 - 2 * a, a, wa},           {1 - 2 * a, a, a, wa},
                                        {b, b, 1 - 2 * b, wb},           {b, 1 - 2 * b, b, wb},
                                        {1 - 2 * b, b, b, wb}};
  }();
  switch (order) {
    case 1:
      return one;
    case 3:
      return three;
    case 7:
      return seven;
    default:
      throw std::invalid_argument("quadrature must be 1, 3 or 7 points");
  }
}

double point_polygon_form_factor(const Vec3& x, const Vec3& n, const std::vector<Vec3>& polygon) {
  if (polygon.size() < 3 || polygon.size() > kMaxClipped / 2) {
    throw std::invalid_argument("polygon needs 3 to 8 vertices");
  }
  std::array<D3, kMaxClipped> poly{};
  for (size_t k = 0; k < polygon.size(); ++k) poly[k] = to_d3(polygon[k]);
  const D3 nd = to_d3(n);
  const double len = norm3(nd);
  if (!(len > 0.0)) throw std::invalid_argument("normal must be non-zero");
  return form_factor_to_polygon(to_d3(x), {nd.x / len, nd.y / len, nd.z / len}, poly.data(),
                                static_cast<int>(polygon.size()));
}

bool some_corner_in_front(const Vec3& p, const Vec3& n, const Vec3 corners[3]) {
  const D3 c[3] = {to_d3(corners[0]), to_d3(corners[1]), to_d3(corners[2])};
  return corner_in_front(to_d3(p), to_d3(n), c);
}

double point_triangle_form_factor(const Vec3& x, const Vec3& n, const Vec3 triangle[3]) {
  const D3 poly[3] = {to_d3(triangle[0]), to_d3(triangle[1]), to_d3(triangle[2])};
  return form_factor_to_polygon(to_d3(x), to_d3(n), poly, 3);
}

namespace {

struct Corners {
  D3 v[3];
};

struct Row {
  std::vector<uint32_t> cols;
  std::vector<float> vals;
};

struct RowCounters {
  uint64_t tested = 0, facing = 0, rays = 0, skipped = 0;
};

// Row i of F: the quadrature rule over receiver patch i of exact point-to-polygon form factors
// to each source patch j, each point's kernel times the fraction of stratified shadow rays to j
// that arrive (none in a convex enclosure, where every facing pair sees each other).
class RowIntegrator {
 public:
  RowIntegrator(const Scene& patches, const FormFactorOptions& options, bool unoccluded, const RenderControl& control)
      : patches_(patches),
        options_(options),
        control_(control),
        rule_(triangle_rule(options.quadrature)),
        unoccluded_(unoccluded),
        sqrt_rays_(static_cast<int>(std::lround(std::sqrt(options.shadow_rays)))),
        square_strata_(sqrt_rays_ * sqrt_rays_ == options.shadow_rays),
        tri_(patches.triangle_count()) {
    for (uint32_t i = 0; i < tri_.size(); ++i) {
      for (int c = 0; c < 3; ++c) tri_[i].v[c] = to_d3(patches.vertex(i, c));
    }
  }

  size_t rule_size() const { return rule_.size(); }

  // points, kernel: the caller's workspace of rule_size() entries.
  void compute(uint32_t i, std::vector<D3>& points, std::vector<double>& kernel, Row& row,
               RowCounters& counters) const {
    const Corners& ti = tri_[i];
    const D3 ni = to_d3(patches_.normal(i));
    for (size_t k = 0; k < rule_.size(); ++k) {
      const QuadraturePoint& q = rule_[k];
      points[k] = {q.b0 * ti.v[0].x + q.b1 * ti.v[1].x + q.b2 * ti.v[2].x,
                   q.b0 * ti.v[0].y + q.b1 * ti.v[1].y + q.b2 * ti.v[2].y,
                   q.b0 * ti.v[0].z + q.b1 * ti.v[1].z + q.b2 * ti.v[2].z};
    }
    for (uint32_t j = 0; j < tri_.size() && !control_.cancelled(); ++j) {
      if (j == i) continue;  // a planar patch does not see itself
      const Corners& tj = tri_[j];
      // Exact culls: the planes are shared by all points of each patch.
      if (!corner_in_front(ti.v[0], ni, tj.v)) continue;  // j behind or in i's plane
      const D3 nj = cross3(sub(tj.v[1], tj.v[0]), sub(tj.v[2], tj.v[0]));
      if (!corner_in_front(tj.v[0], nj, ti.v)) continue;  // i behind or in j's plane
      ++counters.tested;
      double unoccluded_value = 0.0;
      for (size_t k = 0; k < rule_.size(); ++k) {
        kernel[k] = form_factor_to_polygon(points[k], ni, tj.v, 3);
        unoccluded_value += rule_[k].weight * kernel[k];
      }
      if (!(unoccluded_value > 0.0)) continue;
      ++counters.facing;
      const double value = visible_value(i, j, unoccluded_value, points, kernel, counters);
      if (value > options_.min_value && value > 0.0) {
        row.cols.push_back(j);
        row.vals.push_back(static_cast<float>(value));
      }
    }
  }

 private:
  // F_ij with visibility: the unoccluded value, or the rule's sum of kernels times visible fractions.
  double visible_value(uint32_t i, uint32_t j, double unoccluded_value, const std::vector<D3>& points,
                       const std::vector<double>& kernel, RowCounters& counters) const {
    if (options_.shadow_rays <= 0) return unoccluded_value;
    if (unoccluded_) {
      for (size_t k = 0; k < rule_.size(); ++k) {
        if (kernel[k] > 0.0) counters.skipped += static_cast<uint64_t>(options_.shadow_rays);
      }
      return unoccluded_value;
    }
    Pcg32 rng(hash_combine(options_.seed, i), j);
    double value = 0.0;
    for (size_t k = 0; k < rule_.size(); ++k) {
      if (!(kernel[k] > 0.0)) continue;
      const Vec3 x(static_cast<float>(points[k].x), static_cast<float>(points[k].y), static_cast<float>(points[k].z));
      const int visible = visible_rays(x, patches_.normal(i), i, j, rng);
      counters.rays += static_cast<uint64_t>(options_.shadow_rays);
      value += rule_[k].weight * kernel[k] * visible / options_.shadow_rays;
    }
    return value;
  }

  // How many of shadow_rays stratified points on source j (a jittered grid in the unit square)
  // x, on receiver i with normal n, sees.
  int visible_rays(const Vec3& x, const Vec3& n, uint32_t i, uint32_t j, Pcg32& rng) const {
    int visible = 0;
    for (int s = 0; s < options_.shadow_rays; ++s) {
      if ((s & 255) == 255 && control_.cancelled()) break;
      Point2 u{rng.next_float(), rng.next_float()};
      if (square_strata_) {
        u = {(static_cast<float>(s % sqrt_rays_) + u.u) / static_cast<float>(sqrt_rays_),
             (static_cast<float>(s / sqrt_rays_) + u.v) / static_cast<float>(sqrt_rays_)};
      } else {
        u.u = (static_cast<float>(s) + u.u) / static_cast<float>(options_.shadow_rays);
      }
      const Point2 b = shadow_ray_target(u);
      const Vec3 y =
          patches_.vertex(j, 0) * (1.f - b.u - b.v) + patches_.vertex(j, 1) * b.u + patches_.vertex(j, 2) * b.v;
      visible += patches_.visible(x, n, y, j, i) ? 1 : 0;
    }
    return visible;
  }

  const Scene& patches_;
  const FormFactorOptions& options_;
  const RenderControl& control_;  // checked per pair and every 256 shadow rays: a row can take long
  const std::vector<QuadraturePoint>& rule_;
  bool unoccluded_;
  int sqrt_rays_;
  bool square_strata_;
  std::vector<Corners> tri_;
};

// The first rows to compute: all, or those of patches that reflect and (when given) receive.
std::vector<uint32_t> first_rows(uint32_t n, const FormFactorRows* wanted) {
  std::vector<uint32_t> todo;
  for (uint32_t i = 0; i < n; ++i) {
    const bool scatters = !wanted || wanted->scatters[i];
    const bool receives = !wanted || wanted->receivers.empty() || wanted->receivers[i];
    if (scatters && receives) todo.push_back(i);
  }
  return todo;
}

// The next wave of view-only rows: patches first seen from this wave's rows that reflect (in
// row order, so the waves do not depend on the schedule); marks them important.
std::vector<uint32_t> next_wave(const std::vector<uint32_t>& todo, const std::vector<Row>& rows,
                                const FormFactorRows& wanted, std::vector<uint8_t>& important) {
  std::vector<uint32_t> next;
  for (const uint32_t i : todo) {
    for (const uint32_t j : rows[i].cols) {
      if (important[j]) continue;
      important[j] = 1;
      if (wanted.scatters[j]) next.push_back(j);
    }
  }
  return next;
}

// The rows as one CSR matrix, freeing each row as it goes (rows can be large).
CsrMatrix to_csr(std::vector<Row>& rows) {
  const auto n = static_cast<uint32_t>(rows.size());
  CsrMatrix F;
  F.n = n;
  F.indptr.assign(n + 1, 0);
  for (uint32_t i = 0; i < n; ++i) F.indptr[i + 1] = F.indptr[i] + rows[i].cols.size();
  F.indices.reserve(F.indptr[n]);
  F.values.reserve(F.indptr[n]);
  for (Row& r : rows) {
    F.indices.insert(F.indices.end(), r.cols.begin(), r.cols.end());
    F.values.insert(F.values.end(), r.vals.begin(), r.vals.end());
    r = Row{};
  }
  return F;
}

}  // namespace

CsrMatrix compute_form_factors(const Scene& patches, const FormFactorOptions& options, RenderControl& control,
                               FormFactorStats& stats, const FormFactorRows* wanted) {
  if (options.shadow_rays < 0) throw std::invalid_argument("shadow_rays must be >= 0");
  require_diffuse_reflectors(patches, "radiosity form factors");
  require_surface_emitters(patches, "radiosity form factors");
  const auto n = static_cast<uint32_t>(patches.triangle_count());
  if (wanted && (wanted->scatters.size() != n || (!wanted->receivers.empty() && wanted->receivers.size() != n))) {
    throw std::invalid_argument("scatters and receivers need one entry per patch");
  }
  const RowIntegrator integrator(patches, options, options.skip_unneeded && patches.features().convex_enclosure,
                                 control);
  control.total.store(n);
  const Stopwatch start;
  std::vector<Row> rows(n);
  std::atomic<uint64_t> tested{0}, facing{0}, rays{0}, rays_skipped{0};
  std::vector<uint32_t> todo = first_rows(n, wanted);
  std::vector<uint8_t> important;
  if (wanted && !wanted->receivers.empty()) important = wanted->receivers;
  uint64_t computed = 0;
  constexpr size_t kRowsPerTask = 16;
  while (!todo.empty() && !control.cancelled()) {
    parallel_for_each_index(options.threads, (todo.size() + kRowsPerTask - 1) / kRowsPerTask, [&](size_t task) {
      RowCounters local;
      std::vector<D3> points(integrator.rule_size());
      std::vector<double> kernel(integrator.rule_size());
      for (size_t r = task * kRowsPerTask; r < std::min(todo.size(), (task + 1) * kRowsPerTask) && !control.cancelled();
           ++r) {
        integrator.compute(todo[r], points, kernel, rows[todo[r]], local);
        control.done.fetch_add(1, std::memory_order_relaxed);
      }
      tested.fetch_add(local.tested);
      facing.fetch_add(local.facing);
      rays.fetch_add(local.rays);
      rays_skipped.fetch_add(local.skipped);
    });
    computed += todo.size();
    if (important.empty()) break;
    todo = next_wave(todo, rows, *wanted, important);
  }
  CsrMatrix F = to_csr(rows);
  stats.pairs_tested = tested.load();
  stats.pairs_facing = facing.load();
  stats.rays = rays.load();
  stats.rays_skipped = rays_skipped.load();
  stats.rows_computed = computed;
  stats.important = important.empty() ? n : static_cast<uint64_t>(std::count(important.begin(), important.end(), 1));
  stats.seconds = start();
  stats.interrupted = control.cancelled();
  if (!stats.interrupted) control.done.store(n);
  return F;
}

}  // namespace dualight
