// Drives any per-pixel estimator: tiles on TBB threads, progressive passes of samples per pixel,
// a time limit, cancellation, and stats. Each (pixel, sample index) pair gets its own random
// stream, so the image is the same for any thread count, pass size or schedule.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>

#include "core/parallel.h"
#include "core/render_control.h"
#include "core/sampler.h"
#include "film/film.h"
#include "film/splat_list.h"
#include "pathspace/render_stats.h"
#include "pathspace/shadow_ray.h"

namespace dualight {

struct PixelDriverOptions {
  uint32_t spp = 64;  // 0 = until time_limit
  uint64_t seed = 0;
  int threads = 0;
  double time_limit = 0.0;
  bool light_paths = false;  // every sample also traces one light path that may splat
  bool unoccluded = false;   // connections need no shadow rays (shadow_ray.h)
};

// estimate(x, y, sampler, counters, splats) returns the sample value for film position (x, y)
// in pixels, adds the rays it traced (and connections it skipped) to `counters` and its light path's splats to `splats`. The film
// position uses the sampler's first 2D sample. Each tile collects its splats in a list of its own;
// the lists are added to the film in tile order after every pass.
template <class Sampler, class Estimate>
RenderStats drive_pixels(Film& film, const PixelDriverOptions& opt, RenderControl& control,
                         const Estimate& estimate) {
  using Clock = std::chrono::steady_clock;
  constexpr int kTile = 16;
  const int w = film.width(), h = film.height();
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
  const size_t n_tiles = static_cast<size_t>(tiles_x) * tiles_y;
  const uint64_t n_pixels = static_cast<uint64_t>(w) * h;
  const bool unbounded = opt.spp == 0;
  control.total.store(unbounded ? 0 : n_pixels * opt.spp);

  std::atomic<uint64_t> rays{0}, skipped{0}, skipped_shadow{0}, invalid{0};
  std::vector<SplatList> tile_splats(opt.light_paths ? n_tiles : 0);
  std::vector<uint64_t> tile_samples(n_tiles, 0);
  SplatList no_splats;  // estimators without light paths never add to it
  RenderStats stats;
  const auto start = Clock::now();
  auto elapsed = [&] { return std::chrono::duration<double>(Clock::now() - start).count(); };

  uint32_t spp_done = 0;
  uint32_t pass_spp = 1;
  while ((unbounded || spp_done < opt.spp) && !control.cancelled()) {
    if (opt.time_limit > 0.0 && elapsed() >= opt.time_limit) {
      stats.time_limited = true;
      break;
    }
    const uint32_t first = spp_done;
    const uint32_t count = unbounded ? pass_spp : std::min(pass_spp, opt.spp - spp_done);
    const double pass_start = elapsed();
    parallel_for_each_index(opt.threads, n_tiles, [&](size_t tile) {
      const int x0 = static_cast<int>(tile % tiles_x) * kTile, y0 = static_cast<int>(tile / tiles_x) * kTile;
      TraceCounters local = trace_counters(opt.unoccluded);
      uint64_t local_invalid = 0;
      SplatList& splats = opt.light_paths ? tile_splats[tile] : no_splats;
      splats.clear();
      tile_samples[tile] = 0;
      for (int y = y0; y < std::min(y0 + kTile, h); ++y) {
        for (int x = x0; x < std::min(x0 + kTile, w); ++x) {
          if (control.cancelled()) break;
          const size_t pixel = static_cast<size_t>(y) * w + x;
          for (uint32_t s = first; s < first + count; ++s) {
            Sampler sampler(opt.seed, pixel, s);
            const Point2 jitter = sampler.next_2d();
            splats.begin_path();
            Color value = estimate(static_cast<float>(x) + jitter.u, static_cast<float>(y) + jitter.v, sampler,
                                   local, splats);
            splats.end_path();
            if (!is_finite(value)) {
              value = Color(0.f);
              ++local_invalid;
            }
            film.add_sample(pixel, value);
          }
          tile_samples[tile] += count;
          control.done.fetch_add(count, std::memory_order_relaxed);
        }
      }
      rays.fetch_add(local.rays, std::memory_order_relaxed);
      skipped.fetch_add(local.skipped_connections, std::memory_order_relaxed);
      skipped_shadow.fetch_add(local.skipped_shadow_rays, std::memory_order_relaxed);
      invalid.fetch_add(local_invalid, std::memory_order_relaxed);
    });
    if (opt.light_paths) {
      for (size_t tile = 0; tile < n_tiles; ++tile) {
        film.add_splats(tile_splats[tile], tile_samples[tile]);
        invalid.fetch_add(tile_splats[tile].invalid(), std::memory_order_relaxed);
      }
    }
    if (control.cancelled()) break;
    spp_done += count;
    // Aim for passes of about a quarter second so time limits and progress stay responsive, and
    // at most half the time left under a time limit, so that the last pass overshoots little.
    const double pass_seconds = std::max(elapsed() - pass_start, 1e-6);
    const double per_spp = pass_seconds / count;
    const double aim = opt.time_limit > 0.0 ? std::clamp(0.5 * (opt.time_limit - elapsed()), 1e-3, 0.25) : 0.25;
    pass_spp = static_cast<uint32_t>(std::clamp(aim / per_spp, 1.0, 4096.0));
  }

  stats.seconds = elapsed();
  stats.rays = rays.load();
  stats.skipped_connections = skipped.load();
  stats.skipped_shadow_rays = skipped_shadow.load();
  stats.unoccluded = opt.unoccluded;
  stats.invalid_samples = invalid.load();
  stats.interrupted = control.cancelled();
  const std::vector<uint32_t> counts = film.sample_counts();
  uint64_t total = 0;
  uint32_t min_count = counts.empty() ? 0 : counts[0];
  for (const uint32_t c : counts) {
    total += c;
    min_count = std::min(min_count, c);
  }
  stats.samples = total;
  stats.spp = min_count;
  return stats;
}

}  // namespace dualight
