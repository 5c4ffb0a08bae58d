#include "radiosity/hierarchical.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/stopwatch.h"
#include "core/triangle_grid.h"
#include "radiosity/diffuse_only.h"
#include "radiosity/form_factors.h"

namespace dualight {

namespace {

Vec3 midpoint(const Vec3& a, const Vec3& b) { return (a + b) * 0.5f; }

Vec3 point_in(const Vec3 v[3], float b1, float b2) { return v[0] * (1.f - b1 - b2) + v[1] * b1 + v[2] * b2; }

// Groups link indices by a key (receiver or source) into CSR-like offsets.
void group_links(size_t n_elements, size_t n_links, const std::vector<uint32_t>& key,
                 std::vector<uint32_t>& offsets, std::vector<uint32_t>& order) {
  offsets.assign(n_elements + 1, 0);
  for (size_t l = 0; l < n_links; ++l) ++offsets[key[l] + 1];
  std::partial_sum(offsets.begin(), offsets.end(), offsets.begin());
  order.resize(n_links);
  std::vector<uint32_t> next(offsets.begin(), offsets.end() - 1);
  for (size_t l = 0; l < n_links; ++l) order[next[key[l]]++] = static_cast<uint32_t>(l);
}

}  // namespace

HierarchicalSolver::HierarchicalSolver(const Scene& scene, ReceiverSamples receiver, HierarchicalOptions options,
                                       RenderControl* control, const std::vector<Color>& albedo)
    : scene_(scene),
      receiver_(std::move(receiver)),
      options_(options),
      first_shot_(scene, options.first_shot_points, options.env_strata) {
  if (!(options_.epsilon > 0.0)) throw std::invalid_argument("epsilon must be > 0");
  if (options_.shadow_rays < 0) throw std::invalid_argument("shadow_rays must be >= 0");
  if (options_.sweeps < 1) throw std::invalid_argument("sweeps must be >= 1");
  require_diffuse_reflectors(scene, "hierarchical radiosity");
  roots_ = static_cast<uint32_t>(scene.triangle_count());
  if (!albedo.empty() && albedo.size() != roots_) {
    throw std::invalid_argument("albedo must give one colour per triangle");
  }
  for (const Color& a : albedo) {
    for (int c = 0; c < 3; ++c) {
      if (!(a[c] >= 0.f && a[c] <= 1.f)) throw std::invalid_argument("albedo must lie in [0, 1]");
    }
  }
  double largest = 0.0;
  elements_.reserve(roots_);
  for (uint32_t t = 0; t < roots_; ++t) {
    Element e;
    for (int c = 0; c < 3; ++c) e.v[c] = scene.vertex(t, c);
    e.normal = scene.normal(t);
    e.area = scene.area(t);
    e.root = t;
    const Color rho = albedo.empty() ? diffuse_reflectance(scene.material(t).bsdf) : albedo[t];
    for (int c = 0; c < 3; ++c) e.rho[c] = rho[c];
    const Emitter* emitter = scene.emitter_at(t);
    emission_varies_ = emission_varies_ || (emitter != nullptr && std::get<AreaEmitter>(*emitter).texture != nullptr);
    largest = std::max(largest, e.area);
    elements_.push_back(e);
  }
  emission_varies_ = emission_varies_ || !first_shot_.empty();
  // Progress: the roots' first shot (when there is one), then link_roots' rows.
  if (control != nullptr) control->total.store(first_shot_.empty() ? roots_ : 2 * uint64_t{roots_});
  set_emission(0, control, control != nullptr && !first_shot_.empty() ? &control->done : nullptr);
  for (const Element& e : elements_) {
    emitted_radiosity_max_ = std::max(emitted_radiosity_max_, e.E[0] * kLuminanceWeights[0] +
                                                                  e.E[1] * kLuminanceWeights[1] +
                                                                  e.E[2] * kLuminanceWeights[2]);
  }
  if (options_.min_area <= 0.0) options_.min_area = 1e-4 * largest;
  for (size_t k = 0; k < receiver_.prim.size(); ++k) {
    if (receiver_.prim[k] >= roots_) throw std::invalid_argument("receiver sample names a missing triangle");
  }

  link_roots(control);
  assign_receiver();
}

// Initial links between every pair of input triangles that face each other and see each other.
void HierarchicalSolver::link_roots(RenderControl* control) {
  std::vector<std::vector<Link>> per_root(roots_);
  std::atomic<uint64_t> rays{0}, skipped{0};
  parallel_for_each_index(options_.threads, roots_, [&](size_t i) {
    uint64_t local = 0, local_skipped = 0;
    for (uint32_t j = 0; j < roots_; ++j) {
      if (control != nullptr && (j & 1023) == 0 && control->cancelled()) break;
      if (j == i || !facing(elements_[i], elements_[j])) continue;
      const Link l = make_link(static_cast<uint32_t>(i), j, local, local_skipped);
      if (l.F > 0.f || l.F_oracle > 0.f) per_root[i].push_back(l);
    }
    rays.fetch_add(local);
    skipped.fetch_add(local_skipped);
    if (control != nullptr) control->done.fetch_add(1, std::memory_order_relaxed);
  });
  rays_ += rays.load();
  rays_skipped_ += skipped.load();
  for (auto& v : per_root) links_.insert(links_.end(), v.begin(), v.end());
}

bool HierarchicalSolver::facing(const Element& a, const Element& b) const {
  // Some corner of each lies in front of the other's plane, by more than rounding.
  return some_corner_in_front(a.v[0], a.normal, b.v) && some_corner_in_front(b.v[0], b.normal, a.v);
}

HierarchicalSolver::Link HierarchicalSolver::make_link(uint32_t receiver, uint32_t source, uint64_t& rays,
                                                      uint64_t& rays_skipped) const {
  const Element& r = elements_[receiver];
  const Element& s = elements_[source];
  // Receiver-side 7-point rule (degree 5, Radon), exact contour integral over the source, each
  // point weighted by its own visibility of the source: kernel and visibility are correlated
  // across a partly hidden pair (a doorway), so F_unoccluded times one visible fraction for the
  // whole pair is biased.
  const std::vector<QuadraturePoint>& rule = triangle_rule(7);
  Vec3 points[7];
  double kernel[7];
  double F = 0.0;
  for (int k = 0; k < 7; ++k) {
    points[k] = point_in(r.v, static_cast<float>(rule[k].b1), static_cast<float>(rule[k].b2));
    kernel[k] = rule[k].weight * point_triangle_form_factor(points[k], r.normal, s.v);
    F += kernel[k];
  }
  Link link{receiver, source, static_cast<float>(F), static_cast<float>(F), static_cast<float>(F), {}, {}};
  for (int k = 0; k < 7; ++k) link.F_point[k] = static_cast<float>(kernel[k] / rule[k].weight);
  if (!(F > 0.0) || options_.shadow_rays == 0) return link;
  if (options_.skip_unneeded && scene_.features().convex_enclosure) {
    // Facing elements of a convex enclosure always see each other (scene_features.h).
    for (int k = 0; k < 7; ++k) rays_skipped += kernel[k] > 0.0 ? 2 * static_cast<uint64_t>(options_.shadow_rays) : 0;
    return link;
  }
  Pcg32 rng(hash_combine(options_.seed, (static_cast<uint64_t>(receiver) << 32) | source), iteration_);
  const int n = options_.shadow_rays;  // per receiver point
  // Optionally scales `point_values` (the point form factors) by each point's visible fraction.
  auto visible_estimate = [&](float* point_values) {
    double estimate = 0.0;
    for (int k = 0; k < 7; ++k) {
      if (!(kernel[k] > 0.0)) continue;
      int visible = 0;
      for (int m = 0; m < n; ++m) {
        const Point2 u = shadow_ray_target({(m + rng.next_float()) / n, rng.next_float()});
        const Vec3 y = point_in(s.v, u.u, u.v);
        visible += scene_.visible(points[k], r.normal, y, s.root, r.root) ? 1 : 0;
      }
      rays += static_cast<uint64_t>(n);
      estimate += kernel[k] * visible / n;
      if (point_values != nullptr) point_values[k] *= static_cast<float>(visible) / static_cast<float>(n);
    }
    return estimate;
  };
  link.F = static_cast<float>(visible_estimate(nullptr));
  link.F_oracle = static_cast<float>(visible_estimate(link.F_point));
  return link;
}

// pi x the mean radiance the element's root emits over it: its emitter's Le, or the mean of its
// radiance texture over the element (the corners' surface coordinates from their barycentrics
// in the root).
Color HierarchicalSolver::mean_emitted_radiance(const Element& e) const {
  const Emitter* emitter = scene_.emitter_at(e.root);  // a triangle's emitter is an AreaEmitter
  if (emitter == nullptr) return Color(0.f);
  const AreaEmitter& area = std::get<AreaEmitter>(*emitter);
  if (area.texture == nullptr || e.parent < 0) return area.Le;  // a root: the scene's mean
  Point2 uv[3];
  for (int k = 0; k < 3; ++k) uv[k] = surface_uv(area, barycentrics(area.p0, area.p1, area.p2, e.v[k]));
  return mean_rgb_over_triangle(*area.texture, uv[0], uv[1], uv[2]);
}

void HierarchicalSolver::set_emission(size_t first, const RenderControl* control, std::atomic<uint64_t>* done) {
  const size_t end = elements_.size();
  parallel_for_each_index(options_.threads, end - first, [&](size_t k) {
    if (control != nullptr && control->cancelled()) return;
    Element& e = elements_[first + k];
    Pcg32 rng(options_.seed ^ 0x51a7'f00d'5eedull, first + k);
    const Color H = first_shot_.mean_irradiance(e.v, e.normal, rng);
    const Color Le = mean_emitted_radiance(e);
    for (int c = 0; c < 3; ++c) e.E[c] = kPi * Le[c] + e.rho[c] * H[c];
    if (done != nullptr) done->fetch_add(1, std::memory_order_relaxed);
  });
}

void HierarchicalSolver::subdivide(uint32_t e) {
  if (elements_[e].first_child >= 0) return;
  const Element parent = elements_[e];
  const Vec3 m01 = midpoint(parent.v[0], parent.v[1]), m12 = midpoint(parent.v[1], parent.v[2]),
             m20 = midpoint(parent.v[2], parent.v[0]);
  const Vec3 corners[4][3] = {
      {parent.v[0], m01, m20}, {m01, parent.v[1], m12}, {m20, m12, parent.v[2]}, {m01, m12, m20}};
  elements_[e].first_child = static_cast<int32_t>(elements_.size());
  for (const auto& c : corners) {
    Element child = parent;
    std::copy(c, c + 3, child.v);
    child.area = parent.area / 4.0;
    child.first_child = -1;
    child.parent = static_cast<int32_t>(e);
    std::fill(child.Bg, child.Bg + 3, 0.0);
    std::fill(child.Wg, child.Wg + 3, 0.0);
    child.R = 0.0;
    elements_.push_back(child);
  }
}

uint32_t HierarchicalSolver::leaf_at(uint32_t root, float b1, float b2) const {
  uint32_t e = root;
  float b0 = 1.f - b1 - b2;
  while (elements_[e].first_child >= 0) {
    const uint32_t first = static_cast<uint32_t>(elements_[e].first_child);
    float c0, c1, c2;
    uint32_t child;
    if (b0 >= 0.5f) {
      child = first;
      c1 = 2 * b1, c2 = 2 * b2, c0 = 1 - c1 - c2;
    } else if (b1 >= 0.5f) {
      child = first + 1;
      c0 = 2 * b0, c2 = 2 * b2, c1 = 1 - c0 - c2;
    } else if (b2 >= 0.5f) {
      child = first + 2;
      c0 = 2 * b0, c1 = 2 * b1, c2 = 1 - c0 - c1;
    } else {  // the middle triangle (m01, m12, m20)
      child = first + 3;
      c0 = 1 - 2 * b2, c1 = 1 - 2 * b0, c2 = 1 - 2 * b1;
    }
    e = child, b0 = c0, b1 = c1, b2 = c2;
  }
  return e;
}

void HierarchicalSolver::assign_receiver() {
  for (Element& e : elements_) e.R = 0.0;
  for (size_t k = 0; k < receiver_.prim.size(); ++k) {
    elements_[leaf_at(receiver_.prim[k], receiver_.b1[k], receiver_.b2[k])].R += receiver_.weight;
  }
  for (Element& e : elements_) e.R /= e.area;  // density
}

void HierarchicalSolver::push_pull_radiosity(uint32_t e, const double down[3]) {
  Element& el = elements_[e];
  const double up[3] = {el.Bg[0] + down[0], el.Bg[1] + down[1], el.Bg[2] + down[2]};
  if (el.first_child < 0) {
    for (int c = 0; c < 3; ++c) el.B[c] = el.E[c] + up[c];
    return;
  }
  double sum[3] = {0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const uint32_t child = static_cast<uint32_t>(elements_[e].first_child + k);
    push_pull_radiosity(child, up);
    for (int c = 0; c < 3; ++c) sum[c] += elements_[child].B[c] * elements_[child].area;
  }
  Element& again = elements_[e];
  for (int c = 0; c < 3; ++c) again.B[c] = sum[c] / again.area;
}

void HierarchicalSolver::push_pull_importance(uint32_t e, const double down[3]) {
  Element& el = elements_[e];
  const double up[3] = {el.Wg[0] + down[0], el.Wg[1] + down[1], el.Wg[2] + down[2]};
  if (el.first_child < 0) {
    for (int c = 0; c < 3; ++c) el.W[c] = el.R + up[c];
    return;
  }
  double sum[3] = {0, 0, 0};
  for (int k = 0; k < 4; ++k) {
    const uint32_t child = static_cast<uint32_t>(elements_[e].first_child + k);
    push_pull_importance(child, up);
    for (int c = 0; c < 3; ++c) sum[c] += elements_[child].W[c] * elements_[child].area;
  }
  Element& again = elements_[e];
  for (int c = 0; c < 3; ++c) again.W[c] = sum[c] / again.area;
}

// The links the oracle flags for refinement [HSA91 sec. 4; SAS92 sec. 4]: their error bound
// (BF) or their error weighted by importance exceeds epsilon times the brightest emission or
// the measurement, and their larger element can still be split. Then the links that make what
// their receiver gathers vary across it by too much (links_to_push_down) are pushed down to the
// receiver's children.
std::vector<HierarchicalSolver::Refinement> HierarchicalSolver::flag_links(const RenderControl* control) const {
  double primal[3], dual[3];
  measurements(primal, dual);
  const double measurement = primal[0] + primal[1] + primal[2];
  const std::vector<char> push_down = links_to_push_down(measurement, control);
  std::vector<Refinement> to_refine;
  for (uint32_t l = 0; l < links_.size(); ++l) {
    const Link& link = links_[l];
    const Element& r = elements_[link.receiver];
    const Element& s = elements_[link.source];
    // Both directional form factors, as in [HSA91]: a small source next to a large receiver
    // has a small F_ij but makes the receiver's irradiance vary strongly across it (F_ji is
    // large), which averaging over the receiver would miss.
    // A partly visible link (a shadow boundary crosses it) is judged by its unoccluded form
    // factor: its visibility varies across the elements, and sampling the source uniformly
    // by area misses how that variation correlates with the kernel [HSA91, SAS92].
    const bool partial = link.F_oracle > 0.f && link.F_oracle < 0.999f * link.F_unoccluded;
    const double F_judged = partial ? link.F_unoccluded : link.F_oracle;
    const double F_max = std::max<double>(F_judged, F_judged * r.area / s.area);
    double q = 0.0, threshold = 0.0;
    if (options_.oracle == RefinementOracle::BF) {
      // Bound on the radiosity error this link leaves at the receiver's points.
      for (int c = 0; c < 3; ++c) q += kLuminanceWeights[c] * F_max * s.B[c];
      threshold = options_.epsilon * emitted_radiosity_max_;
    } else {
      // That error weighted by how much the receiver matters for the view, plus the importance
      // error it leaves at the source weighted by the source's radiosity [SAS92]: both are
      // F_max * rho_i * W_i * B_j times an area.
      for (int c = 0; c < 3; ++c) q += F_max * r.rho[c] * r.W[c] * s.B[c] * std::max(r.area, s.area);
      threshold = options_.epsilon * measurement;
    }
    if (q > threshold && std::max(r.area, s.area) / 4.0 >= options_.min_area) {
      to_refine.push_back({l, r.area >= s.area});
    } else if (push_down[l]) {
      to_refine.push_back({l, true});
    }
  }
  return to_refine;
}

// The per-link bounds above do not bound an element's total: each link's error can be under the
// threshold while the errors of many links at a leaf add up with one sign (a leaf in a corner
// gathers more from the adjacent walls than the averages its coarse ancestors' links carry, and
// partial refinement of those links breaks the cancellation a complete set of links at one level
// has). This a-posteriori check evaluates what each element gathers at its own quadrature points
// and, where that strays from the element's average by more than the oracle's threshold (epsilon
// times the brightest emission for BF; for importance, times the measurement once weighted by
// the element's importance and area), flags the links that stray most, until what the rest
// gather strays by at most half the threshold: those are pushed down to the element's children
// [error estimates from the gathered radiosity's variation: Lischinski, Smits and Greenberg
// 1994; Bekaert and Willems 1996]. Returns a flag per link (fewer once `control` is cancelled).
std::vector<char> HierarchicalSolver::links_to_push_down(double measurement, const RenderControl* control) const {
  std::vector<uint32_t> key(links_.size());
  for (size_t l = 0; l < links_.size(); ++l) key[l] = links_[l].receiver;
  std::vector<uint32_t> offsets, order;
  group_links(elements_.size(), links_.size(), key, offsets, order);
  const double threshold =
      options_.epsilon * (options_.oracle == RefinementOracle::BF ? emitted_radiosity_max_ : measurement);
  std::vector<char> push(links_.size(), 0);
  constexpr size_t kChunk = 256;
  parallel_for_each_index(options_.threads, (elements_.size() + kChunk - 1) / kChunk, [&](size_t chunk) {
    std::vector<std::array<double, 7>> deviation;
    if (control != nullptr && control->cancelled()) return;
    for (size_t e = chunk * kChunk; e < std::min(elements_.size(), (chunk + 1) * kChunk); ++e) {
      const size_t count = offsets[e + 1] - offsets[e];
      if (count == 0 || elements_[e].area / 4.0 < options_.min_area) continue;
      const uint32_t* links = &order[offsets[e]];
      gathered_deviations(static_cast<uint32_t>(e), links, count, deviation);
      for (const size_t i : strays_to_push_down(deviation, threshold)) push[links[i]] = 1;
    }
  });
  return push;
}

// For each of the receiver's links, what it gathers at the receiver's 7 quadrature points minus
// its average over the receiver: the point form factor times the oracle's visible fraction from
// that point (both kept from the link's construction) times rho_i B_j, the channels weighted as the oracle weighs them
// (luminance for BF; importance density times area for importance).
void HierarchicalSolver::gathered_deviations(uint32_t receiver, const uint32_t* links, size_t count,
                                             std::vector<std::array<double, 7>>& deviation) const {
  const Element& r = elements_[receiver];
  const std::vector<QuadraturePoint>& rule = triangle_rule(7);
  double weight[3];
  for (int c = 0; c < 3; ++c) {
    weight[c] = r.rho[c] * (options_.oracle == RefinementOracle::BF ? kLuminanceWeights[c] : r.W[c] * r.area);
  }
  deviation.assign(count, {});
  for (size_t i = 0; i < count; ++i) {
    const Link& link = links_[links[i]];
    const Element& s = elements_[link.source];
    const double transported = weight[0] * s.B[0] + weight[1] * s.B[1] + weight[2] * s.B[2];
    for (int k = 0; k < 7; ++k) deviation[i][k] = transported * link.F_point[k];
    double mean = 0.0;
    for (int k = 0; k < 7; ++k) mean += rule[k].weight * deviation[i][k];
    for (int k = 0; k < 7; ++k) deviation[i][k] -= mean;
  }
}

// The links to take off a receiver, largest deviation first, until the sum of the remaining
// links' deviations is within half the threshold at every point; none if it is within the
// threshold already.
std::vector<size_t> HierarchicalSolver::strays_to_push_down(const std::vector<std::array<double, 7>>& deviation,
                                                            double threshold) {
  std::array<double, 7> total{};
  for (const auto& d : deviation) {
    for (int k = 0; k < 7; ++k) total[k] += d[k];
  }
  const auto largest = [](const std::array<double, 7>& d) {
    double m = 0.0;
    for (const double x : d) m = std::max(m, std::abs(x));
    return m;
  };
  std::vector<size_t> out;
  if (largest(total) <= threshold) return out;
  std::vector<size_t> by_size(deviation.size());
  std::iota(by_size.begin(), by_size.end(), size_t{0});
  std::sort(by_size.begin(), by_size.end(),
            [&](size_t a, size_t b) { return largest(deviation[a]) > largest(deviation[b]); });
  for (const size_t i : by_size) {
    if (largest(total) <= 0.5 * threshold || largest(deviation[i]) == 0.0) break;
    out.push_back(i);
    for (int k = 0; k < 7; ++k) total[k] -= deviation[i][k];
  }
  return out;
}

// Splits the flagged end of each flagged link (at most max_links / 3 of them) and links its
// children in its place; fills st.links_refined and st.link_limit.
// Cancelled (`control`), it keeps the links it had: the split elements stay, as leaves that take
// their parents' gathered radiosity, and the hierarchy stays consistent.
void HierarchicalSolver::refine_links(std::vector<Refinement> to_refine, HierarchicalStep& st,
                                      const RenderControl* control) {
  // Each refinement adds three links: stop before max_links (BF in a scene where everything
  // emits would otherwise refine until memory runs out).
  const uint64_t room = options_.max_links > links_.size() ? (options_.max_links - links_.size()) / 3 : 0;
  if (to_refine.size() > room) {
    to_refine.resize(room);
    st.link_limit = true;
  }
  // Split the flagged end of each flagged link, then link its children in its place.
  std::vector<Link> kept;
  std::vector<std::pair<uint32_t, uint32_t>> pending;  // (receiver, source) of new links
  std::vector<char> refine(links_.size(), 0);
  for (const Refinement& r : to_refine) refine[r.link] = r.split_receiver ? 2 : 1;
  const size_t first_new = elements_.size();
  for (uint32_t l = 0; l < links_.size(); ++l) {
    const Link link = links_[l];
    if (!refine[l]) {
      kept.push_back(link);
      continue;
    }
    const bool split_receiver = refine[l] == 2;
    const uint32_t split = split_receiver ? link.receiver : link.source;
    subdivide(split);
    const uint32_t first = static_cast<uint32_t>(elements_[split].first_child);
    for (uint32_t k = 0; k < 4; ++k) {
      pending.emplace_back(split_receiver ? first + k : link.receiver, split_receiver ? link.source : first + k);
    }
  }
  if (emission_varies_) set_emission(first_new, control);
  std::vector<Link> created(pending.size());
  std::atomic<uint64_t> rays{0}, skipped{0};
  constexpr size_t kChunk = 256;
  parallel_for_each_index(options_.threads, (pending.size() + kChunk - 1) / kChunk, [&](size_t chunk) {
    uint64_t local = 0, local_skipped = 0;
    if (control != nullptr && control->cancelled()) return;
    for (size_t k = chunk * kChunk; k < std::min(pending.size(), (chunk + 1) * kChunk); ++k) {
      const auto [r, s] = pending[k];
      created[k] = facing(elements_[r], elements_[s]) ? make_link(r, s, local, local_skipped)
                                                      : Link{r, s, 0.f, 0.f, 0.f, {}, {}};
    }
    rays.fetch_add(local);
    skipped.fetch_add(local_skipped);
  });
  rays_ += rays.load();
  rays_skipped_ += skipped.load();
  if (control != nullptr && control->cancelled()) return;
  for (const Link& l : created) {
    // A link the oracle sees as occluded is never refined: dropping it when the transport
    // estimate is 0 too loses nothing.
    if (l.F > 0.f || l.F_oracle > 0.f) kept.push_back(l);
  }
  links_.swap(kept);
  st.links_refined = to_refine.size();
}

// A link carries its source's radiosity as its receiver sees it: a source's average is what the
// receiver sees only where the kernel is flat across it. The average over-weights what the
// receiver sees little of (a source's far part, the part a partly hidden link does not see) and
// leaves a bias of one sign in every gather, within each element's error bound but adding up
// over an enclosure (the cube lost 4 % of its energy at BF 1e-3). So where the source has
// children, the link carries theirs, each weighted by its share of the link's form factor:
// exact point form factors from the receiver's 7 points, and for a partly hidden link only from
// the points whose ray to the child's centroid arrives.
HierarchicalSolver::SourceView HierarchicalSolver::source_view(const Link& link, uint64_t& rays) const {
  SourceView view;
  const Element& s = elements_[link.source];
  if (s.first_child < 0) return view;
  view.share[0] = kNone;
  if (!(link.F_unoccluded > 0.f)) return view;
  const Element& r = elements_[link.receiver];
  const bool partial = link.F_oracle < 0.999f * link.F_unoccluded;
  const std::vector<QuadraturePoint>& rule = triangle_rule(7);
  Vec3 points[7];
  for (int k = 0; k < 7; ++k) points[k] = point_in(r.v, static_cast<float>(rule[k].b1), static_cast<float>(rule[k].b2));
  double seen[4] = {0, 0, 0, 0}, total = 0.0;
  for (int q = 0; q < 4; ++q) {
    const Element& child = elements_[static_cast<size_t>(s.first_child + q)];
    const Vec3 centroid = (child.v[0] + child.v[1] + child.v[2]) / 3.f;
    for (int k = 0; k < 7; ++k) {
      const Vec3& x = points[k];
      const double kernel = rule[k].weight * point_triangle_form_factor(x, r.normal, child.v);
      if (!(kernel > 0.0)) continue;
      if (partial) ++rays;
      if (!partial || scene_.visible(x, r.normal, centroid, child.root, r.root)) seen[q] += kernel;
    }
    total += seen[q];
  }
  if (!(total > 0.0)) return view;
  for (int q = 0; q < 4; ++q) view.share[q] = static_cast<float>(seen[q] / total);
  return view;
}

// source_view of every link whose source has gained children since it was last seen (fewer once
// `control` is cancelled: the rest carry averages until the next step).
void HierarchicalSolver::update_source_views(const RenderControl* control) {
  std::atomic<uint64_t> rays{0};
  constexpr size_t kChunk = 1024;
  parallel_for_each_index(options_.threads, (links_.size() + kChunk - 1) / kChunk, [&](size_t chunk) {
    if (control != nullptr && control->cancelled()) return;
    uint64_t local = 0;
    for (size_t l = chunk * kChunk; l < std::min(links_.size(), (chunk + 1) * kChunk); ++l) {
      Link& link = links_[l];
      if (link.view.share[0] == kNotSeen) link.view = source_view(link, local);
    }
    rays.fetch_add(local);
  });
  rays_ += rays.load();
}

// The radiosity `link` carries: its source's children's, weighted by the link's view of them, or
// the source's own where it has none.
void HierarchicalSolver::seen_radiosity(const Link& link, double seen[3]) const {
  const Element& s = elements_[link.source];
  for (int c = 0; c < 3; ++c) {
    seen[c] = s.B[c];
    if (link.view.share[0] < 0.f) continue;
    seen[c] = 0.0;
    for (int q = 0; q < 4; ++q) seen[c] += link.view.share[q] * elements_[static_cast<size_t>(s.first_child + q)].B[c];
  }
}

// Gathers both systems on the current links and pushes and pulls them through the trees,
// sweep after sweep until the change is within tolerance; returns the last change.
double HierarchicalSolver::solve_links(RenderControl* control) {
  const size_t n_links = links_.size();
  std::vector<uint32_t> by_receiver(n_links), by_source(n_links);
  for (size_t l = 0; l < n_links; ++l) {
    by_receiver[l] = links_[l].receiver;
    by_source[l] = links_[l].source;
  }
  std::vector<uint32_t> r_offsets, r_order, s_offsets, s_order;
  group_links(elements_.size(), n_links, by_receiver, r_offsets, r_order);
  group_links(elements_.size(), n_links, by_source, s_offsets, s_order);
  update_source_views(control);
  // Importance flows back to the children a link sees: entry 4 l + q (child q of link l's
  // source) for the links that see children, grouped by that child.
  std::vector<uint32_t> entries, seen_child;
  for (size_t l = 0; l < n_links; ++l) {
    if (links_[l].view.share[0] < 0.f) continue;
    for (uint32_t q = 0; q < 4; ++q) {
      entries.push_back(static_cast<uint32_t>(4 * l + q));
      seen_child.push_back(static_cast<uint32_t>(elements_[links_[l].source].first_child) + q);
    }
  }
  std::vector<uint32_t> c_offsets, c_order;
  group_links(elements_.size(), entries.size(), seen_child, c_offsets, c_order);
  const double zero[3] = {0, 0, 0};
  double change = 0.0;
  for (int sweep = 0; sweep < options_.sweeps; ++sweep) {
    if (control != nullptr && control->cancelled()) break;
    std::vector<double> before;  // B and W of every element: both systems must settle
    before.reserve(elements_.size() * 6);
    for (const Element& e : elements_) {
      before.insert(before.end(), e.B, e.B + 3);
      before.insert(before.end(), e.W, e.W + 3);
    }
    parallel_for_each_index(options_.threads, (elements_.size() + 1023) / 1024, [&](size_t chunk) {
      for (size_t e = chunk * 1024; e < std::min(elements_.size(), (chunk + 1) * 1024); ++e) {
        Element& el = elements_[e];
        double bg[3] = {0, 0, 0}, wg[3] = {0, 0, 0};
        for (uint32_t k = r_offsets[e]; k < r_offsets[e + 1]; ++k) {  // radiosity arrives at e
          const Link& link = links_[r_order[k]];
          double seen[3];
          seen_radiosity(link, seen);
          for (int c = 0; c < 3; ++c) bg[c] += el.rho[c] * link.F * seen[c];
        }
        for (uint32_t k = s_offsets[e]; k < s_offsets[e + 1]; ++k) {  // importance arrives at e
          const Link& link = links_[s_order[k]];
          if (link.view.share[0] >= 0.f) continue;  // (at its children, below)
          const Element& r = elements_[link.receiver];
          const double F_reverse = r.area * link.F / el.area;
          for (int c = 0; c < 3; ++c) wg[c] += r.rho[c] * F_reverse * r.W[c];
        }
        for (uint32_t k = c_offsets[e]; k < c_offsets[e + 1]; ++k) {  // ... as a seen child
          const uint32_t entry = entries[c_order[k]];
          const Link& link = links_[entry / 4];
          const Element& r = elements_[link.receiver];
          const double F_reverse = r.area * link.F * link.view.share[entry % 4] / el.area;
          for (int c = 0; c < 3; ++c) wg[c] += r.rho[c] * F_reverse * r.W[c];
        }
        std::copy(bg, bg + 3, el.Bg);
        std::copy(wg, wg + 3, el.Wg);
      }
    });
    for (uint32_t root = 0; root < roots_; ++root) {
      push_pull_radiosity(root, zero);
      push_pull_importance(root, zero);
    }
    change = leaf_change(before);
    if (control != nullptr) control->done.fetch_add(1, std::memory_order_relaxed);
    if (change <= options_.tolerance) break;
  }

  return change;
}

HierarchicalStep HierarchicalSolver::step(RenderControl* control) {
  const Stopwatch t0;
  HierarchicalStep st;
  const uint64_t rays_before = rays_, skipped_before = rays_skipped_;
  // Progress: the refinement, then each sweep (the sweeps may end early, at the tolerance).
  if (control != nullptr) control->total.store(static_cast<uint64_t>(options_.sweeps) + 1);
  // Refine (from the second step on: the oracles need a solution).
  if (iteration_ > 0) {
    const size_t elements_before = elements_.size();
    refine_links(flag_links(control), st, control);
    if (elements_.size() != elements_before) assign_receiver();
  }
  if (control != nullptr) control->done.store(1);
  const double change = solve_links(control);
  if (control != nullptr && !control->cancelled()) control->done.store(control->total.load());

  ++iteration_;
  st.iteration = iteration_;
  st.elements = elements_.size();
  st.leaves = static_cast<uint64_t>(std::count_if(elements_.begin(), elements_.end(),
                                                  [](const Element& e) { return e.first_child < 0; }));
  st.links = links_.size();
  st.rays = rays_ - rays_before;
  st.rays_skipped = rays_skipped_ - skipped_before;
  st.memory_bytes = elements_.size() * sizeof(Element) + links_.capacity() * sizeof(Link);
  st.residual = change;
  st.converged = iteration_ > 1 && st.links_refined == 0 && !st.link_limit && !(control && control->cancelled());
  st.seconds = t0();
  return st;
}

double HierarchicalSolver::leaf_change(const std::vector<double>& before) const {
  // Largest change of B and of W in this sweep, each relative to its own largest value.
  double change[2] = {0, 0}, scale[2] = {0, 0};
  for (size_t e = 0; e < elements_.size(); ++e) {
    for (int c = 0; c < 3; ++c) {
      change[0] = std::max(change[0], std::abs(elements_[e].B[c] - before[6 * e + c]));
      scale[0] = std::max(scale[0], std::abs(elements_[e].B[c]));
      change[1] = std::max(change[1], std::abs(elements_[e].W[c] - before[6 * e + 3 + c]));
      scale[1] = std::max(scale[1], std::abs(elements_[e].W[c]));
    }
  }
  double worst = 0.0;
  for (int k = 0; k < 2; ++k) worst = std::max(worst, scale[k] > 0.0 ? change[k] / scale[k] : change[k]);
  return worst;
}

void HierarchicalSolver::measurements(double primal[3], double dual[3]) const {
  for (int c = 0; c < 3; ++c) primal[c] = dual[c] = 0.0;
  for (const Element& e : elements_) {
    if (e.first_child >= 0) continue;
    for (int c = 0; c < 3; ++c) {
      primal[c] += e.area * e.R * e.B[c];
      dual[c] += e.area * e.W[c] * e.E[c];
    }
  }
}

double HierarchicalSolver::link_coverage_error(bool only_facing_roots) const {
  std::vector<std::vector<uint32_t>> incoming(elements_.size());
  for (const Link& l : links_) incoming[l.receiver].push_back(l.source);
  double worst = 0.0;
  std::vector<double> covered(roots_);
  for (uint32_t e = 0; e < elements_.size(); ++e) {
    if (elements_[e].first_child >= 0) continue;
    std::fill(covered.begin(), covered.end(), 0.0);
    for (int32_t a = static_cast<int32_t>(e); a >= 0; a = elements_[a].parent) {
      for (const uint32_t src : incoming[a]) covered[elements_[src].root] += elements_[src].area;
    }
    for (uint32_t r = 0; r < roots_; ++r) {
      if (r == elements_[e].root) continue;
      if (only_facing_roots && !facing(elements_[elements_[e].root], elements_[r])) continue;
      worst = std::max(worst, std::abs(covered[r] / elements_[r].area - 1.0));
    }
  }
  return worst;
}

std::vector<HierarchicalSolver::Leaf> HierarchicalSolver::leaves() const {
  std::vector<uint32_t> incoming(elements_.size(), 0);
  for (const Link& l : links_) ++incoming[l.receiver];
  std::vector<Leaf> out;
  for (uint32_t id = 0; id < elements_.size(); ++id) {
    const Element& e = elements_[id];
    if (e.first_child >= 0) continue;
    Leaf l;
    std::copy(e.v, e.v + 3, l.v);
    l.root = e.root;
    l.area = e.area;
    std::copy(e.B, e.B + 3, l.B);
    std::copy(e.W, e.W + 3, l.W);
    std::copy(e.E, e.E + 3, l.E);
    l.R = e.R;
    l.link_density = 0.0;
    for (int32_t a = static_cast<int32_t>(id); a >= 0; a = elements_[a].parent) {
      l.link_density += incoming[a] / elements_[a].area;
    }
    out.push_back(l);
  }
  return out;
}

std::vector<HierarchicalSolver::LinkView> HierarchicalSolver::links() const {
  std::vector<LinkView> out;
  out.reserve(links_.size());
  for (const Link& l : links_) {
    const Element& r = elements_[l.receiver];
    const Element& s = elements_[l.source];
    out.push_back({r.root, s.root, (r.v[0] + r.v[1] + r.v[2]) / 3.f, (s.v[0] + s.v[1] + s.v[2]) / 3.f, l.F});
  }
  return out;
}

}  // namespace dualight
