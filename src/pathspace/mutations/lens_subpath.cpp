#include "pathspace/mutations/lens_subpath.h"

#include <algorithm>

namespace dualight {

namespace {

// Camera-side walk density of z[m .. k - 1].
double lens_subpath_density(const PinholeCamera& camera, const Path& z, int m) {
  double p = 1.0;
  for (size_t i = static_cast<size_t>(m); i + 1 < z.size(); ++i) p *= pdf_from_eye(camera, z, i);
  return p;
}

// Longest lens subpath tried when max_depth is unbounded (glass can trap a walk).
constexpr int kUnboundedSpecularLimit = 64;

}  // namespace

bool LensSubpathMutation::suitable(const Path& x) const {
  const int m = first_diffuse_from_eye(x);
  return m >= 1 && !is_specular(x[m]) && !is_specular(x[m - 1]);
}

bool LensSubpathMutation::propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y,
                                  Transition& t) const {
  const int k = static_cast<int>(x.size()) - 1;
  const int m = first_diffuse_from_eye(x);
  const int max_new = ctx.max_depth >= 0 ? ctx.max_depth - m : kUnboundedSpecularLimit;
  Path eye{x[k]};
  const Point2 film = ctx.camera.film_position(next_2d(rng));
  Vec3 d = ctx.camera.generate_ray(film.u, film.v).d;
  for (;;) {
    if (static_cast<int>(eye.size()) - 1 >= max_new) return false;
    Vertex hit;
    if (!trace_vertex(ctx.scene, eye.back(), d, hit, ctx.counters)) return false;
    eye.push_back(hit);
    if (!is_specular(hit)) break;
    const Vertex& v = eye.back();
    if (!sample_scatter(v, direction(v, eye[eye.size() - 2]), TransportMode::Radiance, next_2d(rng), d)) return false;
  }
  if (!connect_visible(ctx.scene, eye.back(), x[m - 1], ctx.counters)) return false;
  y.assign(x.begin(), x.begin() + m);
  y.insert(y.end(), eye.rbegin(), eye.rend());
  if (!ctx.length_allowed(y.size() - 1)) return false;
  t.forward = lens_subpath_density(ctx.camera, y, m);
  t.reverse = lens_subpath_density(ctx.camera, x, m);
  return true;
}

}  // namespace dualight
