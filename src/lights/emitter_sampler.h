// The scene's choice among its emitters, in proportion to their power (pbrt-v4's
// PowerLightSampler): it owns the selection probability that every estimator's light sample
// and MIS weight uses.
#pragma once
#include <vector>

#include "core/distribution.h"
#include "lights/emitter.h"

namespace dualight {

class PowerEmitterSampler {
 public:
  PowerEmitterSampler() = default;
  explicit PowerEmitterSampler(const std::vector<Emitter>& emitters) {
    if (emitters.empty()) return;
    std::vector<double> weights;
    weights.reserve(emitters.size());
    for (const Emitter& e : emitters) weights.push_back(power(e));
    distribution_ = DiscreteDistribution(weights);
  }
  // Index of the emitter u picks (u in [0, 1); there must be emitters).
  size_t sample(float u) const { return distribution_.sample(u); }
  float pmf(size_t i) const { return distribution_.pmf(i); }
  std::vector<float> float_item_ends() const { return distribution_.float_item_ends(); }

 private:
  DiscreteDistribution distribution_;
};

}  // namespace dualight
