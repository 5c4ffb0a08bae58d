#include "pathspace/path_tracer.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "core/frame.h"
#include "core/sampling.h"
#include "film/pixel_estimate.h"
#include "guiding/adjoint_rr.h"
#include "guiding/guide_training.h"
#include "guiding/guiding_trial.h"
#include "guiding/guided_sampling.h"
#include "materials/shading_normal.h"
#include "pathspace/next_event.h"
#include "pathspace/path_tracer_lanes.h"
#include "pathspace/pixel_driver.h"
#include "pathspace/russian_roulette.h"
#include "pathspace/shadow_ray.h"

namespace dualight {

namespace {

// The guide of a guided render (guiding/), and where a training iteration keeps its records.
// With pixel_estimate > 0 (the sample's pixel's value, estimated by the previous iteration's
// image: the final render's samples, and the training's after its first iteration) paths play
// adjoint-driven roulette and splitting (adjoint_rr.h).
struct PathGuiding {
  const SdTree* tree = nullptr;
  GuideRecords* records = nullptr;
  float pixel_estimate = 0.f;
};

// The vertices of one camera path that sampled a non-Dirac direction, with the radiance that
// arrived along each: every later contribution over the throughput there (guide_record.h). They
// become records when the path ends. Where adjoint-driven roulette splits the path, the vertices
// form a tree: each knows the vertex before it on its branch, and a contribution arrived along the
// directions of its branch's vertices only.
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
  // the throughput after it; `before` the branch's last vertex (-1: none). Returns the new vertex
  // (`before` when it is not kept).
  int vertex(const Vec3& p, const Vec3& wi, float pdf_w, float pdf_bsdf, const Color& fcos, const Color& beta,
             int before) {
    if (out_ == nullptr || !(pdf_w > 0.f)) return before;
    pending_.push_back({p, wi, pdf_w, pdf_bsdf, fcos, beta, Color(0.f), before});
    return static_cast<int>(pending_.size()) - 1;
  }
  // Adds contribution C to the path's estimate: it arrived along every direction sampled on its
  // branch up to vertex `last`.
  void add(Color& L, const Color& C, int last) {
    L += C;
    if (out_ == nullptr || is_black(C)) return;
    for (int i = last; i >= 0; i = pending_[static_cast<size_t>(i)].before) pending_[static_cast<size_t>(i)].L += C;
  }

