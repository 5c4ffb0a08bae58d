// Camera importance and projection, and verify() on subpaths: it must find nothing wrong with
// the walks' own bookkeeping and must notice a tampered density or throughput.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "box_scene.h"
#include "check.h"
#include "lobe_records.h"
#include "core/sampler.h"
#include "pathspace/bdpt_sample.h"
#include "pathspace/path.h"
#include "pathspace/path_tracer.h"
#include "pathspace/path_tracer_lanes.h"
#include "pathspace/mis_weight.h"
#include "pathspace/subpath.h"

using namespace dualight;

namespace {

const PinholeCamera kCamera({0.5f, 0.5f, 0.05f}, {0.5f, 0.5f, 1.f}, {0, 1, 0}, 60.f, 32, 24);

}  // namespace

TEST_CASE("camera_projection_inverts_generate_ray") {
  for (const Point2 xy : {Point2{0.5f, 0.5f}, Point2{31.2f, 3.7f}, Point2{16.f, 12.f}, Point2{7.3f, 23.9f}}) {
    const Ray r = kCamera.generate_ray(xy.u, xy.v);
    Point2 back{};
    CHECK(kCamera.raster_position(r.o + r.d * 3.f, back));
    CHECK_NEAR(back.u, xy.u, 1e-3f);
    CHECK_NEAR(back.v, xy.v, 1e-3f);
  }
  Point2 unused{};
  CHECK(!kCamera.raster_position({0.5f, 0.5f, -1.f}, unused));  // behind
  CHECK(!kCamera.raster_position({5.f, 0.5f, 1.f}, unused));    // outside the field of view
}

TEST_CASE("camera_importance_integrates_to_one_per_pixel") {
  // We = 1 / (A_pixel cos^3): integrate it over one pixel's solid angle numerically.
  const int n = 64;
  double integral = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const float x = 20.f + (i + 0.5f) / n, y = 5.f + (j + 0.5f) / n;
      const Vec3 d00 = kCamera.generate_ray(x - 0.5f / n, y - 0.5f / n).d;
      const Vec3 d11 = kCamera.generate_ray(x + 0.5f / n, y + 0.5f / n).d;
      const Vec3 d01 = kCamera.generate_ray(x - 0.5f / n, y + 0.5f / n).d;
      const Vec3 d10 = kCamera.generate_ray(x + 0.5f / n, y - 0.5f / n).d;
      // Solid angle of the little cell: two spherical triangles, approximated by flat ones.
      const double omega = 0.5 * (length(cross(d10 - d00, d01 - d00)) + length(cross(d10 - d11, d01 - d11)));
      integral += kCamera.importance(kCamera.generate_ray(x, y).d) * omega;
    }
  }
  CHECK_NEAR(integral, 1.0, 1e-3);
  CHECK(kCamera.importance(Vec3(0, 0, -1)) == 0.f);
  const Vec3 w = kCamera.generate_ray(3.f, 4.f).d;
  CHECK_NEAR(kCamera.pdf_w(w) * 32.f * 24.f / kCamera.importance(w), 1.f, 1e-5f);
}

TEST_CASE("verify_accepts_the_walks_and_catches_tampering") {
  const Scene scene = closed_box();
  const WalkLimits limits{8, 1 << 30};
  TraceCounters rays;
  Path path;
  size_t checked = 0;
  for (uint32_t i = 0; i < 200; ++i) {
    IndependentSampler sampler(1, 0, i);
    const bool from_camera = i % 2 == 0;
    if (from_camera) {
      camera_subpath(scene, kCamera, 16.f, 12.f, sampler, limits, path, rays);
    } else {
      light_subpath(scene, sampler, limits, path, rays);
    }
    const PathCheck ok = verify(kCamera, path, from_camera);
    CHECK(ok.off == 0);
    CHECK((ok.pdf_fwd < 1e-4f && ok.pdf_rev < 1e-4f && ok.beta < 1e-4f));
    if (path.size() < 4) continue;
    ++checked;
    Path bad = path;
    bad[2].pdf_fwd *= 1.01f;
    CHECK(verify(kCamera, bad, from_camera).pdf_fwd > 0.009f);
    bad = path;
    bad[1].pdf_rev *= 0.98f;
    CHECK(verify(kCamera, bad, from_camera).pdf_rev > 0.019f);
    bad = path;
    bad[3].beta *= 1.02f;
    CHECK(verify(kCamera, bad, from_camera).beta > 0.019f);
    // Evaluating a subpath in the other transport mode must not matter for diffuse surfaces.
    CHECK(verify(kCamera, path, !from_camera).off == 0);
  }
  CHECK(checked > 50);
}

