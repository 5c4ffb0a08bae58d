// Path-space Metropolis light transport [Veach and Guibas 1997; Veach 1997, ch. 11]. A Markov
// chain over complete paths x (emitter to camera) whose stationary density is proportional to
// f*(x), the luminance of the path's measurement contribution over the whole film. Mutations:
// bidirectional (delete and regenerate a subpath), lens subpath, lens, caustic and multi-chain
// perturbations (src/pathspace/mutations), each chosen among those that suit the current path
// with probability proportional to its weight. Start-up: `bootstrap` BDPT samples estimate
// b = the integral of f* (with a 95 % interval) and the chains start from paths resampled from
// them in proportion to their MIS-weighted contributions, so there is no start-up bias to
// discard [Veach 1997, sec. 11.3.1]. Every mutation splats the current and proposed paths with
// their expected weights (1 - a and a), times b / (f* M) for M mutations in all. Chains run in
// parallel rounds and their splats merge in chain order: the image depends on the seed only.
// Use it where paths are hard to find and their neighbours are found by perturbing them: light
// through a gap, caustics seen directly or through glass.
#pragma once
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "pathspace/chain_split.h"
#include "pathspace/estimator_options.h"
#include "pathspace/mis_weight.h"
#include "pathspace/mlt_importance.h"
#include "pathspace/mlt_result.h"
#include "core/render_control.h"
#include "geometry/scene.h"

namespace dualight {

struct MltOptions : EstimatorOptions {  // spp counts mutations per pixel; sampler is unused
  uint32_t bootstrap = 100000;
  uint32_t chains = 256;
  MisHeuristic heuristic = MisHeuristic::Power;  // of the bootstrap samples and the direct light
  uint32_t direct_spp = 128;                     // as PssmltOptions::direct_spp
  // Selection weights; 0 disables a mutation. The bidirectional mutation alone is ergodic.
  float bidirectional = 1.f;
  float lens_subpath = 0.25f;
  float lens_perturbation = 1.f;
  float caustic_perturbation = 1.f;
  float multi_chain_perturbation = 1.f;
  // Film offsets of the lens and multi-chain perturbations, in pixels (0: a tenth of the film's
  // width), and angular offsets of the caustic and multi-chain perturbations, in radians.
  float lens_radius_min = 0.1f, lens_radius_max = 0.f;
  float angle_min = 1e-4f, angle_max = 0.1f;

  // Each field's own range is checked where it is set (bindings/options.h); these relate two.
  void validate() const {
    EstimatorOptions::validate();
    if (lens_radius_max > 0.f && lens_radius_max <= lens_radius_min) {
      throw std::invalid_argument("need 0 < lens_radius_min < lens_radius_max (pixels; lens_radius_max 0 = auto)");
    }
    if (!(angle_max > angle_min)) throw std::invalid_argument("need 0 < angle_min < angle_max < pi (radians)");
  }

  // The chains' target f*: image luminance (Veach), or luminance divided by the square root of a
  // smoothed estimate of the pixel's brightness (mlt_importance.h), from the direct light and
  // `bootstrap` / 4 pilot BDPT samples of their own.
  MltImportance importance = MltImportance::Luminance;
};

struct Transition;  // pathspace/mutations/mutation.h

// A seam for the test module only (tests/hooks/mlt_checks.h: negative controls that break
// detailed balance on purpose); renders pass none and their acceptance is Veach's.
struct MltChainHooks {
  // When set, stands for T(y -> x) / T(x -> y) in the acceptance.
  double (*transition_ratio)(const Transition& t) = nullptr;
};


struct PathMltResult {
  MltResult result;  // b is the bootstrap's (MLT has no large steps to refine it)
  std::vector<MutationStats> mutations;
  std::vector<std::string> skipped_mutations;  // enabled, but the scene cannot use them
};

PathMltResult render_mlt(const Scene& scene, const PinholeCamera& camera, const MltOptions& options,
                         RenderControl& control, const MltChainHooks& hooks = {});

// Throws std::invalid_argument when the scene holds what path-space MLT cannot render: a BSDF
// that mixes Dirac and non-Dirac lobes (smooth plastic).
void check_path_space_supports(const Scene& scene);

// render_mlt in the three parts of chain_split.h, for renders split into tasks; as
// pssmlt_start_up, pssmlt_chains and pssmlt_finish.
ChainStartUpShape mlt_start_up_shape(const MltOptions& options, size_t pixels);
ChainStartUp mlt_start_up(const Scene& scene, const PinholeCamera& camera, const MltOptions& options,
                          RenderControl& control, const std::function<double()>& elapsed);
ChainPart mlt_chains(const Scene& scene, const PinholeCamera& camera, const MltOptions& options,
                     const ChainStartUp& start, uint64_t first, uint64_t count, RenderControl& control,
                     const std::function<double()>& elapsed);
PathMltResult mlt_finish(const Scene& scene, const ChainStartUp& start, const ChainPart& part,
                         const MltOptions& options, const PinholeCamera& camera);

}  // namespace dualight
