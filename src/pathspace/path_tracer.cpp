#include "pathspace/path_tracer.h"

#include <optional>

#include "core/frame.h"
#include "core/sampling.h"
#include "materials/shading_normal.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/shadow_ray.h"

namespace dualight {

namespace {

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
inline Color next_event(const Scene& scene, const SurfaceHit& hit, const Bsdf& bsdf, const Vec3& wo_world,
                        const Color& beta, float u_select, Point2 u_light, Strategies strategies,
                        TraceCounters& counters) {
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
  const float weight = is_delta_light(*choice.emitter)
                           ? 1.f
                           : two_strategy_weight(strategies, Strategies::Light, ls.pdf_w, pdf_bsdf_w);
  if (weight == 0.f) return Color(0.f);  // BSDF sampling alone: no shadow ray
  if (!shadow_ray_visible_to(scene, hit.p, hit.n, hit.prim, ls.p, ls.prim, ls.on_surface, counters)) {
    return Color(0.f);
  }
  return beta * f * ls.Le * (std::abs(dot(ls.wi, hit.ns)) * weight / ls.pdf_w);
}

// One camera path; returns its radiance estimate.
template <class Sampler>
Color trace_path(const Scene& scene, const Ray& camera_ray, const PathTracerOptions& opt, Sampler& sampler,
                 TraceCounters& counters) {
  const bool has_emitters = scene.emitter_count() > 0;
  const auto depth_allows = [&](int segments) { return opt.max_depth < 0 || segments <= opt.max_depth; };

  Color L(0.f), beta(1.f);
  Ray ray = camera_ray;
  float prev_pdf_w = 0.f;    // solid-angle density of the BSDF sample that made `ray`
  bool prev_delta = true;    // the camera ray, like a delta bounce, cannot be found by NEE
  // `depth` is the number of segments up to and including `ray`, i.e. the index of the vertex it hits.
  for (int depth = 1; depth_allows(depth); ++depth) {
    SurfaceHit hit;
    ++counters.rays;
    if (!scene.intersect(ray, hit)) {
      if (scene.environment() != nullptr) {
        L += environment_seen(scene, *scene.environment(), ray.d, beta, prev_pdf_w, prev_delta, opt.strategies);
      }
      break;
    }

    const Vec3 wo_world = -ray.d;
    if (hit.emitter != nullptr) {
      L += emission_seen(scene, hit, wo_world, beta, prev_pdf_w, prev_delta, opt.strategies);
    }
    if (!depth_allows(depth + 1)) break;

    // The BSDF's frame is the shading normal's (it tells a dielectric's inside from its
    // outside); two-sided BSDFs handle wo.z < 0 themselves. Radiance transport needs no
    // correction for shading normals (materials/shading_normal.h).
    const Frame frame = Frame::from_normal(hit.ns);
    const Vec3 wo = frame.to_local(wo_world);
    std::optional<Bsdf> textured;  // engaged only where textures change the material's BSDF
    const Bsdf& bsdf = hit.material->textured() ? textured.emplace(hit.material->bsdf_at(hit.uv))
                                                : hit.material->bsdf;
    if (has_emitters && is_delta(bsdf)) {
      ++counters.skipped_connections;  // no light sample can meet a specular lobe
    } else if (has_emitters) {
      const float u_select = sampler.next_1d();
      const Point2 u_light = sampler.next_2d();
      L += next_event(scene, hit, bsdf, wo_world, beta, u_select, u_light, opt.strategies, counters);
    }

    BsdfSample bs;
    if (!sample(bsdf, wo, sampler.next_2d(), TransportMode::Radiance, bs)) break;
    beta *= bs.weight;
    prev_pdf_w = bs.pdf_w;
    prev_delta = bs.delta;
    const Vec3 wi_world = frame.to_world(bs.wi);
    ray = Ray{scene.spawn_origin(hit.p, leaves_front(hit.n, hit.ns, wi_world, bs.wi.z) ? hit.n : -hit.n), wi_world};

    if (depth >= opt.rr_depth) {
      const float q = std::min(max_component(beta), 0.95f);
      if (!(sampler.next_1d() < q)) break;
      beta /= q;
    }
  }
  return L;
}

}  // namespace

RenderResult render_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                         RenderControl& control) {
  RenderResult result{Film(camera.width(), camera.height()), {}};
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, false,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  const auto estimate = [&](float x, float y, auto& sampler, TraceCounters& counters, SplatList&) {
    return trace_path(scene, scene.eye_ray(camera.generate_ray(x, y)), options, sampler, counters);
  };
  result.stats = with_sampler(options.sampler, [&](auto tag) {
    return drive_pixels<typename decltype(tag)::type>(result.film, driver, control, estimate);
  });
  return result;
}

}  // namespace dualight
