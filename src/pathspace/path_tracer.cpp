#include "pathspace/path_tracer.h"

#include <optional>
#include <type_traits>

#include "core/frame.h"
#include "core/sampling.h"
#include "guiding/guide_training.h"
#include "guiding/guided_sampling.h"
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
  float pdf_bsdf_w = pdf_w_world(bsdf, hit.ns, wo_world, ls.wi, TransportMode::Radiance);
  // Guided, the other strategy's samples come from the mixture.
  if (guide.active()) pdf_bsdf_w = guide.mixture_pdf_w(pdf_bsdf_w, ls.wi);
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

// The guide of a guided render (guiding/), and where a training iteration keeps its records.
struct PathGuiding {
  const SdTree* tree = nullptr;
  GuideRecords* records = nullptr;
};

// The vertices of one camera path that sampled a non-Dirac direction, with the radiance that
// arrived along each: every later contribution over the throughput there (guide_record.h). They
// become records when the path ends.
class RadianceRecorder {
 public:
  explicit RadianceRecorder(GuideRecords* out) : out_(out) {}
  RadianceRecorder(const RadianceRecorder&) = delete;
  RadianceRecorder& operator=(const RadianceRecorder&) = delete;
  ~RadianceRecorder() {
    GuideRecord r;
    for (const Pending& v : pending_) {
      if (make_record(v.p, v.wi, v.L, v.beta, v.fcos, v.pdf_bsdf, v.pdf_w, r)) out_->push_back(r);
    }
  }
  bool on() const { return out_ != nullptr; }
  // A direction wi sampled at p with density pdf_w (the BSDF's: pdf_bsdf), f |cos| there fcos; beta
  // the throughput after it.
  void vertex(const Vec3& p, const Vec3& wi, float pdf_w, float pdf_bsdf, const Color& fcos, const Color& beta) {
    if (out_ != nullptr && pdf_w > 0.f) pending_.push_back({p, wi, pdf_w, pdf_bsdf, fcos, beta, Color(0.f)});
  }
  // Adds contribution C to the path's estimate: it arrived along every direction sampled so far.
  void add(Color& L, const Color& C) {
    L += C;
    if (out_ == nullptr || is_black(C)) return;
    for (Pending& v : pending_) v.L += C;
  }

 private:
  struct Pending {
    Vec3 p, wi;
    float pdf_w, pdf_bsdf;
    Color fcos, beta, L;
  };
  GuideRecords* out_;
  std::vector<Pending> pending_;
};

// What an unguided render records: nothing (trace_path<false> compiles no guiding at all).
struct NoRecorder {
  explicit NoRecorder(GuideRecords*) {}
  static constexpr bool on() { return false; }
  void vertex(const Vec3&, const Vec3&, float, float, const Color&, const Color&) {}
  static void add(Color& L, const Color& C) { L += C; }
};

