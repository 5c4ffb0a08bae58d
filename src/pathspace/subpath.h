// Random walks that build camera and light subpaths with their area densities
// [Veach 1997, sec. 10.2; pbrt-v3 sec. 16.3.1-16.3.2]. Depths count segments as in Mitsuba:
// a camera subpath has at most max_depth + 1 vertices (camera included), a light subpath at most
// max_depth (emitter included), so every strategy's path has at most max_depth segments.
// Russian roulette starts at the vertex with index rr_depth (segments from the subpath's start)
// and only rescales beta: MIS weights stay functions of the path, so the estimate stays unbiased.
#pragma once
#include <algorithm>
#include <limits>

#include "core/frame.h"
#include "guiding/guided_sampling.h"
#include "guiding/sd_tree.h"
#include "pathspace/path.h"
#include "pathspace/render_stats.h"
#include "pathspace/russian_roulette.h"

namespace dualight {

struct WalkLimits {
  int max_depth = -1;  // segments; -1 = unbounded
  int rr_depth = 5;
};

// A guide for a walk's directions (guiding/; null: BSDF sampling alone), and the guide of the
// other transport direction, which a walk the other way would sample from: the reverse densities
// (pdf_rev) follow it (null: the BSDF's alone), as bidirectional MIS needs them [Vorba et al.
// 2014, sec. 6]. A walk for one estimator alone (the light tracer) leaves `reverse` null.
struct WalkGuide {
  const SdTree* tree = nullptr;
  const SdTree* reverse = nullptr;

  bool any() const { return tree != nullptr || reverse != nullptr; }
};

// The two guides of guided BDPT: camera subpaths sample from the radiance guide, light subpaths
// from the importance guide, and each one's reverse densities are the other's.
struct SubpathGuides {
  const SdTree* radiance = nullptr;
  const SdTree* importance = nullptr;