namespace {

// The closed box with a mirror quad standing in it, so that paths have delta vertices; with
// `lights`, also the emitters without a surface; `open_top` leaves out the box's top (y = 1);
// `quad`: the quad's BSDF, if not the mirror (glass: its back side is inside the glass).
Scene box_with_mirror(std::vector<Emitter> lights = {}, bool open_top = false, Bsdf quad = Mirror{Color(0.9f)}) {
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  std::vector<uint32_t> t = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                             3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
  if (open_top) t.erase(t.begin() + 18, t.begin() + 24);
  std::vector<uint32_t> m(t.size() / 3, 0);
  const auto add = [&](std::initializer_list<float> xyz, uint32_t material) {
    const uint32_t base = static_cast<uint32_t>(p.size() / 3);
    for (const float v : xyz) p.push_back(v);
    for (const uint32_t i : {base, base + 1, base + 2, base, base + 2, base + 3}) t.push_back(i);
    m.push_back(material);
    m.push_back(material);
  };
  add({0.3f, 0.95f, 0.3f, 0.7f, 0.95f, 0.3f, 0.7f, 0.95f, 0.7f, 0.3f, 0.95f, 0.7f}, 1);  // emitter, facing -y
  add({0.2f, 0.1f, 0.8f, 0.8f, 0.1f, 0.8f, 0.8f, 0.7f, 0.6f, 0.2f, 0.7f, 0.6f}, 2);  // tilted mirror
  return Scene(std::move(p), std::move(t), std::move(m),
               {Material{Lambertian{Color(0.6f)}, Color(0.f)}, Material{Lambertian{Color(0.3f)}, Color(4.f)},
                Material{std::move(quad), Color(0.f)}},
               std::move(lights));
}

}  // namespace

namespace {

struct StrategySum {
  float sum = 0.f;
  bool any_delta = false;  // some strategy was left out for connecting at a delta vertex
  std::vector<float> weight;  // by s, the number of light vertices; -1: the strategy cannot make the path
};

// The MIS weights of the strategies (s, t = n - s) that can make the complete path `full`
// (x_0 the camera .. x_k on an emitter), each given the subpaths it would have drawn, with
// densities recomputed from positions in both directions. A point emitter's x_k (at_point)
// cannot be hit: no s = 0 strategy, and its camera-side density is 0.
// With `guides` (guided BDPT), camera-side densities are the radiance guide's mixtures and
// light-side ones the importance guide's; `mis_guides` are the ones mis_weight is told of.
StrategySum strategy_weight_sum(const Scene& scene, const Path& full, MisHeuristic heuristic,
                                Strategies strategies = Strategies::Mis, const SubpathGuides* guides = nullptr,
                                const SubpathGuides* mis_guides = nullptr) {
  const SdTree* radiance = guides != nullptr ? guides->radiance : nullptr;
  const SdTree* importance = guides != nullptr ? guides->importance : nullptr;
  const size_t n = full.size(), k = n - 1;
  const bool point = is_delta_light(*full[k].emitter);  // no path hits it
  std::vector<float> p_cam(n, 0.f), p_light(n, 0.f);
  for (size_t j = 1; j < n; ++j) {
    if (full[j - 1].delta || (point && j == k)) continue;
    p_cam[j] = pdf_area(kCamera, full[j - 1], j >= 2 ? &full[j - 2] : nullptr, full[j], radiance);
  }
  Vertex origin = full[k];
  origin.type = VertexType::Light;
  p_light[k] = pdf_light_origin(scene, origin);
  p_light[k - 1] = pdf_light(origin, full[k - 1]);
  for (size_t j = 0; j + 2 < n; ++j) {
    if (!full[j + 1].delta) p_light[j] = pdf_area(kCamera, full[j + 1], &full[j + 2], full[j], importance);
  }
  StrategySum out;
  out.weight.assign(n + 1, -1.f);
  for (size_t t = 1; t <= n; ++t) {
    const size_t s = n - t;
    if ((s == 1 && t == 1) || (s == 0 && point)) continue;
    Path cam(full.begin(), full.begin() + static_cast<std::ptrdiff_t>(t)), light;
    for (size_t j = 0; j < t; ++j) {
      cam[j].pdf_fwd = p_cam[j];
      cam[j].pdf_rev = p_light[j];
    }
    for (size_t j = 0; j < s; ++j) {
      Vertex v = full[k - j];
      v.pdf_fwd = p_light[k - j];
      v.pdf_rev = p_cam[k - j];
      if (j == 0) v.type = VertexType::Light;
      light.push_back(v);
    }
    // Strategies that would connect at a delta vertex cannot make the path.
    if ((t >= 2 && full[t - 1].delta) || (s >= 1 && full[k + 1 - s].delta)) {
      out.any_delta = true;
      continue;
    }
    const Vertex sampled = s == 1 ? light[0] : Vertex{};
    Vertex cam_vertex = full[0];
    out.weight[s] = mis_weight(scene, kCamera, light, cam, t == 1 ? cam_vertex : sampled, static_cast<int>(s),
                               static_cast<int>(t), heuristic, strategies, mis_guides);
    out.sum += out.weight[s];
  }
  return out;
}

}  // namespace

