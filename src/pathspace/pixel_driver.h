// Drives any per-pixel estimator: tiles (or rows of them) on TBB threads, progressive passes of
// samples per pixel, a time limit, cancellation, and stats. Each (pixel, sample index) pair gets
// its own random stream, and every sum has a fixed order (a pixel's samples in sample order;
// splats in order of sample index, then tile, then pixel; both within blocks of kBlockSpp sample
// indices, film.h), so the image is the same for any thread count, pass size, schedule, or split
// into tasks of whole blocks (first_sample a multiple of kBlockSpp).
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

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

namespace pixel_driver_detail {
constexpr int kTile = 16;
}  // namespace pixel_driver_detail

// A pixel sample: pixel (x, y) at sample index s.
struct PixelSample {
  int x, y;
  uint32_t s;
};

// A batch estimate estimates many pixel samples in one call (the path tracer in lanes,
// path_tracer_lanes.h, which keeps its lanes busy with them): f(samples, n, counters, values)
// writes values[i], the estimate of samples[i], and starts each sample with start_sample (its
// sampler and film position, as for a per-pixel estimate). Batch estimates take no splats.
template <class F>
struct BatchEstimate {
  F f;
};
template <class F>
BatchEstimate<F> batch_estimate(F f) {
  return {std::move(f)};
}

// A per-pixel estimate f whose rows are prepared first: begin_row(x0, x1, y, s, counters) runs
// before the pixels [x0, x1) of row y (a tile's row) are estimated at sample index s, on the
// thread that then estimates them (BDPT's light pool, bdpt.cpp).
template <class F, class B>
struct RowEstimate {
  F f;
  B begin_row;
};
template <class F, class B>
RowEstimate<F, B> row_estimate(F f, B begin_row) {
  return {std::move(f), std::move(begin_row)};
}
template <class T>
struct is_row_estimate : std::false_type {};
template <class F, class B>
struct is_row_estimate<RowEstimate<F, B>> : std::true_type {};

// Pixel x's coordinate plus a jitter in [0, 1), kept inside the pixel: in floats x + jitter
// rounds up to x + 1 when the jitter lies within half a float spacing of 1 (2^-24 at x = 1,
// 2^-19 at x = 32), and its integer part is then the next pixel, past the film at its last one.
inline float in_pixel(int x, float jitter) {
  const float next = static_cast<float>(x + 1);
  return std::min(static_cast<float>(x) + jitter, std::nextafter(next, 0.f));
}

// Sample p's sampler (its own random stream, in `sampler`) and the film position its first 2D
// sample picks in the pixel, whose integer parts are the pixel's (estimates find their pixel
// from them).
template <class Sampler>
Point2 start_sample(uint64_t seed, int film_width, const PixelSample& p, std::optional<Sampler>& sampler) {
  const Point2 jitter =
      sampler.emplace(seed, static_cast<size_t>(p.y) * static_cast<size_t>(film_width) + p.x, p.s).next_2d();
  return {in_pixel(p.x, jitter.u), in_pixel(p.y, jitter.v)};
}