  bool any() const { return radiance != nullptr || importance != nullptr; }
  WalkGuide camera() const { return {radiance, importance}; }
  WalkGuide light() const { return {importance, radiance}; }
};

// An rr_depth no walk reaches: no Russian roulette (beta stays recomputable from the path, and
// a walk of a fixed strategy's length is not cut short).
inline constexpr int kNoRussianRoulette = 1 << 30;

namespace subpath_detail {

// Keeps on v a guide a guided walk looked up there: the radiance guide's or the importance
// guide's (set_vertex_guides then need not look it up again).
inline void keep_guide(Vertex& v, bool radiance, const VertexGuide& g) {
  (radiance ? v.radiance_guide : v.importance_guide) = g;
  (radiance ? v.radiance_guide_known : v.importance_guide_known) = true;
}

// Extends `path` from its last vertex along `ray`, which was sampled with solid-angle density
// pdf_w; at most `max_new` vertices are added. A camera subpath (Radiance) whose ray leaves a
// scene with an environment ends at a vertex at infinity on it (escape_vertex).
// kGuided compiles the guide's sampling in (guide.tree may still be null).
template <bool kGuided = false, class Sampler>
void random_walk(const Scene& scene, Ray ray, Sampler& sampler, Color beta, float pdf_w, size_t max_new,
                 int rr_depth, TransportMode mode, Path& path, TraceCounters& counters, const WalkGuide& guide = {}) {
  Color throughput(1.f);  // beta without the start's emission, for Russian roulette
  float rr_scale = 1.f;  // the roulette scale (russian_roulette.h)
  for (size_t added = 0; added < max_new; ++added) {
    SurfaceHit hit;
    ++counters.rays;
    if (!scene.intersect(ray, hit)) {
      if (mode == TransportMode::Radiance && scene.environment() != nullptr) {
        path.push_back(escape_vertex(scene, ray.d, beta, pdf_w));
      }
      return;
    }
    Vertex v = surface_vertex(hit, ray.d);
    v.beta = beta;
    v.pdf_fwd = solid_angle_to_area(pdf_w, path.back(), v);
    path.push_back(v);
    if (added + 1 == max_new) return;

    Vertex& cur = path.back();
    const Frame frame = shading_frame(cur);
    const Vec3 wo = frame.to_local(cur.wo);
    BsdfSample bs;
    float pdf_rev_w = 0.f, vertex_bsdf_ratio = 1.f;
    const bool sampled = with_bsdf(cur, [&](const Bsdf& b) {
      if constexpr (kGuided) {
        const VertexGuide g = guide.tree != nullptr ? vertex_guide(guide.tree->at(cur.p), b) : VertexGuide{};
        if (guide.tree != nullptr) keep_guide(cur, mode == TransportMode::Radiance, g);
        const float u_select = g.active() ? sampler.next_1d() : 0.f;
        if (!sample_guided(b, frame, g, wo, u_select, sampler.next_2d(), mode, bs, vertex_bsdf_ratio)) return false;
      } else if (!sample(b, wo, sampler.next_2d(), mode, bs)) {
        return false;
      }
      if (bs.delta) return true;
      pdf_rev_w = dualight::pdf_w(b, bs.wi, wo, mode);
      if constexpr (kGuided) {
        if (guide.reverse != nullptr) {
          const VertexGuide r = vertex_guide(guide.reverse->at(cur.p), b);
          keep_guide(cur, mode != TransportMode::Radiance, r);
          if (r.active()) pdf_rev_w = r.mixture_pdf_w(pdf_rev_w, cur.wo);
        }
      }
      return true;
    });
    if (!sampled) return;
    if (bs.delta) {
      cur.delta = true;
      pdf_w = 0.f;
    } else {
      pdf_w = bs.pdf_w;
    }
    const Vec3 wi = frame.to_world(bs.wi);
    const Color weight = bs.weight * walk_weight_correction(cur.n, cur.ns, cur.wo, wi, mode);
    beta *= weight;
    throughput *= weight;
    rr_scale *= roulette_scale(bs, mode, vertex_bsdf_ratio);
    Vertex& prev = path[path.size() - 2];
    prev.pdf_rev = solid_angle_to_area(pdf_rev_w, cur, prev);

    if (static_cast<int>(path.size()) - 1 >= rr_depth) {
      const float q = roulette_survival(throughput, rr_scale);
      if (!(sampler.next_1d() < q)) return;
      beta /= q;
      throughput /= q;
    }
    ray = Ray{scene.spawn_origin(cur.p, leaves_front(cur.n, cur.ns, wi, bs.wi.z) ? cur.n : -cur.n), wi};
  }
}

inline size_t max_vertices(int max_depth, int extra) {
  return max_depth < 0 ? std::numeric_limits<size_t>::max() : static_cast<size_t>(max_depth + extra);
}

}  // namespace subpath_detail

// The camera subpath through film position (x, y): the camera vertex, then surface vertices.
template <class Sampler>
void camera_subpath(const Scene& scene, const PinholeCamera& camera, float x, float y, Sampler& sampler,
                    const WalkLimits& limits, Path& path, TraceCounters& counters, const WalkGuide& guide = {}) {
  path.clear();
  const Ray ray = scene.eye_ray(camera.generate_ray(x, y));
  Vertex c;
  c.type = VertexType::Camera;
  c.p = ray.o;
  c.n = camera.forward();
  c.ns = c.n;
  c.beta = Color(1.f);  // We / pdf = 1: camera rays sample importance exactly
  path.push_back(c);
  const size_t max_new = subpath_detail::max_vertices(limits.max_depth, 1) - 1;
  if (!guide.any()) {
    subpath_detail::random_walk(scene, ray, sampler, Color(1.f), camera.pdf_w(ray.d), max_new, limits.rr_depth,
                                TransportMode::Radiance, path, counters);
  } else {
    subpath_detail::random_walk<true>(scene, ray, sampler, Color(1.f), camera.pdf_w(ray.d), max_new,
                                      limits.rr_depth, TransportMode::Radiance, path, counters, guide);
  }
}

// A light subpath: a point on an emitter chosen by power, then a direction the emitter samples.
template <class Sampler>
void light_subpath(const Scene& scene, Sampler& sampler, const WalkLimits& limits, Path& path,
                   TraceCounters& counters, const WalkGuide& guide = {}) {
  path.clear();
  const size_t max_vertices = subpath_detail::max_vertices(limits.max_depth, 0);
  if (max_vertices == 0) return;
  const float u_select = sampler.next_1d();
  path.push_back(emitter_vertex(scene, u_select, sampler.next_2d()));
  const Vertex& y0 = path.back();
  EmitterDirection d;
  if (!sample_Le_direction(*y0.emitter, y0.pdf_fwd, y0.p, y0.uv, sampler.next_2d(), d)) return;
  const Vec3 origin = y0.on_surface() ? scene.spawn_origin(y0.p, y0.n) : (y0.at_infinity ? d.origin : y0.p);
  const Ray ray{origin, d.w};
  if (!guide.any()) {
    subpath_detail::random_walk(scene, ray, sampler, d.beta, d.pdf_w, max_vertices - 1, limits.rr_depth,
                                TransportMode::Importance, path, counters);
  } else {
    subpath_detail::random_walk<true>(scene, ray, sampler, d.beta, d.pdf_w, max_vertices - 1, limits.rr_depth,
                                      TransportMode::Importance, path, counters, guide);
  }
}

}  // namespace dualight
