// Test hooks for path-space MLT's mutations (issue 6: each mutation on its own keeps the target
// density, and the transition densities it reports are right). Not part of the product: the
// test module dualight._testing (bind_mlt.cpp) binds them with a leading `check_mlt_`.
//
// render_single_mutation: MLT whose chains use one mutation only (the others get weight 0, the
// bidirectional one too) and stay put on paths it does not suit. The chains start from paths
// resampled from the bootstrap in proportion to their weight, so b x (the start distribution)
// equals f in expectation, and a kernel that leaves f invariant keeps it: the image stays
// unbiased although such a chain is not ergodic. With TransitionRatio::Ignored or Inverted the
// acceptance is wrong on purpose (a negative control).
//
// check_perturbation_densities: finite-difference Jacobians of the perturbations' maps (film
// offset, or direction at a diffuse vertex, to the next non-specular vertex through at most one
// specular reflection), against the density `propose` reported for its proposal.
//
// check_bidirectional_density: Horvitz-Thompson estimates of a region's area from
// bidirectional proposals that regenerate one vertex, weighted by 1 / T(x -> y).
#pragma once
#include <string>
#include <vector>

#include "pathspace/mlt.h"

namespace dualight {

// How the acceptance uses the mutation's transition ratio T(y -> x) / T(x -> y). Only Used is
// correct (render_mlt's own); the others are negative controls (through MltChainHooks).
enum class TransitionRatio { Used, Ignored, Inverted };

PathMltResult render_single_mutation(const Scene& scene, const PinholeCamera& camera, MltOptions options,
                                     const std::string& mutation, TransitionRatio transition_ratio);

// One perturbation proposal y and one block of its map (film -> vertex, or direction at a
// diffuse vertex -> next non-specular vertex). `reported`: the factor of T(x -> y) that
// `propose` reports for that block, in the geometric form (per pixel^2 of film or per steradian,
// a specular reflection's Radiance-form convention undone by G_unfolded / (G G)); `measured`:
// the same density from the area of the image of a small square (film) or cone (directions);
// `cos_end`: |cos| at the moved vertex, for the negative control that drops it.
struct DensityCheck {
  int block = 0;  // 0: film, 1: the first angular block, ...
  int specular = 0;
  double reported = 0.0, measured = 0.0, cos_end = 0.0;
};
// mutation: "lens_perturbation", "multi_chain_perturbation" or "caustic_perturbation"; paths
// from `paths` bootstrap samples, `proposals` tries each; film_step in pixels, angle_step in
// radians (the sides of the squares).
std::vector<DensityCheck> check_perturbation_densities(const Scene& scene, const PinholeCamera& camera,
                                                       const MltOptions& options, const std::string& mutation,
                                                       size_t paths, size_t proposals, double film_step,
                                                       double angle_step);

// A Horvitz-Thompson check of the bidirectional mutation's T(x -> y): of `proposals` proposals
// from one bootstrap path x, those that regenerate x_v alone (v = 0: the emitter point; v = 1:
// the first vertex after it) and put x'_v in a region A (in_region in the .cpp: for v = 0 the
// emitters, all seen from x_1; for v = 1 the non-specular points both x_0 and x_2 see): the sum
// of 1 / T(x -> y) over all proposals, divided by their number, estimates A's area. `area`: A's
// area (v = 0 exact; v = 1 from `region_points` uniform points, standard error `area_se`).
// Per counted proposal: 1 / T and its parts for controls (the move's probability, the light-
// and eye-side walks' area densities of x'_v, |cos| at x'_v towards x_{v+1}).
struct BidirectionalCheck {
  double area = 0.0, area_se = 0.0;
  size_t proposals = 0;
  std::vector<double> inv_t, move, pdf_light, pdf_eye, cos;
};
BidirectionalCheck check_bidirectional_density(const Scene& scene, const PinholeCamera& camera,
                                               const MltOptions& options, int vertex, size_t proposals,
                                               size_t region_points);

}  // namespace dualight
