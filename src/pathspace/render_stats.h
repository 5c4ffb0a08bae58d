// What every image estimator reports besides its image.
#pragma once
#include <cstdint>

#include "film/film.h"

namespace dualight {

// Work counted by each task and summed into RenderStats.
struct TraceCounters {
  uint64_t rays = 0;
  // Connections (shadow rays) not traced because they cannot carry light: a specular vertex at
  // an end, a zero BSDF or emission term, or a point outside the camera's view.
  uint64_t skipped_connections = 0;
  TraceCounters& operator+=(const TraceCounters& o) {
    rays += o.rays;
    skipped_connections += o.skipped_connections;
    return *this;
  }
};

struct RenderStats {
  uint64_t samples = 0;          // camera samples (paths) completed
  uint64_t rays = 0;             // closest-hit and shadow rays traced
  uint64_t skipped_connections = 0;  // see TraceCounters
  uint64_t invalid_samples = 0;  // NaN/Inf path contributions, zeroed and counted
  uint32_t spp = 0;              // samples per pixel completed by every pixel
  double seconds = 0.0;
  bool interrupted = false;
  bool time_limited = false;     // stopped by time_limit before reaching spp
};

struct RenderResult {
  Film film;
  RenderStats stats;
};

}  // namespace dualight
