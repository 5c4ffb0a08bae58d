// Bidirectional path tracing [Veach and Guibas 1995; Veach 1997, ch. 10]: for every pixel sample
// one camera subpath and one light subpath, and every way of joining them — s light vertices and
// t camera vertices, s >= 0, t >= 1 — weighted by multiple importance sampling (power heuristic
// by default, or balance). t = 1 strategies are light tracing: they splat onto the film wherever
// the light vertex projects. Depths count segments as in Mitsuba (max_depth = 1: emitters seen
// directly; -1: unbounded, then Russian roulette from rr_depth ends subpaths). Use it where paths
// are hard to find from one side: caustics (light -> specular -> diffuse -> eye) and light
// arriving through small openings.
//
// With `guiding` (guided BDPT), a radiance guide and an importance guide are trained first,
// together, from guided BDPT's own samples (bdpt.cpp, guiding/guide_training.h); camera subpaths
// then sample directions from the radiance guide, light
// subpaths from the importance guide, each mixed with BSDF sampling, and the MIS weights use the
// mixtures' densities in both directions: pdf_fwd from a subpath's own guide, pdf_rev from the
// other's [Vorba, Karlík, Šik, Ritschel, Křivánek 2014, sec. 6].
#pragma once
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/render_control.h"
#include "core/sampler.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "guiding/guiding_options.h"
#include "pathspace/mis_weight.h"
#include "pathspace/estimator_options.h"
#include "pathspace/render_stats.h"

namespace dualight {

// Where BDPT's Russian roulette starts by default: vertex 2, not the path tracer's 5 (Mitsuba's).
// Every vertex of one subpath connects to every vertex of the other, so a subpath's vertices cost
// connections as well as rays, and a roulette that starts earlier saves more time than it adds
// noise. At equal time (README, "Speed"; benchmarks/bench_bdpt_rr.py) BDPT with 2 was 1.3-1.4x
// as efficient as with 5 on the Cornell box and its caustic variant, 1.04-1.13x on the door ajar,
// and 1.0-1.6x on the other stored test scenes but the furnace (0.54x: without roulette its
// estimate hardly varies). pbrt-v4's BDPT plays no roulette; Mitsuba 3 has no BDPT.
inline constexpr int kBdptRrDepth = 2;

// BDPT's light pool (BdptOptions::light_pool): how many light subpaths a connection takes its
// own from by default, and at most (the pixels of a tile row, pixel_driver.h). Each pixel sample
// traces one light subpath, as in classic BDPT, but from a stream of its own, before its tile row
// is estimated at that sample index. Each connection of a camera vertex to a light vertex
// (s >= 2, t >= 2) takes the light subpath of another pixel of its group of light_pool pixels
// (same tile row, same sample index): strategy (s, t) of the group's pixel k takes subpath
// k + shift(s, t) mod light_pool, with one uniformly drawn shift per strategy for the whole
// group (LightPool, bdpt_sample.h). Every such subpath is a sample of the light subpath
// distribution independent of the camera subpath, so each strategy keeps its expectation and the
// MIS weights (functions of the path) still sum to one; and, per strategy, each subpath serves
// one pixel of the group, as in classic BDPT. What changes: one camera subpath's connections no
// longer all share one light subpath, so where few light subpaths reach what the camera sees
// (Veach's door) a sample's connections no longer succeed or fail together. The pixels of a
// group share their subpaths, so their errors correlate (by about 0.03 between neighbours on the
// door); measured on block means from single pixels to 32x32 blocks, no block shape lost (at
// equal spp on the door, 64 seeds: pixels 0.69x the relMSE, the groups' 1x16 blocks 0.96x,
// 32x32 blocks 0.99x; README, "Speed"; benchmarks/bench_bdpt_pool.py). Each sample costs
// 3-7 % more (the same rays): at equal time the door gains 1.3-1.4x, the Cornell box about
// breaks even and the caustic box loses up to 9 %. A light vertex cache [Davidovic, Krivanek,
// Hasan, Slusallek 2014, sec. 4.3] shares light vertices across the whole image; groups within a
// tile row keep the image a function of the seed, whatever the threads or passes. The light
// tracing (t = 1) and next-event estimation (s = 1) strategies use the sample's own subpath.
inline constexpr int kBdptLightPoolMax = 16;
inline constexpr int kBdptLightPool = 16;

struct BdptOptions : EstimatorOptions, GuidingOptions {
  BdptOptions() { rr_depth = kBdptRrDepth; }

  MisHeuristic heuristic = MisHeuristic::Power;
  // All strategies by MIS, or one alone (s = 0 first or s = 1 first; strategies.h).
  Strategies strategies = Strategies::Mis;
  // One extra film layer per strategy holding its MIS-weighted contributions, which sum to the
  // image (needs a bounded max_depth).
  bool strategy_images = false;
  // Paths of fewer segments are left out (MLT renders direct light separately with them).
  int min_depth = 1;
  // The light subpaths each connection takes its own from (kBdptLightPool); 1: the sample's own,
  // classic BDPT. Guided BDPT always uses 1 (its training records what each subpath carried, and
  // its trial compares the guides with nothing else).
  int light_pool = kBdptLightPool;

  void validate() const {
    EstimatorOptions::validate();
    if (strategy_images && max_depth < 1) {
      throw std::invalid_argument("strategy_images needs a bounded max_depth >= 1");
    }
    if (light_pool < 1 || light_pool > kBdptLightPoolMax) {
      throw std::invalid_argument("light_pool must be within [1, " + std::to_string(kBdptLightPoolMax) +
                                  "]: the pixels of a tile row");
    }
  }
};

// The strategies of paths with 1..max_depth segments, in layer order: by depth, then by t.
std::vector<std::pair<int, int>> bdpt_strategies(int max_depth);

RenderResult render_bdpt(const Scene& scene, const PinholeCamera& camera, const BdptOptions& options,
                         RenderControl& control);

}  // namespace dualight
