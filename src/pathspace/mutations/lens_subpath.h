// The lens subpath mutation [Veach 1997, sec. 11.4.4]: replace the camera end E S* D of a path
// whose x_{m-1} is not specular by a new one through a uniformly chosen film position (specular
// lobes sampled, any number of them within the length limits), joined to x_{m-1}. It spreads the
// chain over the image, as the bidirectional mutation does for the whole path; its transition
// densities are those of the camera-side walk.
#pragma once
#include "pathspace/mutations/perturbation.h"

namespace dualight {

class LensSubpathMutation : public Mutation {
 public:
  const char* name() const override { return "lens_subpath"; }
  bool suitable(const Path& x) const override;
  bool propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const override;
};

}  // namespace dualight
