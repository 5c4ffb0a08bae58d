#include "pathspace/mmlt.h"

#include <algorithm>

namespace dualight {

void StrategyEvaluator::operator()(PrimarySampleSampler& sampler, Contribution& out, TraceCounters& counters) {
  out.splats.clear();
  out.f = 0.f;
  const int d = depth_;
  // (s, t) with s + t = d + 1, t >= 1, s >= s_first_; (1, 1) only as (0, 2).
  const int n = (d == 1 ? 1 : d + 1) - s_first_;
  const float u_strategy = d == 1 ? 0.f : sampler.next_1d();
  if (n <= 0) return;
  const int s = d == 1 ? 0 : s_first_ + std::min(static_cast<int>(u_strategy * static_cast<float>(n)), n - 1);
  const int t = d + 1 - s;
  const Point2 film = camera_.film_position(sampler.next_2d());
  const float x = film.u, y = film.v;
  const float pixels = static_cast<float>(camera_.width()) * static_cast<float>(camera_.height());
  // Subpaths of exactly t and s vertices (no Russian roulette: the strategy fixes the length).
  camera_subpath(scene_, camera_, x, y, sampler, WalkLimits{t - 1, kNoRussianRoulette}, paths_.camera, counters);
  if (static_cast<int>(paths_.camera.size()) != t) return;
  sampler.start_stream(kLightStream);
  paths_.light.clear();
  if (s > 0) {
    light_subpath(scene_, sampler, WalkLimits{s, kNoRussianRoulette}, paths_.light, counters);
    if (static_cast<int>(paths_.light.size()) != s) return;
  }
  sampler.start_stream(kConnectStream);
  Vertex sampled;
  Point2 raster{};
  Color c = connect(scene_, camera_, paths_.light, paths_.camera, s, t, sampler, sampled, raster, counters);
  if (is_black(c)) return;
  c *= mis_weight(scene_, camera_, paths_.light, paths_.camera, sampled, s, t, bdpt_.heuristic) *
       static_cast<float>(n);
  if (!is_finite(c)) {
    ++invalid_;
    return;
  }
  if (t == 1) {
    out.splats.push_back(
        {static_cast<uint32_t>(raster.v) * camera_.width() + static_cast<uint32_t>(raster.u), 0, c});
  } else {
    out.splats.push_back(
        {static_cast<uint32_t>(y) * camera_.width() + static_cast<uint32_t>(x), 0, c * pixels});
  }
  out.f = std::max(0.f, luminance(out.splats.back().value));
}

}  // namespace dualight
