// Perturbations of the camera end [Veach 1997, sec. 11.4.3.1 and 11.4.3.3]. Both move the film
// position by an exponentially distributed offset and trace the new ray through the same
// specular lobes as the old path (E S* D) to a non-specular vertex x'_m.
//   Lens perturbation: x_{m-1} is not specular; x'_m is joined to it by a shadow ray.
//   Multi-chain perturbation: x_{m-1} is specular, so no shadow ray can reach it; the direction
//   at x'_m towards the light is perturbed by an exponentially distributed angle and followed
//   through the next specular chain, and so on until a vertex whose light-side neighbour is not
//   specular (E S* D S+ D ... D), or the emitter.
// Offsets are symmetric, so the transition densities keep only the Jacobian factors: area
// densities of the traced vertices per unit film area or solid angle (the rest cancels).
#pragma once
#include "pathspace/mutations/perturbation.h"

namespace dualight {

class EyePerturbation : public Mutation {
 public:
  // film: offsets in pixels; angle: offsets in radians at the diffuse vertices of a multi-chain.
  EyePerturbation(bool multi_chain, PerturbationRange film, PerturbationRange angle)
      : multi_chain_(multi_chain), film_(film), angle_(angle) {}
  const char* name() const override { return multi_chain_ ? "multi_chain_perturbation" : "lens_perturbation"; }
  bool suitable(const Path& x) const override;
  bool propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const override;

 private:
  bool multi_chain_;
  PerturbationRange film_, angle_;
};

}  // namespace dualight
