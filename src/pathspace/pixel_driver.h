// Drives any per-pixel estimator: tiles on TBB threads, progressive passes of samples per pixel,
// a time limit, cancellation, and stats. Each (pixel, sample index) pair gets its own random
// stream, and every sum has a fixed order (a pixel's samples in sample order; splats in order of
// sample index, then tile, then pixel; both within blocks of kBlockSpp sample indices, film.h),
// so the image is the same for any thread count, pass size, schedule, or split into tasks of
// whole blocks (first_sample a multiple of kBlockSpp).
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "core/stopwatch.h"
#include "core/render_control.h"
#include "core/sampler.h"
#include "film/film.h"
#include "film/splat_list.h"
#include "pathspace/render_stats.h"

namespace dualight {

struct PixelDriverOptions {
  uint32_t spp = 64;  // 0 = until time_limit
  uint64_t seed = 0;
  int threads = 0;
  double time_limit = 0.0;
  bool light_paths = false;  // every sample also traces one light path that may splat
  bool unoccluded = false;   // connections need no shadow rays (shadow_ray.h)
  uint32_t first_sample = 0;  // renders sample indices [first_sample, first_sample + spp)
};

// estimate(x, y, sampler, counters, splats) returns the sample value for film position (x, y)
// in pixels, adds the rays it traced (and connections it skipped) to `counters` and its light path's splats to `splats`. The film
// position uses the sampler's first 2D sample. Each tile collects its splats in a list of its own,
// sample index by sample index; after every pass they are added to the film by sample index, then
// in tile order.
template <class Sampler, class Estimate>
RenderStats drive_pixels(Film& film, const PixelDriverOptions& opt, RenderControl& control,
                         const Estimate& estimate) {
  constexpr int kTile = 16;
  const int w = film.width(), h = film.height();
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
  const size_t n_tiles = static_cast<size_t>(tiles_x) * tiles_y;
  const uint64_t n_pixels = static_cast<uint64_t>(w) * h;
  const bool unbounded = opt.spp == 0;
  control.total.store(unbounded ? 0 : n_pixels * opt.spp);

  SharedTraceCounters work(opt.unoccluded);
  std::atomic<uint64_t> invalid{0};
  // Per tile: its splats, and for each sample index of the pass where they end and how many
  // pixels (light paths) it covered.
  struct TileSplats {
    SplatList list;
    std::vector<std::pair<size_t, uint32_t>> rows;
  };
  std::vector<TileSplats> tile_splats(opt.light_paths ? n_tiles : 0);
  SplatList no_splats;  // estimators without light paths never add to it
  RenderStats stats;
  const Stopwatch elapsed;
  const auto block_ends_at = [](uint32_t s) { return (s + 1) % kBlockSpp == 0; };

  uint32_t spp_done = 0;
  uint32_t pass_spp = 1;
  while ((unbounded || spp_done < opt.spp) && !control.cancelled()) {
    if (opt.time_limit > 0.0 && elapsed() >= opt.time_limit) {
      stats.time_limited = true;
      break;
    }
    const uint32_t first = opt.first_sample + spp_done;
    const uint32_t count = unbounded ? pass_spp : std::min(pass_spp, opt.spp - spp_done);
    const double pass_start = elapsed();
    parallel_for_each_index(opt.threads, n_tiles, [&](size_t tile) {
      const int x0 = static_cast<int>(tile % tiles_x) * kTile, y0 = static_cast<int>(tile / tiles_x) * kTile;
      const int x1 = std::min(x0 + kTile, w), y1 = std::min(y0 + kTile, h);
      TraceCounters local = work.local();
      uint64_t local_invalid = 0;
      SplatList& splats = opt.light_paths ? tile_splats[tile].list : no_splats;
      splats.clear();
      if (opt.light_paths) tile_splats[tile].rows.clear();
      // Sample index by sample index, so that the tile's splats come grouped by sample index.
      for (uint32_t s = first; s < first + count && !control.cancelled(); ++s) {
        uint32_t row_paths = 0;
        for (int y = y0; y < y1; ++y) {
          for (int x = x0; x < x1; ++x) {
            const size_t pixel = static_cast<size_t>(y) * w + x;
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
            if (block_ends_at(s)) film.end_block(pixel);
            ++row_paths;
          }
          if (control.cancelled()) break;
        }
        if (opt.light_paths) tile_splats[tile].rows.emplace_back(splats.splats().size(), row_paths);
        control.done.fetch_add(row_paths, std::memory_order_relaxed);
      }
      work.add(local);
      invalid.fetch_add(local_invalid, std::memory_order_relaxed);
    });
    if (opt.light_paths) {
      std::vector<size_t> begin(n_tiles, 0);
      for (uint32_t i = 0; i < count; ++i) {
        for (size_t tile = 0; tile < n_tiles; ++tile) {
          TileSplats& t = tile_splats[tile];
          if (i >= t.rows.size()) continue;  // cancelled before this sample index
          const Splat* data = t.list.splats().data();
          film.add_splats(data + begin[tile], data + t.rows[i].first, t.rows[i].second);
          begin[tile] = t.rows[i].first;
        }
        if (block_ends_at(first + i)) film.end_splat_block();
      }
      for (const TileSplats& t : tile_splats) invalid.fetch_add(t.list.invalid(), std::memory_order_relaxed);
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
  film.end_blocks();  // the last block, when the render ends inside one

  stats.seconds = elapsed();
  work.into(stats);
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
