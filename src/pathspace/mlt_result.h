// What every Metropolis method reports: its image (the chains' estimate at the final b, plus
// the direct light rendered apart), its work, and the normalisation b with its interval.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "pathspace/render_stats.h"

namespace dualight {

struct MltStats {
  // Normalisation E[f] and the half-width of its 95 % interval, from the bootstrap samples and
  // every large step (independent samples too, Kelemen et al.); the chains' part of the image
  // is rescaled to it at the end (`b_splatted` is the bootstrap estimate the splats were made
  // with). Multiplexed: the sums over path lengths of b_d and of its variance.
  double b = 0.0, b_ci95 = 0.0, b_splatted = 0.0;
  // Multiplexed: b_d and its 95 % half-width by path length d in segments (index d; 0 for the
  // lengths rendered apart as direct light). Empty otherwise.
  std::vector<double> b_per_depth, b_per_depth_ci95;
  std::vector<uint64_t> mutations_per_depth;  // multiplexed, by path length as b_per_depth
  uint64_t independent_samples = 0;
  uint64_t mutations = 0, accepted = 0, large_steps = 0, large_steps_accepted = 0;
  uint64_t zero_proposals = 0;  // proposals with f = 0 (rejected)
  uint64_t pilot_samples = 0;   // path-space MLT with flattened importance: the pilot's BDPT samples
};

struct MutationStats {
  std::string name;
  uint64_t proposed = 0;  // chosen for a path
  uint64_t accepted = 0;
  uint64_t failed = 0;    // no valid proposal (missed ray, blocked connection, f = 0)
};

struct MltResult {
  std::vector<float> image;  // H x W x 3: the chains' estimate at the final b, plus the direct light
  RenderStats stats;         // the chains' work; seconds counts the whole render
  RenderStats direct;        // paths of 1 and 2 segments by BDPT, when direct_spp > 0
  MltStats mlt;
};

}  // namespace dualight