 private:
  struct Pending {
    Vec3 p, wi;
    float pdf_w, pdf_bsdf;
    Color fcos, beta, L;
    int before;
  };
  GuideRecords* out_;
  std::vector<Pending> pending_;
};

// What an unguided render records: nothing (trace_path<false> compiles no guiding at all).
struct NoRecorder {
  explicit NoRecorder(GuideRecords*) {}
  static constexpr bool on() { return false; }
  int vertex(const Vec3&, const Vec3&, float, float, const Color&, const Color&, int before) { return before; }
  static void add(Color& L, const Color& C, int) { L += C; }
};

// Where a camera path is between two vertices.
struct CameraPathState {
  Ray ray;
  Color beta{1.f};
  float prev_pdf_w = 0.f;   // solid-angle density of the BSDF sample that made `ray`
  bool prev_delta = true;   // the camera ray, like a delta bounce, cannot be found by NEE
  int depth = 1;            // the number of segments up to and including `ray`: the index of the vertex it hits
  int paths = 1;            // how many paths splitting has made of the camera sample so far
  int recorded = -1;        // the recorder's last vertex on this path's branch (-1: none)
  float roulette_scale = 1.f;  // russian_roulette.h
};

// Adjoint-driven roulette and splitting (adjoint_rr.h) for a path at a vertex of `leaf`, in a
// pixel of estimated value `pixel`: scales the path's throughput and counts its paths.
inline RouletteOrSplit roulette_or_split(const SdTree::Leaf& leaf, float pixel, float u, CameraPathState& s,
                                         TraceCounters& counters) {
  const RouletteOrSplit go_on =
      adjoint_roulette(average(s.beta), leaf.reflected, pixel, s.paths, u, AdjointRouletteSettings{});
  if (go_on.paths == 0) {
    ++counters.roulette_stops;
    return go_on;
  }
  counters.split_paths += static_cast<uint64_t>(go_on.paths - 1);
  s.beta *= go_on.scale;
  s.paths *= go_on.paths;
  return go_on;
}

// Follows a camera path from state s, adding what it finds to L; where adjoint-driven roulette
// splits it, the extra paths are followed by recursion. kGuided compiles the guide's sampling,
// records and roulette in.
template <bool kGuided, class Sampler, class Recorder>
void extend_path(const Scene& scene, const PathTracerOptions& opt, Sampler& sampler, TraceCounters& counters,
                 const PathGuiding& guiding, Recorder& recorder, CameraPathState s, Color& L) {
  const bool has_emitters = scene.emitter_count() > 0;
  const auto depth_allows = [&](int segments) { return opt.max_depth < 0 || segments <= opt.max_depth; };
  for (; depth_allows(s.depth); ++s.depth) {
    SurfaceHit hit;
    ++counters.rays;
    if (!scene.intersect(s.ray, hit)) {
      if (scene.environment() != nullptr) {
        recorder.add(L, environment_seen(scene, *scene.environment(), s.ray.d, s.beta, s.prev_pdf_w, s.prev_delta,
                                         opt.strategies),
                     s.recorded);
      }
      return;
    }

    const Vec3 wo_world = -s.ray.d;
    if (hit.emitter != nullptr) {
      recorder.add(L, emission_seen(scene, hit, wo_world, s.beta, s.prev_pdf_w, s.prev_delta, opt.strategies),
                   s.recorded);
    }
    if (!depth_allows(s.depth + 1)) return;

    // The BSDF's frame is the shading normal's (it tells a dielectric's inside from its
    // outside); two-sided BSDFs handle wo.z < 0 themselves. Radiance transport needs no
    // correction for shading normals (materials/shading_normal.h).
    const Frame frame = Frame::from_normal(hit.ns);
    const Vec3 wo = frame.to_local(wo_world);
    std::optional<Bsdf> textured;  // engaged only where textures change the material's BSDF
    const Bsdf& bsdf = hit.material->textured() ? textured.emplace(hit.material->bsdf_at(hit.uv))
                                                : hit.material->bsdf;
    VertexGuide guide;
    const SdTree::Leaf* leaf = nullptr;
    if constexpr (kGuided) {
      if (guiding.tree != nullptr) {
        leaf = &guiding.tree->at(hit.p);
        guide = vertex_guide(*leaf, bsdf);
      }
    }
    if (has_emitters && is_delta(bsdf)) {
      ++counters.skipped_connections;  // no light sample can meet a specular lobe
    } else if (has_emitters) {
      const float u_select = sampler.next_1d();
      const Point2 u_light = sampler.next_2d();
      recorder.add(L,
                   next_event(scene, hit, bsdf, guide, wo_world, s.beta, u_select, u_light, opt.strategies, counters),
                   s.recorded);
    }

    RouletteOrSplit go_on;
    if constexpr (kGuided) {
      if (guiding.pixel_estimate > 0.f && leaf != nullptr) {
        go_on = roulette_or_split(*leaf, guiding.pixel_estimate, sampler.next_1d(), s, counters);
        if (go_on.paths == 0) return;
      }
    }
    // The path leaves the vertex in a sampled direction: false where it ends there.
    const auto leave = [&](CameraPathState& next) {
      BsdfSample bs;
      const float u_guide = guide.active() ? sampler.next_1d() : 0.f;
      float bsdf_ratio;
      if (!sample_guided(bsdf, frame, guide, wo, u_guide, sampler.next_2d(), TransportMode::Radiance, bs, bsdf_ratio)) {
        return false;
      }
      next.beta *= bs.weight;
      next.roulette_scale *= roulette_scale(bs, TransportMode::Radiance, bsdf_ratio);
      next.prev_pdf_w = bs.pdf_w;
      next.prev_delta = bs.delta;
      const Vec3 wi_world = frame.to_world(bs.wi);
      if (!bs.delta && recorder.on()) {
        next.recorded = recorder.vertex(hit.p, wi_world, bs.pdf_w, pdf_w(bsdf, wo, bs.wi, TransportMode::Radiance),
                                        bs.weight * bs.pdf_w, next.beta, next.recorded);
      }
      next.ray = Ray{scene.spawn_origin(hit.p, leaves_front(hit.n, hit.ns, wi_world, bs.wi.z) ? hit.n : -hit.n),
                     wi_world};
      if (!go_on.known && next.depth >= opt.rr_depth) {
        const float q = roulette_survival(next.beta, next.roulette_scale);
        if (!(sampler.next_1d() < q)) return false;
        next.beta /= q;
      }
      return true;
    };
    for (int i = 1; i < go_on.paths; ++i) {
      CameraPathState split = s;
      if (leave(split)) {
        ++split.depth;
        extend_path<kGuided>(scene, opt, sampler, counters, guiding, recorder, split, L);
      }
    }
    if (!leave(s)) return;
  }
}

// One camera path; returns its radiance estimate.
template <bool kGuided, class Sampler>
Color trace_path(const Scene& scene, const Ray& camera_ray, const PathTracerOptions& opt, Sampler& sampler,
                 TraceCounters& counters, const PathGuiding& guiding) {
  Color L(0.f);
  std::conditional_t<kGuided, RadianceRecorder, NoRecorder> recorder(guiding.records);
  CameraPathState start;
  start.ray = camera_ray;
  extend_path<kGuided>(scene, opt, sampler, counters, guiding, recorder, start, L);
  return L;
}

// The kernel of `kernels` for samples of class Sampler.
template <class Sampler>
TracePathLanes<Sampler> lanes_for(const PathLanesKernels& kernels) {
  if constexpr (std::is_same_v<Sampler, SobolSampler>) {
    return kernels.sobol;
  } else {
    return kernels.independent;
  }
}

// The pixels' samples on `film` by the path tracer in lanes (path_tracer_lanes.h): the image
// drive_path's unguided estimate makes, bit for bit.
RenderStats drive_path_lanes(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                             RenderControl& control, Film& film, const PixelDriverOptions& driver,
                             const PathLanesKernels& kernels) {
  const PathLanesScene ps = path_lanes_scene(scene, camera, options);
  RenderStats stats = with_sampler(options.sampler, [&](auto tag) {
    using Sampler = typename decltype(tag)::type;
    const TracePathLanes<Sampler> trace = lanes_for<Sampler>(kernels);
    return drive_pixels<Sampler>(
        film, driver, control,
        batch_estimate(
            [&](const PixelSample* samples, size_t n, TraceCounters& counters, Color* values) {
              trace(ps, driver.seed, film.width(), samples, n, counters, values);
            }));
  });
  stats.lanes = kernels.isa;
  return stats;
}

// The pixels' samples on `film`, guided by `guiding` (no tree and no collector: unguided, with
// no guiding code compiled into the path).
// pixel_estimates (when not null and not empty): each pixel's estimated value, for adjoint-driven roulette.
RenderStats drive_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                       RenderControl& control, Film& film, const PathGuiding& guiding,
                       RecordCollector* collector = nullptr, const std::vector<float>* pixel_estimates = nullptr) {
  const PixelDriverOptions driver{options.spp, options.seed, options.threads, options.time_limit, false,
                                  connections_unoccluded(scene, camera, options.skip_unneeded), options.first_sample};
  const auto drive = [&](const auto& estimate) {
    return with_sampler(options.sampler, [&](auto tag) {
      return drive_pixels<typename decltype(tag)::type>(film, driver, control, estimate);
    });
  };
  if (guiding.tree == nullptr && collector == nullptr) {
    const PathLanesChoice lanes = choose_path_lanes(scene, options);
    if (lanes.kernels) return drive_path_lanes(scene, camera, options, control, film, driver, *lanes.kernels);
    RenderStats stats = drive([&](float x, float y, auto& sampler, TraceCounters& counters, SplatList&) {
      return trace_path<false>(scene, scene.eye_ray(camera.generate_ray(x, y)), options, sampler, counters, {});
    });
    stats.lanes_off_because = lanes.why_not;
    return stats;
  }
  return drive([&](float x, float y, auto& sampler, TraceCounters& counters, SplatList&) {
    PathGuiding g = guiding;
    if (collector != nullptr) g.records = &collector->local();
    if (pixel_estimates != nullptr && !pixel_estimates->empty()) {
      const int px = std::clamp(static_cast<int>(x), 0, camera.width() - 1);
      const int py = std::clamp(static_cast<int>(y), 0, camera.height() - 1);
      g.pixel_estimate = (*pixel_estimates)[static_cast<size_t>(py) * camera.width() + px];
    }
    return trace_path<true>(scene, scene.eye_ray(camera.generate_ray(x, y)), options, sampler, counters, g);
  });
}

