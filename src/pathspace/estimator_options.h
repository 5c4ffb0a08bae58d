// What every image estimator is told: its budget, path lengths, seed, threads and sampler.
#pragma once
#include <cstdint>
#include <stdexcept>

#include "core/sampler.h"

namespace dualight {

struct EstimatorOptions {
  uint32_t spp = 64;        // samples (or particles) per pixel; 0 = unbounded, then time_limit must be set
  int max_depth = -1;       // segments, as in Mitsuba; -1 = unbounded
  int rr_depth = 5;         // Russian roulette from this vertex on
  uint64_t seed = 0;
  int threads = 0;          // 0 = all cores
  double time_limit = 0.0;  // seconds; 0 = none
  SamplerType sampler = SamplerType::Independent;
  // Skip work the scene makes pointless (shadow rays in a convex enclosure, mutations that
  // cannot apply); false does it all, for benchmarks and checks of the skips themselves.
  bool skip_unneeded = true;
  // Renders sample indices [first_sample, first_sample + spp) (particles times the pixel count
  // for the light tracer): one task of a split render (film.h, sample blocks).
  uint32_t first_sample = 0;

  // What no single field's range says (the bindings check those, bindings/options.h): a render
  // needs a budget. Throws std::invalid_argument.
  void validate() const {
    if (spp == 0 && time_limit == 0.0) throw std::invalid_argument("give spp > 0 or a time_limit");
  }
};

}  // namespace dualight