// One camera path; returns its radiance estimate. kGuided compiles the guide's sampling and
// records in.
template <bool kGuided, class Sampler>
Color trace_path(const Scene& scene, const Ray& camera_ray, const PathTracerOptions& opt, Sampler& sampler,
                 TraceCounters& counters, const PathGuiding& guiding) {
  const bool has_emitters = scene.emitter_count() > 0;
  const auto depth_allows = [&](int segments) { return opt.max_depth < 0 || segments <= opt.max_depth; };

  Color L(0.f), beta(1.f);
  std::conditional_t<kGuided, RadianceRecorder, NoRecorder> recorder(guiding.records);
  Ray ray = camera_ray;
  float prev_pdf_w = 0.f;    // solid-angle density of the BSDF sample that made `ray`
  bool prev_delta = true;    // the camera ray, like a delta bounce, cannot be found by NEE
  // `depth` is the number of segments up to and including `ray`, i.e. the index of the vertex it hits.
  for (int depth = 1; depth_allows(depth); ++depth) {
    SurfaceHit hit;
    ++counters.rays;
    if (!scene.intersect(ray, hit)) {
      if (scene.environment() != nullptr) {
        recorder.add(L, environment_seen(scene, *scene.environment(), ray.d, beta, prev_pdf_w, prev_delta,
                                         opt.strategies));
      }
      break;
    }

    const Vec3 wo_world = -ray.d;
    if (hit.emitter != nullptr) {
      recorder.add(L, emission_seen(scene, hit, wo_world, beta, prev_pdf_w, prev_delta, opt.strategies));
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
    VertexGuide guide;
    if constexpr (kGuided) {
      if (guiding.tree != nullptr) guide = vertex_guide(guiding.tree->at(hit.p), bsdf);
    }
    if (has_emitters && is_delta(bsdf)) {
      ++counters.skipped_connections;  // no light sample can meet a specular lobe
    } else if (has_emitters) {
      const float u_select = sampler.next_1d();
      const Point2 u_light = sampler.next_2d();
      recorder.add(L, next_event(scene, hit, bsdf, guide, wo_world, beta, u_select, u_light, opt.strategies,
                                 counters));
    }

    BsdfSample bs;
    const float u_guide = guide.active() ? sampler.next_1d() : 0.f;
    if (!sample_guided(bsdf, frame, guide, wo, u_guide, sampler.next_2d(), TransportMode::Radiance, bs)) break;
    beta *= bs.weight;
    prev_pdf_w = bs.pdf_w;
    prev_delta = bs.delta;
    const Vec3 wi_world = frame.to_world(bs.wi);
    if (!bs.delta && recorder.on()) {
      recorder.vertex(hit.p, wi_world, bs.pdf_w, pdf_w(bsdf, wo, bs.wi, TransportMode::Radiance),
                      bs.weight * bs.pdf_w, beta);
    }
    ray = Ray{scene.spawn_origin(hit.p, leaves_front(hit.n, hit.ns, wi_world, bs.wi.z) ? hit.n : -hit.n), wi_world};

    if (depth >= opt.rr_depth) {
      const float q = std::min(max_component(beta), 0.95f);
      if (!(sampler.next_1d() < q)) break;
      beta /= q;
    }
  }
  return L;
}

// The pixels' samples on `film`, guided by `guiding` (no tree and no collector: unguided, with
// no guiding code compiled into the path).
RenderStats drive_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                       RenderControl& control, Film& film, const PathGuiding& guiding,
                       RecordCollector* collector = nullptr) {
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, false,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  const auto drive = [&](const auto& estimate) {
    return with_sampler(options.sampler, [&](auto tag) {
      return drive_pixels<typename decltype(tag)::type>(film, driver, control, estimate);
    });
  };
  if (guiding.tree == nullptr && collector == nullptr) {
    return drive([&](float x, float y, auto& sampler, TraceCounters& counters, SplatList&) {
      return trace_path<false>(scene, scene.eye_ray(camera.generate_ray(x, y)), options, sampler, counters, {});
    });
  }
  return drive([&](float x, float y, auto& sampler, TraceCounters& counters, SplatList&) {
    PathGuiding g = guiding;
    if (collector != nullptr) g.records = &collector->local();
    return trace_path<true>(scene, scene.eye_ray(camera.generate_ray(x, y)), options, sampler, counters, g);
  });
}

// Renders the image with the guide of `trained`, then adds the training's stats.
RenderResult render_path_guided(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                                RenderControl& control) {
  const TrainedGuide trained = train_radiance_guide(scene, camera, options, control);
  const PathTracerOptions final_options = after_training(options, trained);
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats =
      drive_path(scene, camera, final_options, control, result.film, {trained.tree.get()});
  add_guiding_stats(result.stats, trained);
  return result;
}

}  // namespace

TrainedGuide train_radiance_guide(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                                  RenderControl& control) {
  return train_guide(scene, options, options, control,
                     [&](uint32_t spp, uint64_t seed, const SdTree* tree, RecordCollector& collector) {
                       const PathTracerOptions o = iteration_options(options, spp, seed);
                       Film scratch(camera.width(), camera.height());
                       return drive_path(scene, camera, o, control, scratch, {tree}, &collector);
                     });
}

RenderResult render_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                         RenderControl& control) {
  if (options.guiding) return render_path_guided(scene, camera, options, control);
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats = drive_path(scene, camera, options, control, result.film, {});
  return result;
}

}  // namespace dualight