namespace pixel_driver_detail {

inline bool block_ends_at(uint32_t s) { return (s + 1) % kBlockSpp == 0; }

// Rows of a tile per unit of work: single rows where several workers share few tiles (a 64x64
// image has 16), so that every worker stays busy up to a pass's end and small images still have
// work for many workers; else whole tiles (fewer, larger tasks).
constexpr size_t kTilesPerWorker = 64;
inline int unit_rows(size_t n_tiles, int threads) {
  const int workers = worker_count(threads);
  return workers > 1 && n_tiles < kTilesPerWorker * static_cast<size_t>(workers) ? 1 : kTile;
}

// A unit's splats (a tile's, or a row of one), and for each sample index of the pass where they
// end and how many pixels (light paths) it covered.
struct TileSplats {
  SplatList list;
  std::vector<std::pair<size_t, uint32_t>> sample_ends;
};

struct TileRect {
  int x0, y0, x1, y1;
};

// Adds sample s's value to `pixel` (zero, counted invalid, where not finite).
inline void add_sample(Film& film, size_t pixel, uint32_t s, Color value, uint64_t& invalid) {
  if (!is_finite(value)) {
    value = Color(0.f);
    ++invalid;
  }
  film.add_sample(pixel, value);
  if (block_ends_at(s)) film.end_block(pixel);
}

// Sample index s of the pixels [x0, x1) of row y, one estimate call each (a row estimate's
// begin_row first); returns how many.
template <class Sampler, class Estimate>
uint32_t render_row(Film& film, const PixelDriverOptions& opt, int x0, int x1, int y, uint32_t s,
                    const Estimate& estimate, TraceCounters& local, uint64_t& invalid, SplatList& splats) {
  if constexpr (is_row_estimate<Estimate>::value) {
    estimate.begin_row(x0, x1, y, s, local);
    return render_row<Sampler>(film, opt, x0, x1, y, s, estimate.f, local, invalid, splats);
  } else {
    std::optional<Sampler> sampler;
    for (int x = x0; x < x1; ++x) {
      const Point2 position = start_sample(opt.seed, film.width(), {x, y, s}, sampler);
      splats.begin_path();
      const Color value = estimate(position.u, position.v, *sampler, local, splats);
      splats.end_path();
      add_sample(film, static_cast<size_t>(y) * film.width() + x, s, value, invalid);
    }
    return static_cast<uint32_t>(x1 - x0);
  }
}

// Sample indices [first, first + count) of every pixel of a tile (or of a row of one), sample
// index by sample index (so the splats come grouped by sample index); `sample_ends` (may be
// null) records where each sample index's splats end.
template <class Sampler, class Estimate>
void render_tile(Film& film, const PixelDriverOptions& opt, const TileRect& r, uint32_t first, uint32_t count,
                 const Estimate& estimate, RenderControl& control, TraceCounters& local, uint64_t& invalid,
                 SplatList& splats, std::vector<std::pair<size_t, uint32_t>>* sample_ends) {
  for (uint32_t s = first; s < first + count && !control.cancelled(); ++s) {
    uint32_t row_paths = 0;
    for (int y = r.y0; y < r.y1; ++y) {
      row_paths += render_row<Sampler>(film, opt, r.x0, r.x1, y, s, estimate, local, invalid, splats);
      if (control.cancelled()) break;
    }
    if (sample_ends != nullptr) sample_ends->emplace_back(splats.splats().size(), row_paths);
    control.done.fetch_add(row_paths, std::memory_order_relaxed);
  }
}

// The same for a batch estimate: the same samples, pixel by pixel (each pixel's by sample index)
// in batches of up to kBatch, their values added to the film in that order, so every pixel adds
// its samples in the same order and the image is the same. A pixel's samples in a row let the
// path tracer's lanes trace their camera rays as coherent packets (path_lanes_kernel.h,
// CameraRays). Cancellation is seen between batches.
constexpr size_t kBatch = static_cast<size_t>(kTile) * kTile;
template <class Sampler, class F>
void render_tile(Film& film, const PixelDriverOptions&, const TileRect& r, uint32_t first, uint32_t count,
                 const BatchEstimate<F>& estimate, RenderControl& control, TraceCounters& local, uint64_t& invalid,
                 SplatList&, std::vector<std::pair<size_t, uint32_t>>* sample_ends) {
  if (sample_ends != nullptr) throw std::logic_error("batch estimates take no light paths");
  std::array<PixelSample, kBatch> batch;
  std::array<Color, kBatch> values;
  size_t n = 0;
  const auto flush = [&] {
    estimate.f(batch.data(), n, local, values.data());
    for (size_t i = 0; i < n; ++i) {
      const PixelSample& p = batch[i];
      add_sample(film, static_cast<size_t>(p.y) * film.width() + p.x, p.s, values[i], invalid);
    }
    control.done.fetch_add(n, std::memory_order_relaxed);
    n = 0;
  };
  for (int y = r.y0; y < r.y1; ++y) {
    for (int x = r.x0; x < r.x1; ++x) {
      for (uint32_t s = first; s < first + count; ++s) {
        if (n == kBatch) {
          flush();
          if (control.cancelled()) return;
        }
        batch[n++] = {x, y, s};
      }
    }
  }
  flush();
}

// Adds the pass's splats to the film by sample index, then in unit order: `units` holds each
// tile's units (the tile, or its rows) in turn, so that is tile order, and row order within a tile.
inline void merge_tile_splats(Film& film, std::vector<TileSplats>& units, uint32_t first, uint32_t count,
                              std::atomic<uint64_t>& invalid) {
  std::vector<size_t> begin(units.size(), 0);
  for (uint32_t i = 0; i < count; ++i) {
    for (size_t unit = 0; unit < units.size(); ++unit) {
      TileSplats& t = units[unit];
      // None: cancelled before this sample index, or a row below the image.
      if (i >= t.sample_ends.size()) continue;
      const Splat* data = t.list.splats().data();
      film.add_splats(data + begin[unit], data + t.sample_ends[i].first, t.sample_ends[i].second);
      begin[unit] = t.sample_ends[i].first;
    }
    if (block_ends_at(first + i)) film.end_splat_block();
  }
  for (const TileSplats& t : units) invalid.fetch_add(t.list.invalid(), std::memory_order_relaxed);
}

// Samples per pixel of the next pass: about a quarter second so time limits and progress stay
// responsive, and at most half the time left under a time limit, so the last pass overshoots little.
inline uint32_t next_pass_spp(double pass_seconds, uint32_t count, double time_limit, double now) {
  const double per_spp = std::max(pass_seconds, 1e-6) / count;
  const double aim = time_limit > 0.0 ? std::clamp(0.5 * (time_limit - now), 1e-3, 0.25) : 0.25;
  return static_cast<uint32_t>(std::clamp(aim / per_spp, 1.0, 4096.0));
}

// The samples every pixel got: their total, and the smallest count (the render's spp).
inline void count_samples(const Film& film, RenderStats& stats) {
  const std::vector<uint32_t> counts = film.sample_counts();
  uint64_t total = 0;
  uint32_t min_count = counts.empty() ? 0 : counts[0];
  for (const uint32_t c : counts) {
    total += c;
    min_count = std::min(min_count, c);
  }
  stats.samples = total;
  stats.spp = min_count;
}

}  // namespace pixel_driver_detail

