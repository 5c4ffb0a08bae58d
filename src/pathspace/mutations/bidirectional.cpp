#include "pathspace/mutations/bidirectional.h"

#include <algorithm>
#include <cmath>

#include "core/frame.h"

namespace dualight {

namespace {

// Deleting nd vertices has weight 2^-(nd - 1); adding ka has weight 2^-|ka - nd|, for ka within
// 2 of nd (so that every move has its reverse) and a length the chain allows.
constexpr int kMaxLengthChange = 2;

double delete_probability(int nd, int k) {
  double total = 0.0;
  for (int n = 1; n <= k; ++n) total += std::ldexp(1.0, -(n - 1));
  return std::ldexp(1.0, -(nd - 1)) / total;
}

double add_weight(int ka, int nd) { return std::ldexp(1.0, -std::abs(ka - nd)); }

double add_probability(const MutationContext& ctx, int ka, int nd, int k) {
  // A length the chain does not allow has probability 0 (not just no share of the total): with
  // direct_spp > 0 the chain must not make paths of 1 or 2 segments, which render_direct_light
  // already counts and b does not include.
  if (!ctx.length_allowed(static_cast<size_t>(k - nd + ka))) return 0.0;
  double total = 0.0;
  for (int a = std::max(1, nd - kMaxLengthChange); a <= nd + kMaxLengthChange; ++a) {
    if (ctx.length_allowed(static_cast<size_t>(k - nd + a))) total += add_weight(a, nd);
  }
  return total > 0.0 ? add_weight(ka, nd) / total : 0.0;
}

// Probability of choosing to delete x[l+1 .. l+nd] and add ka vertices, in a path of k segments.
double move_probability(const MutationContext& ctx, int nd, int ka, int k) {
  return delete_probability(nd, k) / static_cast<double>(k - nd + 1) * add_probability(ctx, ka, nd, k);
}

}  // namespace

double regeneration_density(const MutationContext& ctx, const Path& z, int l, int m) {
  const int n = m - l - 1;
  double sum = 0.0;
  for (int s = 0; s <= n; ++s) {
    const int a = l + s;  // last vertex of the light side's walk (-1: none)
    if (a >= 0 && (is_specular(z[a]) || is_specular(z[a + 1]))) continue;  // no connection there
      double p = 1.0;
    for (int i = l + 1; i <= a; ++i) p *= pdf_from_light(ctx.scene, z, static_cast<size_t>(i));
    for (int i = a + 1; i < m; ++i) p *= pdf_from_eye(ctx.camera, z, static_cast<size_t>(i));
    sum += p;
  }
  return sum / static_cast<double>(n + 1);
}

bool BidirectionalMutation::propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y,
                                    Transition& t) const {
  const int k = static_cast<int>(x.size()) - 1;
  // What to delete: nd vertices after x[l].
  int nd = k;
  {
    double u = rng.next_float();
    for (int n = 1; n <= k; ++n) {
      const double p = delete_probability(n, k);
      if (u < p) {
        nd = n;
        break;
      }
      u -= p;
    }
  }
  const int l = std::min(static_cast<int>(rng.next_float() * static_cast<float>(k - nd + 1)), k - nd) - 1;
  const int m = l + nd + 1;
  // How many to add.
  int ka = 0;
  {
    double u = rng.next_float();
    for (int a = std::max(1, nd - kMaxLengthChange); a <= nd + kMaxLengthChange; ++a) {
      const double p = add_probability(ctx, a, nd, k);
      if (p > 0.0) ka = a;  // the last allowed one takes float rounding
      if (u < p) break;
      u -= p;
    }
  }
  if (ka == 0) return false;
  const int s = std::min(static_cast<int>(rng.next_float() * static_cast<float>(ka + 1)), ka);

  // The light side: the kept prefix, then s new vertices.
  y.assign(x.begin(), x.begin() + (l + 1));
  for (int j = 0; j < s; ++j) {
    if (y.empty()) {
      const float u_select = rng.next_float();
      y.push_back(emitter_vertex(ctx.scene, u_select, next_2d(rng)));
      continue;
    }
    const Vertex& v = y.back();
    Vec3 d, origin;  // origin: the distant disk's point when v is at infinity
    if (y.size() == 1) {
      // A direction of density 0 still makes the path: its transition density is then 0.
      EmitterDirection emitted;
      sample_Le_direction(*v.emitter, v.pdf_fwd, v.p, v.uv, next_2d(rng), emitted);
      d = emitted.w;
      origin = emitted.origin;
    } else if (!sample_scatter(v, direction(v, y[y.size() - 2]), TransportMode::Importance, next_2d(rng), d)) {
      return false;
    }
    Vertex hit;
    if (!trace_vertex(ctx.scene, v, d, hit, ctx.counters, origin)) return false;
    y.push_back(hit);
  }
  // The camera side, built backwards: the kept suffix reversed, then ka - s new vertices.
  Path eye(x.rbegin(), x.rbegin() + (k - m + 1));
  for (int j = 0; j < ka - s; ++j) {
    const Vertex& v = eye.back();
    Vec3 d;
    if (v.type == VertexType::Camera) {
      const Point2 film = ctx.camera.film_position(next_2d(rng));
      d = ctx.camera.generate_ray(film.u, film.v).d;
    } else if (!sample_scatter(v, direction(v, eye[eye.size() - 2]), TransportMode::Radiance, next_2d(rng), d)) {
      return false;
    }
    Vertex hit;
    if (!trace_vertex(ctx.scene, v, d, hit, ctx.counters)) return false;
    eye.push_back(hit);
  }
  if (!y.empty()) {
    const Vertex& a = y.back();
    const Vertex& b = eye.back();
    if (is_specular(a) || is_specular(b)) return false;
    if (!connect_visible(ctx.scene, a, b, ctx.counters)) return false;
  }
  y.insert(y.end(), eye.rbegin(), eye.rend());
  y.front().type = VertexType::Light;
  const int k_new = static_cast<int>(y.size()) - 1;
  t.forward = move_probability(ctx, nd, ka, k) * regeneration_density(ctx, y, l, l + ka + 1);
  t.reverse = move_probability(ctx, ka, nd, k_new) * regeneration_density(ctx, x, l, m);
  return true;
}

}  // namespace dualight