namespace {

struct SumChecks {
  size_t checked = 0, with_delta = 0;
  size_t refracted = 0;  // paths with a chain whose ends lie in media of different IOR
};

// For complete paths x_0 (camera) .. x_k (on an emitter) found by camera subpaths in `scene`,
// checks that the weights of the strategies that can make each one sum to 1.
SumChecks check_weights_sum_to_one(const Scene& scene) {
  const WalkLimits limits{7, 1 << 30};
  TraceCounters rays;
  Path path;
  SumChecks out;
  for (uint32_t i = 0; i < 3000 && out.checked < 300; ++i) {
    IndependentSampler sampler(5, 1, i);
    const Point2 u = sampler.next_2d();
    camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, path, rays);
    for (size_t k = 2; k < path.size(); ++k) {
      if (!path[k].is_emitter() || dot(path[k].n, path[k - 1].p - path[k].p) <= 0.f) continue;
      const Path full(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(k + 1));
      const StrategySum r =
          strategy_weight_sum(scene, full, (i & 1) ? MisHeuristic::Power : MisHeuristic::Balance);
      CHECK_NEAR(r.sum, 1.f, 2e-4f);
      // One strategy alone (BSDF or light sampling first): exactly one strategy keeps the path.
      for (const Strategies alone : {Strategies::Bsdf, Strategies::Light}) {
        CHECK(strategy_weight_sum(scene, full, MisHeuristic::Power, alone).sum == 1.f);
      }
      ++out.checked;
      out.with_delta += r.any_delta;
      size_t crossings = 0;  // refractions (the path crossing a delta vertex's surface)
      for (size_t j = 1; j < k; ++j) {
        crossings += full[j].delta && dot(full[j].n, full[j - 1].p - full[j].p) *
                                              dot(full[j].n, full[j + 1].p - full[j].p) < 0.f;
      }
      out.refracted += crossings % 2;
    }
  }
  return out;
}

}  // namespace

TEST_CASE("mis_weights_of_all_strategies_sum_to_one") {
  // For a complete path x_0 (camera) .. x_k (on an emitter), the weights of the strategies
  // that can make it sum to 1.
  const SumChecks c = check_weights_sum_to_one(box_with_mirror());
  CHECK(c.checked >= 100);
  CHECK(c.with_delta >= 10);
}

TEST_CASE("mis_weights_sum_to_one_through_glass") {
  // The same with the quad of glass (IOR 1.5, its back side inside the glass): chains that
  // refract once join vertices in media of different IOR, whose densities differ by
  // (eta_a / eta_b)^2 (mis_weight.cpp, chain_correction); every strategy must use the same.
  const SumChecks c = check_weights_sum_to_one(box_with_mirror({}, false, Dielectric{1.5f}));
  CHECK(c.checked >= 100);
  CHECK(c.with_delta >= 10);
  CHECK(c.refracted >= 10);
  MESSAGE("paths: ", c.checked, ", with a delta vertex: ", c.with_delta, ", refracted: ", c.refracted);
}

