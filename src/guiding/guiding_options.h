// What an estimator that can be guided is told about its guide (guide_training.h).
#pragma once
#include <cstdint>
#include <memory>
#include <stdexcept>

namespace dualight {

class SdTree;

struct GuidingOptions {
  bool guiding = false;
  // Share of the budget (samples per pixel, or time_limit) spent training, in iterations of
  // doubling samples per pixel (1, 2, 4, ...); the image is rendered with the last guide. With
  // spp, training adds its share on top: the image has spp samples per pixel.
  float guide_training = 0.25f;
  // The image keeps the samples of this many last training iterations (0: none), added to its own:
  // every sample is an unbiased estimate whatever guide drew it, so the image stays their plain
  // mean, and the training's cost is partly recovered. The last iterations hold 3/4 of the training's
  // samples and were guided by trees close to the final one.
  uint32_t guide_keep_iterations = 2;
  // Under a time limit, try before the last training iteration (or after the training) whether
  // the guide pays (guiding_trial.h): a guided and an unguided pass, kept in the image, and the
  // image rendered by the more efficient; an unguided win stops the training.
  bool guide_trial = true;
  // Probability of sampling the BSDF instead of the guide (one-sample MIS, guided_sampling.h):
  // learnt per spatial leaf, at least guide_bsdf_fraction (sd_tree.h), or guide_bsdf_fraction
  // everywhere.
  bool guide_learn_bsdf_fraction = true;
  float guide_bsdf_fraction = 0.5f;
  // Records a spatial leaf may hold in an iteration of 1 sample per pixel; the bound grows with
  // the square root of the iteration's samples per pixel [MGN17, sec. 3.3].
  uint32_t guide_spatial_threshold = 1000;
  // Path tracing: adjoint-driven Russian roulette and splitting in the final render and in the
  // training iterations after the first, from the guide's estimate of reflected radiance and the
  // previous iteration's image (adjoint_rr.h).
  bool guide_adjoint_roulette = true;
  float guide_rho = 0.01f;  // directional subdivision: a node with more of its leaf's value is split
  // Records one training iteration may keep (24 bytes each): training stops before one would need more.
  uint32_t guide_max_records = 1u << 23;
  // Guides the first training iteration samples from instead of the BSDF alone (null: none),
  // e.g. seeded from a radiosity and importance solution (guiding.py): the radiance guide's for
  // camera paths, the importance guide's for light paths. Not options a user types: the
  // bindings set them from Guide objects.
  std::shared_ptr<const SdTree> guide_start_radiance, guide_start_importance;
};

}  // namespace dualight