// Each pixel's estimated value for adjoint-driven roulette: the training's last image blurred over
// 3x3 pixels, at least 1 % of its mean (a pixel the training saw dark still has paths go on);
// empty where the training left no image.
std::vector<float> pixel_estimates(const std::vector<double>& image, const PinholeCamera& camera) {
  if (image.empty()) return {};
  const std::vector<double> blurred = box_blurred(image, camera.width(), camera.height(), 1);
  double mean = 0.0;
  for (const double v : blurred) mean += v;
  mean /= static_cast<double>(blurred.size());
  if (!(mean > 0.0) || !std::isfinite(mean)) return {};
  std::vector<float> out(blurred.size());
  for (size_t i = 0; i < out.size(); ++i) out[i] = static_cast<float>(std::max(blurred[i], 0.01 * mean));
  return out;
}

// The pixel estimates adjoint-driven roulette plays against, from a guide's last training image.
std::vector<float> roulette_estimates(const TrainedGuide& trained, const PathTracerOptions& options,
                                      const PinholeCamera& camera) {
  if (!options.guide_adjoint_roulette || !trained.last_image) return {};
  return pixel_estimates(film_luminance(*trained.last_image), camera);
}

// Renders `film` guided by `trained` (with its roulette) or unguided.
RenderStats drive_path_with(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                            RenderControl& control, Film& film, const TrainedGuide* trained) {
  if (trained == nullptr) return drive_path(scene, camera, options, control, film, {});
  const std::vector<float> estimates = roulette_estimates(*trained, options, camera);
  return drive_path(scene, camera, options, control, film, {trained->tree.get()}, nullptr, &estimates);
}