namespace {

// Densities of a path camera -> a -> mirror -> end under its two strategies, s = 0 and s = 3,
// and the usual rule's ratio of the second to the first.
struct MirrorPathDensities {
  float camera = 0.f, light = 0.f, usual_ratio = 0.f;
};

struct MirrorChecks {
  size_t checked = 0, usual_off = 0;
};

// Paths camera -> a (diffuse) -> mirror -> end (`ends(end, mirror)`) made by camera subpaths of
// `scene`, up to 200 and at least 50: mis_weight's two weights must be the power heuristic's of
// the densities `densities(full)` gives, and sum to 1; counts where the usual rule's weight is
// off by over 0.01.
template <class Ends, class Densities>
MirrorChecks check_weights_through_the_mirror(const Scene& scene, uint64_t seed, const Ends& ends,
                                              const Densities& densities) {
  const WalkLimits limits{3, 1 << 30};
  TraceCounters rays;
  Path path;
  MirrorChecks out;
  for (uint32_t i = 0; i < 200000 && out.checked < 200; ++i) {
    IndependentSampler sampler(seed, 1, i);
    const Point2 u = sampler.next_2d();
    camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, path, rays);
    if (path.size() < 4 || path[1].delta || !path[2].delta || !ends(path[3], path[2])) continue;
    const Path full(path.begin(), path.begin() + 4);
    const StrategySum r = strategy_weight_sum(scene, full, MisHeuristic::Power);
    const MirrorPathDensities p = densities(full);
    const float expected = p.camera * p.camera / (p.camera * p.camera + p.light * p.light);
    CHECK_NEAR(r.weight[0], expected, 1e-4f);
    CHECK_NEAR(r.weight[0] + r.weight[3], 1.f, 1e-5f);
    out.usual_off += std::abs(1.f / (1.f + p.usual_ratio * p.usual_ratio) - expected) > 1e-2f;
    ++out.checked;
  }
  CHECK(out.checked >= 50);
  MESSAGE("paths checked: ", out.checked, ", the usual rule's weight off by over 0.01 on ", out.usual_off);
  return out;
}

}  // namespace

TEST_CASE("mis_weights_through_a_mirror_follow_the_chains_true_densities") {
  // A path camera -> a (diffuse) -> mirror -> b (on the emitter) is made by two strategies: the
  // camera subpath hitting the emitter (s = 0) and the light subpath seen by the camera (s = 3).
  // Through a plane mirror the chain is an isometry: b sampled from a has density
  // p_w(a) |cos b| / D^2 and a from b p_w(b) |cos a| / D^2, with D the path's length from a to b
  // (the mirror image's distance), so the power heuristic's weight is known in closed form.
  // Control: the usual rule (each end's density through its own first segment) gives other
  // weights on most of these paths.
  const Scene scene = box_with_mirror();
  const auto on_emitter = [](const Vertex& end, const Vertex& m) {
    return end.is_emitter() && dot(end.n, m.p - end.p) > 0.f;
  };
  const MirrorChecks c = check_weights_through_the_mirror(scene, 7, on_emitter, [&](const Path& full) {
    const Vertex &a = full[1], &m = full[2];
    Vertex b = full[3];
    b.type = VertexType::Light;
    const Vec3 am = m.p - a.p, bm = m.p - b.p;
    const float D = length(am) + length(bm);
    const float pw_a = surface_pdf_w(a, direction(a, full[0]), normalize(am), TransportMode::Radiance);
    const float pw_b = emission_pdf_w(b, normalize(bm));
    MirrorPathDensities p;
    p.camera = pdf_area(kCamera, full[0], nullptr, a) * pw_a * std::abs(dot(b.n, normalize(bm))) / (D * D);
    p.light = pdf_light_origin(scene, b) * pw_b * std::abs(dot(a.n, normalize(am))) / (D * D);
    // The usual rule's ratio: the two first segments' one-segment densities at the mirror.
    const float cos_m_a = std::abs(dot(m.n, normalize(am))), cos_m_b = std::abs(dot(m.n, normalize(bm)));
    p.usual_ratio = (pdf_light_origin(scene, b) * pw_b * cos_m_b / dot(bm, bm)) /
                    (pdf_area(kCamera, full[0], nullptr, a) * pw_a * cos_m_a / dot(am, am));
    return p;
  });
  CHECK(c.usual_off * 2 >= c.checked);
}

