// The path tracer's radiance estimates at one vertex [Veach 1997, sec. 9.2; pbrt-v4 sec. 13.4]:
// the emitter a path hits, the environment it escapes to, and next-event estimation (a light
// sample), each MIS-weighted against BSDF sampling with the two-strategy heuristic
// (strategies.h). Shared by the scalar tracer (path_tracer.cpp) and the lanes, which hand the
// emitters they do not compute lane-wide to these very functions (path_lanes_kernel.h), so both
// make the same bits.
#pragma once
#include <cmath>

#include "geometry/scene.h"
#include "guiding/guided_sampling.h"
#include "materials/bsdf.h"
#include "pathspace/render_stats.h"
#include "pathspace/shadow_ray.h"
#include "pathspace/strategies.h"

namespace dualight {

// Radiance of the emitter the path hit at `hit`, seen along wo_world, weighted against
// next-event estimation from the previous vertex, which could have found the same point
// (unless the path got here by a delta bounce or straight from the camera); times the path's
// throughput beta.
inline Color emission_seen(const Scene& scene, const SurfaceHit& hit, const Vec3& wo_world, const Color& beta,
                           float prev_pdf_w, bool prev_delta, Strategies strategies) {
  const Emitter& e = *hit.emitter;
  const Color Le = radiance(e, wo_world, hit.uv);
  if (is_black(Le)) return Color(0.f);
  if (prev_delta) return beta * Le;
  const float cos_light = std::abs(dot(hit.n, wo_world));
  const float pdf_light_w = pdf_Li(e, scene.emitter_pmf(e), -wo_world, hit.t, cos_light);
  return beta * Le * two_strategy_weight(strategies, Strategies::Bsdf, prev_pdf_w, pdf_light_w);
}

// Radiance of the environment `env` a ray along unit d escaped to, weighted against next-event
// estimation as emission_seen, times beta.
inline Color environment_seen(const Scene& scene, const Emitter& env, const Vec3& d, const Color& beta,
                              float prev_pdf_w, bool prev_delta, Strategies strategies) {
  float pdf_light_w = 0.f;
  const Color Le = radiance_seen(env, scene.emitter_pmf(env), d, pdf_light_w);
  if (is_black(Le) || prev_delta) return beta * Le;
  return beta * (Le * two_strategy_weight(strategies, Strategies::Bsdf, prev_pdf_w, pdf_light_w));
}

// A light sample at a vertex before its shadow ray: what it carries where the segment from the
// vertex to p is clear.
struct LightConnection {
  Color f, Le;
  Vec3 wi, p;
  float pdf_w = 0.f, pdf_bsdf_w = 0.f, weight = 0.f;
  uint32_t prim = 0;
  bool on_surface = false, delta_light = false;
};

// next_event's light sample at `hit` up to its shadow ray; false where it carries nothing (no
// ray then).
inline bool light_connection(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const Vec3& wo_world,
                             float u_select, Point2 u_light, Strategies strategies, TraceCounters& counters,
                             LightConnection& c) {
  const EmitterChoice choice = scene.choose_emitter(u_select);
  LightSample ls;
  if (!sample_Li(*choice.emitter, choice.pmf, hit.p, u_light, ls)) return false;
  c.f = eval_f_world(bsdf, hit.ns, wo_world, ls.wi, TransportMode::Radiance);
  if (is_black(c.f)) {
    ++counters.skipped_connections;
    return false;
  }
  c.pdf_bsdf_w = pdf_w_world(bsdf, hit.ns, wo_world, ls.wi, TransportMode::Radiance);
  // A delta emitter (a point light, a direction) is found by no BSDF sample: its sample keeps
  // full weight (ls.pdf_w is then a discrete probability, not comparable with pdf_bsdf_w).
  c.delta_light = is_delta_light(*choice.emitter);
  c.weight = c.delta_light ? 1.f : two_strategy_weight(strategies, Strategies::Light, ls.pdf_w, c.pdf_bsdf_w);
  if (c.weight == 0.f) return false;  // BSDF sampling alone: no shadow ray
  c.Le = ls.Le, c.wi = ls.wi, c.p = ls.p, c.pdf_w = ls.pdf_w, c.prim = ls.prim, c.on_surface = ls.on_surface;
  return true;
}

// The connection's contribution with its segment clear, times the path's throughput beta.
// Guided, the other strategy's samples come from the mixture (its density is looked up only for
// the light samples that arrive: the weight is 0 only where BSDF sampling alone is used).
inline Color light_contribution(const LightConnection& c, const SurfaceHit& hit, const Color& beta,
                                const VertexGuide& guide, Strategies strategies) {
  float weight = c.weight;
  if (guide.active() && !c.delta_light) {
    weight = two_strategy_weight(strategies, Strategies::Light, c.pdf_w, guide.mixture_pdf_w(c.pdf_bsdf_w, c.wi));
  }
  return beta * c.f * c.Le * (std::abs(dot(c.wi, hit.ns)) * weight / c.pdf_w);
}

// Next-event estimation at `hit`: a light sample, MIS-weighted against BSDF sampling, times the
// path's throughput beta.
// World directions throughout: a Lambertian BSDF needs only the two cosines (bsdf.h).
inline Color next_event(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const VertexGuide& guide,
                        const Vec3& wo_world, const Color& beta, float u_select, Point2 u_light,
                        Strategies strategies, TraceCounters& counters) {
  LightConnection c;
  if (!light_connection(scene, hit, bsdf, wo_world, u_select, u_light, strategies, counters, c)) return Color(0.f);
  if (!shadow_ray_visible_to(scene, hit.p, hit.n, hit.prim, c.p, c.prim, c.on_surface, counters)) {
    return Color(0.f);
  }
  return light_contribution(c, hit, beta, guide, strategies);
}

}  // namespace dualight
