// Adjoint-driven Russian roulette and splitting [Vorba and Křivánek 2016, "Adjoint-Driven Russian
// Roulette and Splitting in Light Transport Simulation", sec. 4]. A path's expected contribution
// from a vertex on is its throughput times the adjoint quantity there (for a camera path, the
// radiance the vertex reflects, which the guide's records estimate: sd_tree.h). A weight window
// centred where that equals the pixel's estimated value keeps every path's expected contribution
// near its share: a path far below the window plays Russian roulette, one far above it is split
// into several. Both keep the estimate unbiased whatever the estimates are; wrong estimates cost
// only variance or time. Survival has a floor, so no path is stopped for sure on an estimate.
#pragma once
#include <algorithm>
#include <cmath>

namespace dualight {

struct AdjointRouletteSettings {
  float window = 5.f;             // s: the window's upper bound over its lower [VK16: 5]
  int max_paths = 16;             // a camera sample splits into at most this many paths in all
  float min_survival = 0.3f;      // the least probability of going on
};

// How a path goes on from a vertex: `paths` continuations (0: stopped by the roulette), each
// with its throughput times `scale`; known is false where an estimate is missing (then the
// caller's usual Russian roulette applies).
struct RouletteOrSplit {
  bool known = false;
  int paths = 1;
  float scale = 1.f;
};

// throughput: the path's (a scalar, as the adjoint estimate); adjoint: the estimate at the vertex;
// pixel: the pixel's estimated value; paths_so_far: how many paths the sample already is; u uniform.
inline RouletteOrSplit adjoint_roulette(float throughput, float adjoint, float pixel, int paths_so_far, float u,
                                        const AdjointRouletteSettings& s) {
  if (!(adjoint > 0.f) || !(pixel > 0.f) || !(throughput > 0.f) || !std::isfinite(throughput)) return {};
  const float centre = pixel / adjoint;  // the throughput whose expected contribution is the pixel's value
  const float lower = 2.f * centre / (1.f + s.window), upper = s.window * lower;
  if (throughput > upper) {
    const int room = std::max(1, s.max_paths / std::max(1, paths_so_far));
    const int n = static_cast<int>(std::min(static_cast<float>(room), std::ceil(throughput / centre)));
    return {true, n, 1.f / static_cast<float>(n)};
  }
  if (throughput < lower) {
    const float q = std::max(s.min_survival, throughput / centre);
    return u < q ? RouletteOrSplit{true, 1, 1.f / q} : RouletteOrSplit{true, 0, 0.f};
  }
  return {true, 1, 1.f};
}

}  // namespace dualight