TEST_CASE("guided_walks_and_mis_weights_agree_on_the_mixtures") {
  // Guided BDPT: camera subpaths sample a radiance guide, light subpaths an importance guide
  // (each mixed with the BSDF). The walks' cached densities must be the mixtures recomputed
  // from positions (pdf_fwd from a subpath's own guide, pdf_rev from the other's), and the MIS
  // weights of all strategies making a path, told of both guides, must sum to 1. Control: MIS
  // told of the guides the wrong way round misses 1 on most paths.
  const Scene scene = box_with_mirror();
  const SdTree radiance = lobe_guide(Vec3(0.f, 1.f, 0.f), 0.3f, 21);
  const SdTree importance = lobe_guide(normalize(Vec3(0.f, -0.6f, -0.8f)), 0.3f, 31);
  REQUIRE(radiance.at(Vec3(0.5f)).bsdf_fraction < 1.f);
  REQUIRE(importance.at(Vec3(0.5f)).bsdf_fraction < 1.f);
  const SubpathGuides guides{&radiance, &importance}, swapped{&importance, &radiance};
  const WalkLimits limits{7, 1 << 30};
  TraceCounters rays;
  Path path, light;
  size_t checked = 0, swapped_off = 0, densities = 0, densities_off = 0, reverse = 0, reverse_wrong_guide = 0;
  const auto off = [](float a, float b) { return std::abs(a - b) > 1e-2f * std::max(a, b); };
  const auto agree = [&](float cached, float recomputed) {
    ++densities;
    densities_off += off(cached, recomputed);
  };
  for (uint32_t i = 0; i < 6000 && checked < 300; ++i) {
    IndependentSampler sampler(8, 1, i);
    const Point2 u = sampler.next_2d();
    camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, path, rays, guides.camera());
    light_subpath(scene, sampler, limits, light, rays, guides.light());
    for (size_t j = 2; j < path.size(); ++j) {
      if (path[j - 1].delta) continue;
      agree(path[j].pdf_fwd, pdf_area(kCamera, path[j - 1], &path[j - 2], path[j], &radiance));
      if (j + 1 < path.size() && !path[j].delta) {
        agree(path[j - 1].pdf_rev, pdf_area(kCamera, path[j], &path[j + 1], path[j - 1], &importance));
        ++reverse;  // control: the camera walk's own guide is not the reverse walk's
        reverse_wrong_guide +=
            off(path[j - 1].pdf_rev, pdf_area(kCamera, path[j], &path[j + 1], path[j - 1], &radiance));
      }
    }
    for (size_t j = 2; j + 1 < light.size(); ++j) {
      if (light[j - 1].delta || light[j].delta) continue;
      agree(light[j].pdf_fwd, pdf_area(kCamera, light[j - 1], &light[j - 2], light[j], &importance));
      agree(light[j - 1].pdf_rev, pdf_area(kCamera, light[j], &light[j + 1], light[j - 1], &radiance));
    }
    for (size_t k = 2; k < path.size(); ++k) {
      if (!path[k].is_emitter() || dot(path[k].n, path[k - 1].p - path[k].p) <= 0.f) continue;
      const Path full(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(k + 1));
      const MisHeuristic h = (i & 1) ? MisHeuristic::Power : MisHeuristic::Balance;
      CHECK_NEAR(strategy_weight_sum(scene, full, h, Strategies::Mis, &guides, &guides).sum, 1.f, 2e-4f);
      const float wrong = strategy_weight_sum(scene, full, h, Strategies::Mis, &guides, &swapped).sum;
      swapped_off += std::abs(wrong - 1.f) > 1e-2f;
      ++checked;
    }
  }
  CHECK(checked >= 100);
  CHECK(swapped_off >= checked / 2);
  // Directions and distances recomputed from positions differ from the sampled ones by the ray
  // offsets (up to 1e-2 relative near corners, path.cpp's verify), which can also move a
  // direction across a quadtree cell's edge: almost all, not all, agree.
  CHECK(densities >= 1000);
  CHECK(densities_off <= densities / 100);
  CHECK(reverse_wrong_guide >= reverse / 2);
}

