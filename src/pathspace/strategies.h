// Which sampling strategies an estimator combines [Veach 1997, sec. 9.2 and fig. 9.2]: all of
// them by multiple importance sampling (the default), or one at a time, for teaching and for
// checking MIS itself. "One at a time" keeps the estimate unbiased: each path gets weight 1 from
// the preferred strategy when that strategy can sample it, and from another one only where the
// preferred one cannot (a delta light for BSDF sampling; an emitter seen from the camera or
// through a mirror for light sampling). The weights of every path still sum to 1.
#pragma once
#include "core/sampling.h"

namespace dualight {

// Mis: every strategy, power-heuristic weights (BDPT: its heuristic). Bsdf: sample the BSDF
// (the path tracer's emitter hits; BDPT's strategies with the fewest light vertices, s = 0
// first). Light: sample the emitters (next-event estimation; BDPT's s = 1 first, then s = 0).
enum class Strategies { Mis, Bsdf, Light };

// The weight of a sample of the path tracer's strategy `own` (Bsdf: an emitter hit; Light: a
// next-event sample) whose density is pdf_own, where the other strategy's density of the same
// point is pdf_other (solid angle both).
inline float two_strategy_weight(Strategies chosen, Strategies own, float pdf_own, float pdf_other) {
  if (chosen == Strategies::Mis) return power_heuristic(pdf_own, pdf_other);
  if (chosen == own) return 1.f;
  return pdf_other > 0.f ? 0.f : 1.f;  // only where the chosen strategy cannot find the point
}

// BDPT's preference order of strategies by their number s of light vertices: lower is
// preferred. Bsdf: s = 0, 1, 2, ...; Light: s = 1, 0, 2, 3, ...
inline int strategy_rank(Strategies chosen, int s) {
  if (chosen == Strategies::Light && s <= 1) return 1 - s;
  return s;
}

}  // namespace dualight
