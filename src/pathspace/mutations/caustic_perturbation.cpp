#include "pathspace/mutations/caustic_perturbation.h"

namespace dualight {

namespace {

// The light-side diffuse vertex before the specular chain that ends at x[k - 2].
int chain_start(const Path& x) {
  int j = static_cast<int>(x.size()) - 3;
  while (j > 0 && is_specular(x[j])) --j;
  return j;
}

// Area densities of z[j + 1 .. k - 1] per unit solid angle at z[j], lobes followed.
double jacobian_density(const Scene& scene, const Path& z, int j) {
  const int k = static_cast<int>(z.size()) - 1;
  double p = solid_angle_to_area(1.f, z[j], z[j + 1]);
  for (int i = j + 2; i < k; ++i) p *= pdf_from_light(scene, z, static_cast<size_t>(i), true);
  return p;
}

}  // namespace

// Not from a vertex at infinity (j = 0 on the sky): the direction leaving it is its position's
// and the disk's, not a solid angle to perturb. Mutations keep x[0], so y is unsuitable too.
bool CausticPerturbation::suitable(const Path& x) const {
  const int k = static_cast<int>(x.size()) - 1;
  return k >= 3 && !is_specular(x[k - 1]) && is_specular(x[k - 2]) && !(x[0].at_infinity && chain_start(x) == 0);
}

bool CausticPerturbation::propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y,
                                  Transition& t) const {
  const int k = static_cast<int>(x.size()) - 1;
  const int j = chain_start(x);
  const float theta = angle_.sample(rng.next_float());
  const Vec3 d = perturb_direction(direction(x[j], x[j + 1]), theta, 2.f * kPi * rng.next_float());
  y = x;
  if (!follow_specular_chain(ctx, x, y, j, k - 1, d)) return false;
  if (!connect_visible(ctx.scene, y[k - 1], y[k], ctx.counters)) return false;
  t.forward = jacobian_density(ctx.scene, y, j);
  t.reverse = jacobian_density(ctx.scene, x, j);
  return true;
}

}  // namespace dualight