TEST_CASE("cached_vertex_guides_give_the_same_mis_weights") {
  // Guided BDPT caches each subpath vertex's guides (set_vertex_guides) instead of looking them
  // up per strategy: every weight must be the same bits as with the lookups. Control: caches set
  // as if the light subpath were a camera subpath (the wrong reverse guide) change most weights.
  const Scene scene = box_with_mirror();
  const SdTree radiance = lobe_guide(Vec3(0.f, 1.f, 0.f), 0.3f, 21);
  const SdTree importance = lobe_guide(normalize(Vec3(0.f, -0.6f, -0.8f)), 0.3f, 31);
  const SubpathGuides guides{&radiance, &importance};
  const WalkLimits limits{7, 1 << 30};
  TraceCounters rays;
  Path cam, light;
  size_t compared = 0, wrong_off = 0;
  for (uint32_t i = 0; i < 400; ++i) {
    IndependentSampler sampler(11, 1, i);
    const Point2 u = sampler.next_2d();
    camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, cam, rays, guides.camera());
    light_subpath(scene, sampler, limits, light, rays, guides.light());
    Path cam_cached = cam, light_cached = light, light_wrong = light;
    set_vertex_guides(cam_cached, guides, TransportMode::Radiance);
    set_vertex_guides(light_cached, guides, TransportMode::Importance);
    set_vertex_guides(light_wrong, guides, TransportMode::Radiance);
    for (int t = 2; t <= static_cast<int>(cam.size()); ++t) {
      for (int s = 2; s <= static_cast<int>(light.size()); ++s) {
        if (cam[static_cast<size_t>(t - 1)].delta || light[static_cast<size_t>(s - 1)].delta) continue;
        const Vertex none{};
        const auto weight = [&](const Path& l, const Path& c) {
          return mis_weight(scene, kCamera, l, c, none, s, t, MisHeuristic::Power, Strategies::Mis, &guides);
        };
        const float looked_up = weight(light, cam);
        CHECK(weight(light_cached, cam_cached) == looked_up);
        wrong_off += std::abs(weight(light_wrong, cam_cached) - looked_up) > 1e-3f * looked_up;
        ++compared;
      }
    }
  }
  CHECK(compared >= 300);
  CHECK(wrong_off >= compared / 8);  // 509 of 2324 at the time of writing
}

TEST_CASE("mis_weights_sum_to_one_on_paths_ending_at_point_and_spot_lights") {
  // A camera subpath x_0 .. x_{k-1} (its last vertex not a delta one) closed by a point or spot
  // light x_k: no strategy with s = 0 can make it (no path hits a point), and the weights of
  // those with s >= 1 must sum to 1 (the point's "area density" is the choice's probability,
  // no cosine at it).
  constexpr float kDeg = kPi / 180.f;
  const Scene scene = box_with_mirror(
      {PointEmitter{Vec3(0.5f, 0.85f, 0.5f), Color(0.3f)},
       make_spot(Vec3(0.4f, 0.8f, 0.6f), Vec3(0.1f, -1.f, 0.f), Color(0.8f), 70.f * kDeg, 50.f * kDeg)});
  const WalkLimits limits{6, 1 << 30};
  TraceCounters rays;
  Path path;
  size_t checked = 0;
  for (uint32_t i = 0; i < 2000 && checked < 300; ++i) {
    IndependentSampler sampler(9, 1, i);
    const Point2 u = sampler.next_2d();
    camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, path, rays);
    const size_t first_light = scene.emitter_count() - 2;
    for (size_t k = 2; k <= path.size(); ++k) {
      if (path[k - 1].delta || path[k - 1].type != VertexType::Surface) continue;
      const Emitter& e = scene.emitters()[first_light + (i + k) % 2];
      const Vec3 at = sample_Le_position(e, 1.f, {0.5f, 0.5f}).p;
      if (is_black(radiance(e, path[k - 1].p - at, {}))) continue;
      Path full(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(k));
      Vertex light;
      light.type = VertexType::Light;
      light.p = at;
      light.emitter = &e;
      light.at_point = true;
      full.push_back(light);
      const StrategySum r =
          strategy_weight_sum(scene, full, (i & 1) ? MisHeuristic::Power : MisHeuristic::Balance);
      CHECK_NEAR(r.sum, 1.f, 2e-4f);
      for (const Strategies alone : {Strategies::Bsdf, Strategies::Light}) {
        CHECK(strategy_weight_sum(scene, full, MisHeuristic::Power, alone).sum == 1.f);
      }
      ++checked;
    }
  }
  CHECK(checked >= 100);
}