// estimate(x, y, sampler, counters, splats) returns the sample value for film position (x, y)
// in pixels, adds the rays it traced (and connections it skipped) to `counters` and its light
// path's splats to `splats`. The film position uses the sampler's first 2D sample. Each tile
// collects its splats in a list of its own, sample index by sample index; after every pass they
// are added to the film by sample index, then in tile order.
template <class Sampler, class Estimate>
RenderStats drive_pixels(Film& film, const PixelDriverOptions& opt, RenderControl& control,
                         const Estimate& estimate) {
  using namespace pixel_driver_detail;
  const int w = film.width(), h = film.height();
  const int tiles_x = (w + kTile - 1) / kTile, tiles_y = (h + kTile - 1) / kTile;
  const size_t n_tiles = static_cast<size_t>(tiles_x) * tiles_y;
  const bool unbounded = opt.spp == 0;
  control.total.store(unbounded ? 0 : static_cast<uint64_t>(w) * h * opt.spp);

  SharedTraceCounters work(opt.unoccluded);
  std::atomic<uint64_t> invalid{0};
  // Each unit of work keeps its own splats: merged by sample index, then in tile and row order,
  // they are added in the same order whatever the units, so the image does not depend on them.
  const int rows_per_unit = unit_rows(n_tiles, opt.threads);
  const size_t units_per_tile = static_cast<size_t>(kTile / rows_per_unit);
  const size_t n_units = n_tiles * units_per_tile;
  std::vector<TileSplats> tile_splats(opt.light_paths ? n_units : 0);
  RenderStats stats;
  const Stopwatch elapsed;
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
    parallel_for_each_index(opt.threads, n_units, [&](size_t unit) {
      const size_t tile = unit / units_per_tile;
      const int x0 = static_cast<int>(tile % tiles_x) * kTile;
      const int y0 = static_cast<int>(tile / tiles_x) * kTile + static_cast<int>(unit % units_per_tile) * rows_per_unit;
      if (y0 >= h) return;  // rows of the last tiles below the image
      const TileRect rect{x0, y0, std::min(x0 + kTile, w), std::min(y0 + rows_per_unit, h)};
      TraceCounters local = work.local();
      uint64_t local_invalid = 0;
      SplatList no_splats;  // estimators without light paths never add to it
      SplatList& splats = opt.light_paths ? tile_splats[unit].list : no_splats;
      splats.clear();
      if (opt.light_paths) tile_splats[unit].sample_ends.clear();
      render_tile<Sampler>(film, opt, rect, first, count, estimate, control, local, local_invalid, splats,
                           opt.light_paths ? &tile_splats[unit].sample_ends : nullptr);
      work.add(local);
      invalid.fetch_add(local_invalid, std::memory_order_relaxed);
    });
    if (opt.light_paths) merge_tile_splats(film, tile_splats, first, count, invalid);
    if (control.cancelled()) break;
    spp_done += count;
    pass_spp = next_pass_spp(elapsed() - pass_start, count, opt.time_limit, elapsed());
  }
  film.end_blocks();  // the last block, when the render ends inside one

  stats.seconds = elapsed();
  work.into(stats);
  stats.invalid_samples = invalid.load();
  stats.interrupted = control.cancelled();
  count_samples(film, stats);
  return stats;
}

}  // namespace dualight
