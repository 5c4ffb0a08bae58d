// Shared pieces of Veach's perturbations [Veach 1997, sec. 11.4.3]: exponentially distributed
// offsets (film radius or angle between r_min and r_max, density ~ 1/r^2 in the plane, symmetric
// in the two paths), and the walk that follows the old path's specular lobes.
#pragma once
#include <cmath>

#include "core/frame.h"
#include "pathspace/mutations/mutation.h"

namespace dualight {

struct PerturbationRange {
  float min = 0.f, max = 0.f;
  float sample(float u) const { return max * std::exp(-std::log(max / min) * u); }
};

// A direction at angle theta from w, uniform in azimuth.
inline Vec3 perturb_direction(const Vec3& w, float theta, float phi) {
  const Frame frame = Frame::from_normal(w);
  const float s = std::sin(theta);
  return normalize(frame.to_world({s * std::cos(phi), s * std::sin(phi), std::cos(theta)}));
}

// Index of the first non-specular vertex seen from the camera (x[k - 1], x[k - 2], ...).
inline int first_diffuse_from_eye(const Path& x) {
  int i = static_cast<int>(x.size()) - 2;
  while (i > 0 && is_specular(x[i])) --i;
  return i;
}

// The lobe (refraction or reflection) old specular vertex x[i] used.
inline bool uses_refraction(const Path& x, size_t i) {
  return specular_lobe(x[i], direction(x[i], x[i + 1]), direction(x[i], x[i - 1])).refraction;
}

// Walks from y[from] along d through the old path's specular vertices between `from` and `to`
// (exclusive; step -1 towards the light, +1 towards the camera), taking the lobes x took, and
// stores the new vertices in y; the vertex reached at `to` must be non-specular like x[to].
inline bool follow_specular_chain(const MutationContext& ctx, const Path& x, Path& y, int from, int to, Vec3 d) {
  const int step = to < from ? -1 : 1;
  for (int i = from + step;; i += step) {
    Vertex hit;
    if (!trace_vertex(ctx.scene, y[i - step], d, hit, ctx.counters)) return false;
    if (is_specular(hit) != (i != to)) return false;
    hit.type = x[i].type == VertexType::Light ? VertexType::Light : VertexType::Surface;
    y[i] = hit;
    if (i == to) return true;
    if (!specular_direction(y[i], direction(y[i], y[i - step]), uses_refraction(x, i), d)) return false;
  }
}

}  // namespace dualight
