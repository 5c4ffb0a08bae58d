// One interface for the mutations of path-space MLT [Veach 1997, sec. 11.3-11.4; Mitsuba 0.6's
// `Mutator`]: whether a path suits the mutation, and a proposal together with the transition
// densities both ways, T(x -> y) and T(y -> x). The chain accepts y with probability
//   min(1, f*(y) T(y -> x) / (f*(x) T(x -> y)))
// (times the ratio of the mutation's selection probabilities at y and x). Perturbations whose
// kernel is symmetric in some coordinates (film offset, angle) report densities without that
// symmetric factor: only the ratio matters.
#pragma once
#include <cstdint>

#include "core/rng.h"
#include "pathspace/full_path.h"

namespace dualight {

struct MutationContext {
  const Scene& scene;
  const PinholeCamera& camera;
  int min_depth = 1;   // shortest path (segments) the chain may hold
  int max_depth = -1;  // longest; -1 = unbounded
  TraceCounters& counters;

  bool length_allowed(size_t segments) const {
    return static_cast<int>(segments) >= min_depth && (max_depth < 0 || static_cast<int>(segments) <= max_depth);
  }
};

struct Transition {
  double forward = 0.0;  // T(x -> y)
  double reverse = 0.0;  // T(y -> x)
};

class Mutation {
 public:
  virtual ~Mutation() = default;
  virtual const char* name() const = 0;
  virtual bool suitable(const Path& x) const = 0;
  // Proposes y from x (a path with f(x) > 0); false when the proposal fails (y then counts as a
  // rejected proposal with f = 0). On success y is a complete path whose segments are unoccluded.
  virtual bool propose(const MutationContext& ctx, const Path& x, Pcg32& rng, Path& y, Transition& t) const = 0;
};

// Uniform random pair from a PCG32 stream.
inline Point2 next_2d(Pcg32& rng) {
  const float u = rng.next_float();
  return {u, rng.next_float()};
}

}  // namespace dualight
