// The caustic perturbation [Veach 1997, sec. 11.4.3.2]: for paths ending (D|L) S+ D E, a caustic
// seen directly, perturb the direction leaving the light-side diffuse vertex x_j by an
// exponentially distributed angle, follow the old specular lobes to a new x'_{k-1}, and join it
// to the camera (a new film position). The angular offset is symmetric, so the transition
// densities keep only the Jacobian factors (area densities per unit solid angle at x_j).
#pragma once
#include "pathspace/mutations/perturbation.h"

namespace dualight {

class CausticPerturbation : public Mutation {
 public:
  explicit CausticPerturbation(PerturbationRange angle) : angle_(angle) {}
  const char* name() const override { return "caustic_perturbation"; }
  bool suitable(const Path& x) const override;
  bool propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const override;

 private:
  PerturbationRange angle_;
};

}  // namespace dualight
