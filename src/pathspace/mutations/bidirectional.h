// The bidirectional mutation [Veach 1997, sec. 11.4.2]: delete a subpath x_{l+1} .. x_{m-1}
// (nd >= 1 vertices, short deletions more likely) and regenerate ka >= 1 new vertices, s of them
// by a walk from x_l (or a new emitter point when l = -1) and ka - s from x_m (or the camera),
// joined by a shadow ray. Its transition density sums over every s that could have made the same
// vertices, so it does not depend on the split actually drawn. It changes path lengths and
// reaches every path, so it keeps the chain ergodic; the perturbations only refine.
#pragma once
#include "pathspace/mutations/mutation.h"

namespace dualight {

class BidirectionalMutation : public Mutation {
 public:
  const char* name() const override { return "bidirectional"; }
  bool suitable(const Path&) const override { return true; }
  bool propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const override;
};

// Density (area product measure) with which the bidirectional mutation, having kept z[0..l] and
// z[m..k], generates z[l+1..m-1], summed over the ways to split it between the two walks.
double regeneration_density(const MutationContext& ctx, const Path& z, int l, int m);

}  // namespace dualight