// The radiance guide's training; `checkpoint` as train_guides's.
TrainedGuide train_radiance_guide_with(const Scene& scene, const PinholeCamera& camera,
                                       const PathTracerOptions& options, RenderControl& control,
                                       const TrainingCheckpoint<1>* checkpoint) {
  // With adjoint-driven roulette, iterations after the first play it too, from the previous
  // iteration's image and tree: their samples are then like the image's, worth keeping.
  std::vector<float> estimates;
  return train_guide(
      scene, options, options, camera.width(), camera.height(), control, options.guide_start_radiance,
      [&](uint32_t spp, uint64_t seed, const SdTree* tree, RecordCollector& collector, Film& film) {
        const PathTracerOptions o = iteration_options(options, spp, seed);
        const RenderStats s = drive_path(scene, camera, o, control, film, {tree}, &collector, &estimates);
        if (options.guide_adjoint_roulette) estimates = pixel_estimates(film_luminance(film), camera);
        return s;
      },
      checkpoint);
}

// Trains the radiance guide, tries whether it pays (guiding_trial.h: during the training, which
// it may stop, or after it), renders the image guided or not, and adds the training's and the
// trial's stats and samples.
RenderResult render_path_guided(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                                RenderControl& control) {
  std::optional<GuidingTrial> trial;
  const auto try_guide = [&](const TrainedGuide& t, bool during_training) {
    trial = try_guiding_trial(options, options, t, t.tree != nullptr, during_training, camera.width(), camera.height(),
                              [&](bool guided, uint32_t spp, uint64_t seed, Film& film) {
                                return drive_path_with(scene, camera, iteration_options(options, spp, seed), control,
                                                       film, guided ? &t : nullptr);
                              });
    return trial && !trial->guided;
  };
  const TrainingCheckpoint<1> checkpoint = [&](const std::array<TrainedGuide, 1>& t) {
    return try_guide(t[0], true);
  };
  TrainedGuide trained = train_radiance_guide_with(scene, camera, options, control, &checkpoint);
  if (control.cancelled()) return interrupted_in_training(std::move(trained), camera.width(), camera.height());
  if (!trial) try_guide(trained, false);
  const bool guided = !trial || trial->guided;
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats = drive_path_with(scene, camera, after_trial(after_training(options, trained), trial), control,
                                 result.film, guided ? &trained : nullptr);
  add_guiding_stats(result.stats, trained);
  keep_training_samples(result.film, result.stats, trained);
  keep_trial(result.film, result.stats, trial);
  result.stats.guiding.adjoint_roulette = guided && !roulette_estimates(trained, options, camera).empty();
  result.stats.guiding.split_paths = result.stats.split_paths;
  result.stats.guiding.roulette_stops = result.stats.roulette_stops;
  return result;
}

}  // namespace

TrainedGuide train_radiance_guide(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                                  RenderControl& control) {
  return train_radiance_guide_with(scene, camera, options, control, nullptr);
}

RenderResult render_path(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options,
                         RenderControl& control) {
  if (options.guiding) return render_path_guided(scene, camera, options, control);
  RenderResult result{Film(camera.width(), camera.height()), {}};
  result.stats = drive_path(scene, camera, options, control, result.film, {});
  return result;
}

}  // namespace dualight
