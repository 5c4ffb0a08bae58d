#include "pathspace/mutations/lens_perturbation.h"

namespace dualight {

namespace {

// The part of T that is not symmetric: area densities of z[first .. k - 1] per unit film area
// (the camera's per-film density) or per unit solid angle at a perturbed diffuse vertex, with the
// specular lobes followed, not sampled.
double jacobian_density(const PinholeCamera& camera, const Path& z, int first) {
  const int k = static_cast<int>(z.size()) - 1;
  double p = 1.0;
  for (int i = first; i < k; ++i) {
    if (i + 1 == k || is_specular(z[i + 1])) {
      p *= pdf_from_eye(camera, z, static_cast<size_t>(i), true);
    } else {
      p *= solid_angle_to_area(1.f, z[i + 1], z[i]);
    }
  }
  return p;
}

}  // namespace

bool EyePerturbation::suitable(const Path& x) const {
  const int m = first_diffuse_from_eye(x);
  if (m < 1 || is_specular(x[m])) return false;
  return is_specular(x[m - 1]) == multi_chain_;
}

bool EyePerturbation::propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const {
  const int k = static_cast<int>(x.size()) - 1;
  Point2 raster;
  if (!raster_of(ctx.camera, x[k - 1], raster)) return false;
  const float r = film_.sample(rng.next_float()), phi = 2.f * kPi * rng.next_float();
  const float fx = raster.u + r * std::cos(phi), fy = raster.v + r * std::sin(phi);
  if (!(fx >= 0.f && fy >= 0.f && fx < static_cast<float>(ctx.camera.width()) &&
        fy < static_cast<float>(ctx.camera.height()))) {
    return false;
  }
  y = x;
  Vec3 d = ctx.camera.generate_ray(fx, fy).d;
  int from = k, to = k;
  for (;;) {
    to = from - 1;
    while (to > 0 && is_specular(x[to])) --to;
    if (!follow_specular_chain(ctx, x, y, from, to, d)) return false;
    if (to == 0) break;  // reached the emitter: f(y) says whether it emits
    if (!is_specular(x[to - 1])) {
      if (!connect_visible(ctx.scene, y[to], y[to - 1], ctx.counters)) return false;
      break;
    }
    // Multi-chain: perturb the direction towards the next specular chain.
    const float theta = angle_.sample(rng.next_float());
    d = perturb_direction(direction(x[to], x[to - 1]), theta, 2.f * kPi * rng.next_float());
    from = to;
  }
  // y[to .. k - 1] are new.
  t.forward = jacobian_density(ctx.camera, y, to);
  t.reverse = jacobian_density(ctx.camera, x, to);
  return true;
}

}  // namespace dualight