namespace {

// A 16 x 8 sky brightening towards the zenith, with a bright patch.
Emitter small_envmap() {
  std::vector<float> rgb(3 * 16 * 8);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.2f + 0.1f * static_cast<float>((i / 48) % 8) + (i % 97 == 0 ? 20.f : 0.f);
  const Frame id{Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f), Vec3(0.f, 0.f, 1.f)};
  return EnvmapEmitter{std::make_shared<const EnvironmentMap>(16, 8, rgb, 1.f, id), {}};
}

}  // namespace

TEST_CASE("mis_weights_sum_to_one_on_paths_ending_at_infinity") {
  // The open-top box under an environment (constant, then an image) and a directional light.
  // A camera subpath that leaves through the top ends at the environment's vertex at infinity
  // (every strategy can make it: s = 0 hits it, s = 1 samples its direction, s >= 2 enter from
  // the distant disk); closed instead by the directional light's vertex at infinity, no s = 0
  // strategy can make the path (its direction is a delta) and the rest must sum to 1.
  for (const Emitter& env : {Emitter{ConstantEmitter{Color(0.7f), {}}}, small_envmap()}) {
    const Scene scene = box_with_mirror({env, make_directional(Vec3(0.3f, -1.f, 0.2f), Color(2.f))}, true);
    const Emitter& sun = scene.emitters().back();
    const Vec3 towards_sun = -normalize(Vec3(0.3f, -1.f, 0.2f));
    const WalkLimits limits{6, 1 << 30};
    TraceCounters rays;
    Path path;
    size_t escaped = 0, sunlit = 0;
    for (uint32_t i = 0; i < 4000 && (escaped < 150 || sunlit < 150); ++i) {
      IndependentSampler sampler(11, 1, i);
      const Point2 u = sampler.next_2d();
      camera_subpath(scene, kCamera, u.u * 32.f, u.v * 24.f, sampler, limits, path, rays);
      const auto heuristic = (i & 1) ? MisHeuristic::Power : MisHeuristic::Balance;
      if (path.size() >= 3 && path.back().at_infinity) {
        CHECK_NEAR(strategy_weight_sum(scene, path, heuristic).sum, 1.f, 2e-4f);
        CHECK(strategy_weight_sum(scene, path, heuristic, Strategies::Light).sum == 1.f);
        ++escaped;
      }
      for (size_t k = 2; k <= path.size(); ++k) {
        if (path[k - 1].delta || path[k - 1].type != VertexType::Surface) continue;
        Path full(path.begin(), path.begin() + static_cast<std::ptrdiff_t>(k));
        Vertex light;
        light.type = VertexType::Light;
        light.p = light.n = towards_sun;
        light.emitter = &sun;
        light.at_point = light.at_infinity = true;
        full.push_back(light);
        CHECK_NEAR(strategy_weight_sum(scene, full, heuristic).sum, 1.f, 2e-4f);
        CHECK(strategy_weight_sum(scene, full, heuristic, Strategies::Bsdf).sum == 1.f);
        ++sunlit;
      }
    }
    CHECK(escaped >= 150);
    CHECK(sunlit >= 150);
  }
}

