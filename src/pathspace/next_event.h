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
  const Color Le = radiance(env, -d, {});
  if (is_black(Le) || prev_delta) return beta * Le;
  const float pdf_light_w = pdf_Li(env, scene.emitter_pmf(env), d, 0.f, 1.f);
  return beta * (Le * two_strategy_weight(strategies, Strategies::Bsdf, prev_pdf_w, pdf_light_w));
}

// Next-event estimation at `hit`: a light sample, MIS-weighted against BSDF sampling, times the
// path's throughput beta.
// World directions throughout: a Lambertian BSDF needs only the two cosines (bsdf.h).
inline Color next_event(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const VertexGuide& guide,
                        const Vec3& wo_world, const Color& beta, float u_select, Point2 u_light,
                        Strategies strategies, TraceCounters& counters) {
  const EmitterChoice choice = scene.choose_emitter(u_select);
  LightSample ls;
  if (!sample_Li(*choice.emitter, choice.pmf, hit.p, u_light, ls)) return Color(0.f);
  const Color f = eval_f_world(bsdf, hit.ns, wo_world, ls.wi, TransportMode::Radiance);
  if (is_black(f)) {
    ++counters.skipped_connections;
    return Color(0.f);
  }
  const float pdf_bsdf_w = pdf_w_world(bsdf, hit.ns, wo_world, ls.wi, TransportMode::Radiance);
  // A delta emitter (a point light, a direction) is found by no BSDF sample: its sample keeps
  // full weight (ls.pdf_w is then a discrete probability, not comparable with pdf_bsdf_w).
  const bool delta_light = is_delta_light(*choice.emitter);
  float weight = delta_light ? 1.f : two_strategy_weight(strategies, Strategies::Light, ls.pdf_w, pdf_bsdf_w);
  if (weight == 0.f) return Color(0.f);  // BSDF sampling alone: no shadow ray
  if (!shadow_ray_visible_to(scene, hit.p, hit.n, hit.prim, ls.p, ls.prim, ls.on_surface, counters)) {
    return Color(0.f);
  }
  // Guided, the other strategy's samples come from the mixture (its density is looked up only
  // for the light samples that arrive: the weight is 0 only where BSDF sampling alone is used).
  if (guide.active() && !delta_light) {
    weight = two_strategy_weight(strategies, Strategies::Light, ls.pdf_w, guide.mixture_pdf_w(pdf_bsdf_w, ls.wi));
  }
  return beta * f * ls.Le * (std::abs(dot(ls.wi, hit.ns)) * weight / ls.pdf_w);
}

}  // namespace dualight
