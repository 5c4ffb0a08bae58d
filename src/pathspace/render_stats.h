// What every image estimator reports besides its image.
#pragma once
#include <atomic>
#include <cstdint>
#include <string>

#include "film/film.h"

namespace dualight {

// Work counted by each task and summed into RenderStats.
struct TraceCounters {
  uint64_t rays = 0;
  // Connections (shadow rays) not traced because they cannot carry light: a specular vertex at
  // an end, a zero BSDF or emission term, or a point outside the camera's view.
  uint64_t skipped_connections = 0;
  // Connections that needed no shadow ray: the scene is a convex enclosure holding the camera
  // (scene_features.h), so nothing can stand between two vertices that face each other.
  uint64_t skipped_shadow_rays = 0;
  // Adjoint-driven roulette and splitting (guiding/adjoint_rr.h): paths it added, paths it stopped.
  uint64_t split_paths = 0;
  uint64_t roulette_stops = 0;
  // Not a count: whether this task's connections are known unoccluded (shadow_ray.h).
  bool unoccluded = false;
  TraceCounters& operator+=(const TraceCounters& o) {
    rays += o.rays;
    skipped_connections += o.skipped_connections;
    skipped_shadow_rays += o.skipped_shadow_rays;
    split_paths += o.split_paths;
    roulette_stops += o.roulette_stops;
    return *this;
  }
};

// What training a guide took and made (guiding/guide_training.h); `used` false for unguided renders.
struct GuidingStats {
  bool used = false;
  int iterations = 0;
  uint32_t training_spp = 0;      // samples (particles) per pixel of all iterations
  size_t records = 0;             // records of the last iteration
  size_t spatial_leaves = 0;
  size_t directional_nodes = 0;   // over all leaves
  double training_seconds = 0.0;
  double rendering_seconds = 0.0;  // the image's own render, after training
  double bsdf_fraction = 1.0;  // the leaves' mean weighted by records (guiding/sd_tree.h)
  float bsdf_fraction_min = 1.f, bsdf_fraction_max = 1.f;
  bool stopped_by_records = false;  // the next iteration would have kept more than guide_max_records
  bool stopped_by_trial = false;    // the trial during training found the guide does not pay
  bool seeded = false;               // the first iteration sampled a given guide (guide_start_*)
  bool adjoint_roulette = false;     // the image's paths played adjoint-driven roulette and splitting
  uint64_t split_paths = 0;          // paths splitting added to the image's samples
  uint64_t roulette_stops = 0;       // paths the roulette stopped
  uint32_t kept_spp = 0;             // samples per pixel of training iterations the image kept
  // The guiding trial (guiding/guiding_trial.h): whether it ran, its two passes' samples per
  // pixel and seconds (kept in the image, counted in its spp and seconds), the guided pass's
  // efficiency over the unguided one's and what it had to reach (0: no trial), the passes'
  // disagreement (above 1.15 the ratio is not trusted), and whether the image's own samples were
  // guided.
  bool trial = false;
  uint32_t trial_spp = 0;
  double trial_seconds = 0.0;
  double efficiency_ratio = 0.0;
  double trial_ratio_to_pay = 0.0;  // guiding_trial.h's ratio_to_pay
  double trial_disagreement = 0.0;
  bool rendered_guided = true;
};

struct RenderStats {
  uint64_t samples = 0;          // camera samples (paths) completed
  uint64_t rays = 0;             // closest-hit and shadow rays traced
  uint64_t skipped_connections = 0;  // see TraceCounters
  uint64_t skipped_shadow_rays = 0;  // see TraceCounters
  bool unoccluded = false;           // connections were known unoccluded: no shadow rays at all
  uint64_t invalid_samples = 0;  // NaN/Inf path contributions, zeroed and counted
  uint64_t split_paths = 0, roulette_stops = 0;  // see TraceCounters (guided path tracing only)
  uint32_t spp = 0;              // samples per pixel completed by every pixel
  double seconds = 0.0;
  bool interrupted = false;
  bool time_limited = false;     // stopped by time_limit before reaching spp
  // The path tracer's lanes (path_tracer_lanes.h): the instruction set they ran on, or null
  // (one path at a time), and then why.
  const char* lanes = nullptr;
  std::string lanes_off_because;
  GuidingStats guiding;  // the guide's (guided BDPT: the radiance guide's)
  GuidingStats importance_guiding;  // guided BDPT's importance guide
};

// TraceCounters summed over threads, and the `unoccluded` setting handed to each task's own.
class SharedTraceCounters {
 public:
  explicit SharedTraceCounters(bool unoccluded) : unoccluded_(unoccluded) {}
  TraceCounters local() const {
    TraceCounters c;
    c.unoccluded = unoccluded_;
    return c;
  }
  void add(const TraceCounters& c) {
    rays_.fetch_add(c.rays, std::memory_order_relaxed);
    skipped_connections_.fetch_add(c.skipped_connections, std::memory_order_relaxed);
    skipped_shadow_rays_.fetch_add(c.skipped_shadow_rays, std::memory_order_relaxed);
    split_paths_.fetch_add(c.split_paths, std::memory_order_relaxed);
    roulette_stops_.fetch_add(c.roulette_stops, std::memory_order_relaxed);
  }
  void into(RenderStats& stats) const {
    stats.rays = rays_.load();
    stats.skipped_connections = skipped_connections_.load();
    stats.skipped_shadow_rays = skipped_shadow_rays_.load();
    stats.split_paths = split_paths_.load();
    stats.roulette_stops = roulette_stops_.load();
    stats.unoccluded = unoccluded_;
  }

 private:
  bool unoccluded_;
  std::atomic<uint64_t> rays_{0}, skipped_connections_{0}, skipped_shadow_rays_{0}, split_paths_{0}, roulette_stops_{0};
};

struct RenderResult {
  Film film;
  RenderStats stats;
};

}  // namespace dualight