TEST_CASE("mis_weights_through_a_mirror_to_infinity_follow_the_chains_true_densities") {
  // A path camera -> a (diffuse) -> mirror -> the environment at infinity (the open-top box
  // under a constant sky) is made by two strategies: the camera subpath leaving through the
  // top (s = 0), with densities p_camera(a) and p_w(a) (a plane mirror turns directions
  // without magnifying them), and the light subpath entering from the sky's disk and seen by
  // the camera (s = 3), with densities p(w) for the direction and p_disk |cos a| for a (the
  // beam reaches a at that angle). Control: the usual rule's ratio is the true one times
  // d^2(a, mirror) / |cos a|, which gives other weights on many of these paths.
  const Scene scene = box_with_mirror({Emitter{ConstantEmitter{Color(0.7f), {}}}}, true);
  const auto at_infinity = [](const Vertex& end, const Vertex&) { return end.at_infinity; };
  const MirrorChecks c = check_weights_through_the_mirror(scene, 13, at_infinity, [&](const Path& full) {
    const Vertex &a = full[1], &m = full[2];
    Vertex sky = full[3];
    sky.type = VertexType::Light;
    const Vec3 am = m.p - a.p;
    const float cos_a = std::abs(dot(a.n, normalize(am)));
    const float pw_a = surface_pdf_w(a, direction(a, full[0]), normalize(am), TransportMode::Radiance);
    MirrorPathDensities p;
    p.camera = pdf_area(kCamera, full[0], nullptr, a) * pw_a;
    p.light = pdf_light_origin(scene, sky) * emission_pdf_w(sky, direction(sky, m)) * cos_a;
    p.usual_ratio = p.light / p.camera * dot(am, am) / cos_a;
    return p;
  });
  CHECK(c.usual_off * 4 >= c.checked);
}

TEST_CASE("path_tracer_lanes_render_the_scalar_image_bit_for_bit") {
  // Each build of the lanes the CPU runs, both samplers, odd image sizes (rows of fewer than
  // sixteen pixels), one and two threads: the scalar tracer's means, variances and counters.
  const auto scene = std::make_shared<const Scene>(closed_box());
  const auto render = [&](LaneIsa lanes, SamplerType sampler, int width, int threads) {
    const PinholeCamera camera({0.5f, 0.5f, 0.05f}, {0.5f, 0.5f, 1.f}, {0, 1, 0}, 60.f, width, 7);
    PathTracerOptions options;
    options.spp = 6;
    options.max_depth = 6;
    options.rr_depth = 2;
    options.seed = 11;
    options.threads = threads;
    options.sampler = sampler;
    options.lanes = lanes;
    RenderControl control;
    return render_path(*scene, camera, options, control);
  };
  int builds = 0;
  for (const LaneIsa isa : {LaneIsa::Sse2, LaneIsa::Avx2, LaneIsa::Avx512}) {
    for (const SamplerType sampler : {SamplerType::Independent, SamplerType::Sobol}) {
      for (const int width : {5, 21}) {
        const RenderResult scalar = render(LaneIsa::Off, sampler, width, 1);
        CHECK(scalar.stats.lanes == nullptr);
        PathTracerOptions probe;
        probe.lanes = isa;
        bool runs = true;
        try {
          choose_path_lanes(*scene, probe);
        } catch (const std::invalid_argument&) {
          runs = false;  // this CPU lacks the instruction set
        }
        if (!runs) continue;
        ++builds;
        for (const int threads : {1, 2}) {
          const RenderResult lanes = render(isa, sampler, width, threads);
          REQUIRE(lanes.stats.lanes != nullptr);
          CHECK(lanes.film.mean() == scalar.film.mean());
          CHECK(lanes.film.variance_of_mean() == scalar.film.variance_of_mean());
          CHECK(lanes.stats.rays == scalar.stats.rays);
          CHECK(lanes.stats.skipped_connections == scalar.stats.skipped_connections);
        }
      }
    }
  }
  CHECK(builds > 0);  // the baseline build runs on every x86-64 CPU
}

// The light pool's shifts (bdpt_sample.h) hash each strategy as hash_combine(key, s << 32 | t),
// from the table (s, t < 16) and beyond it alike.
TEST_CASE("light_pool_strategy_hashes_are_hash_combines") {
  const uint64_t key = 0x243f6a8885a308d3ull;
  for (int s = 0; s < 40; ++s) {
    for (int t = 0; t < 40; ++t) {
      CHECK(mix64(key ^ LightPool::strategy_hash(s, t)) ==
            hash_combine(key, static_cast<uint64_t>(s) << 32 | static_cast<uint32_t>(t)));
    }
  }
  // Control: another strategy's entry differs.
  CHECK(mix64(key ^ LightPool::strategy_hash(3, 2)) != hash_combine(key, static_cast<uint64_t>(2) << 32 | 3u));
}
