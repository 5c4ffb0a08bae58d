// Primary-sample-space Metropolis light transport [Kelemen et al. 2002] over BDPT: the random
// numbers of one BDPT sample (film position included) are the state of a Markov chain whose
// stationary density is proportional to f = the luminance of everything the sample contributes,
// over the whole film. Mutations are Kelemen's small steps (normal, deviation sigma, per number)
// and large steps (fresh numbers). Start-up bias is avoided as in Veach's thesis (sec. 11.3.1) and
// pbrt-v3: `bootstrap` independent samples estimate the normalisation b = E[f] and the chains
// start from states resampled in proportion to f. Every mutation splats both the current and
// the proposed state, weighted by their acceptance probabilities (expected values); with
// `large_step_mis` the large steps' proposals also count as independent samples, combined with
// the chains' by Kelemen's MIS (see run_chains in pssmlt.cpp). The chains' part is rescaled at
// the end to b estimated from the bootstrap and every large step. Use it where paths are hard
// to find but, once found, have neighbours that are found by small steps: caustics, light
// through gaps.
#pragma once
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <vector>

#include "core/render_control.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "pathspace/estimator_options.h"
#include "pathspace/bdpt.h"
#include "pathspace/chain_split.h"
#include "pathspace/mis_weight.h"
#include "pathspace/mlt_result.h"
#include "pathspace/render_stats.h"

namespace dualight {

struct PssmltOptions : EstimatorOptions {  // spp counts mutations per pixel; sampler is unused
  uint32_t bootstrap = 100000;
  uint32_t chains = 256;
  float sigma = 0.01f;
  float large_step_probability = 0.3f;
  MisHeuristic heuristic = MisHeuristic::Power;
  // Emitters seen directly and direct lighting (paths of 1 and 2 segments) rendered apart by
  // BDPT with this many samples per pixel, and left out of the chains (Veach's thesis sec.
  // 11.4.2; Mitsuba's `directSamples`): they are easy for BDPT and would otherwise take most
  // mutations. 0 keeps every path in the chains.
  uint32_t direct_spp = 128;
  // Kelemen's MIS of large steps: a large step's proposal is also an independent sample of
  // the image, weighted against the chains by the balance heuristic. Lowers the noise where f
  // is small, which the chains visit rarely.
  bool large_step_mis = true;
  // Multiplexed MLT [Hachisuka et al. 2014]: chains per path length, each sample one BDPT
  // strategy of that length (needs a bounded max_depth). Chains, mutations and, with a
  // time_limit, time are allocated to lengths in proportion to their bootstrap b_d.
  bool multiplexed = false;

  void validate() const {
    EstimatorOptions::validate();
    if (multiplexed && max_depth < 1) {
      throw std::invalid_argument("multiplexed MLT needs a bounded max_depth >= 1 (chains per path length)");
    }
  }
};

MltResult render_pssmlt(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& options,
                        RenderControl& control);

// render_pssmlt in the three parts of chain_split.h, for renders split into tasks. `elapsed`
// is the render's clock in seconds (the time limit and the shares of start_up.h count on it).
ChainStartUp pssmlt_start_up(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& options,
                             RenderControl& control, const std::function<double()>& elapsed);
// Chains [first, first + count) of the start-up (clamped to its chains).
ChainPart pssmlt_chains(const Scene& scene, const PinholeCamera& camera, const PssmltOptions& options,
                        const ChainStartUp& start, uint64_t first, uint64_t count, RenderControl& control,
                        const std::function<double()>& elapsed);
// What the options allow a start-up to hold (checked before its chains run or merge).
ChainStartUpShape pssmlt_start_up_shape(const PssmltOptions& options, size_t pixels);
// The image and stats from the start-up and the parts merged in chain order (seconds left 0).
MltResult pssmlt_finish(const ChainStartUp& start, const ChainPart& part, const PssmltOptions& options,
                        const PinholeCamera& camera);

}  // namespace dualight
