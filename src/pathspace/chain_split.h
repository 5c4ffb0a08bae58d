// A Metropolis render in three parts, so that its chains can run in other processes or on other
// machines (python/dualight/executor.py): the start-up (direct light, pilot, bootstrap, the
// normalisation b, which chains start) runs once; any range of chains then runs from the
// start-up alone and returns a ChainPart; the parts, merged in chain order, and the start-up
// make the image. The single-process render is the same three parts with one range holding all
// chains. A chain's mutation count depends only on its index and the target, its splats sum
// exactly (exact_sum.h), and the large steps' estimates of b merge in chain order, so a split
// render equals the single-process one bit for bit.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "core/exact_sum.h"
#include "core/mean_estimate.h"
#include "pathspace/mlt_result.h"
#include "pathspace/render_stats.h"

namespace dualight {

// Chains that share a target function and a normalisation: all of them (Kelemen's PSSMLT,
// Veach's MLT), or those of one path length (multiplexed MLT).
struct ChainPopulation {
  int depth = 0;                  // multiplexed: the path length in segments; 0 otherwise
  std::vector<double> weights;    // the bootstrap samples' f, resampled for the chains' starts
  double b_splat = 0.0;           // the bootstrap's b: what the chains splat with
  uint64_t first_chain = 0;       // global index of its first chain
  uint64_t chains = 0;
  uint64_t target = 0;            // mutations of all its chains (0: until the deadline)
  std::vector<uint32_t> chain_ids;  // path-space MLT: the seeds of the chains that found a start path
};

struct ChainStartUp {
  std::vector<double> image;      // 3 x pixels: the direct light (zeros without)
  RenderStats direct;             // the direct light's work
  RenderStats stats;              // the start-up's own work (pilot, bootstrap)
  MltStats mlt;                   // b from the bootstrap, its interval and sample counts
  std::vector<ChainPopulation> populations;  // in the order they run
  std::vector<double> pilot_luminance;       // path-space MLT, flattened importance: per pixel
  bool cancelled = false;

  uint64_t chains() const {
    return populations.empty() ? 0 : populations.back().first_chain + populations.back().chains;
  }
  // A copy for the tasks of chains [first, first + count): other populations' weights dropped.
  ChainStartUp for_chains(uint64_t first, uint64_t count) const;
};

// What the chains of one population in a range produced.
struct PopulationPart {
  ExactSums metropolis, large;           // per pixel and channel (empty: no chain in the range)
  std::vector<MeanEstimate> large_f;     // per chain, in chain order: f of its large steps
  uint64_t mutations = 0, accepted = 0, large_steps = 0, large_steps_accepted = 0, zero_proposals = 0;
};

struct ChainPart {
  uint64_t first_chain = 0, chains = 0;
  std::vector<PopulationPart> populations;  // as ChainStartUp::populations
  std::vector<MutationStats> mutations;     // path-space MLT: per mutation type
  RenderStats stats;                        // rays, invalid samples, seconds, interrupted, time_limited
  // Appends `next`, whose chains follow this part's (gaps allowed: an interrupted split render
  // merges the parts that finished). `chains` then counts the range from first_chain to the end.
  void merge(const ChainPart& next);
};

// A part for chains [first, first + count) of `start` (clamped to its chains), with nothing done.
ChainPart empty_part(const ChainStartUp& start, uint64_t first, uint64_t count);

// What a render's options allow its start-up to hold: populations of path lengths [first_depth,
// last_depth], at most `populations` of them (one of depth 0 for every length but multiplexed
// MLT's), at most `chains` chains between them (or one per population), and `mutations` in all
// (0: until the time limit), shared out to the populations.
struct ChainStartUpShape {
  int first_depth = 0, last_depth = 0;
  size_t populations = 1;
  uint64_t chains = 1, mutations = 0;
};

// Throws std::invalid_argument unless `start` can drive a render of `pixels` pixels with this
// shape: its image, pilot and bootstrap finite and of the render's size, its populations'
// depths within the shape's and distinct, chains and mutations within the render's, chains
// only where there is light to start them. A start-up may come from another process (executor
// tasks): every field that indexes memory or bounds a loop is checked.
void check_chain_start_up(const ChainStartUp& start, size_t pixels, const ChainStartUpShape& shape);

// Throws std::invalid_argument unless `part` fits `start` (populations, chain range, sums of
// `values` each wherever mutations were counted, finite estimates).
void check_chain_part(const ChainStartUp& start, const ChainPart& part, size_t values);

// The merged image in float32; std::invalid_argument if a value is beyond float32's range or not
// finite (only corrupt parts' sums get there: each splat is bounded, exact_sum.h).
std::vector<float> chain_image(const std::vector<double>& image);

// A render's stats from its start-up and chains (seconds: the parts'; the caller knows better).
RenderStats chain_render_stats(const ChainStartUp& start, const ChainPart& part, uint64_t mutations, size_t pixels);

// Bytes for pickling, and back (std::invalid_argument on anything malformed).
std::string to_bytes(const ChainStartUp& start);
std::string to_bytes(const ChainPart& part);
ChainStartUp start_up_from_bytes(const std::string& bytes);
ChainPart part_from_bytes(const std::string& bytes);

}  // namespace dualight
