// BSDF sampling and a guide's directional distribution combined by one-sample MIS with the
// balance heuristic [Veach 1997, sec. 9.2.4; MGN17, sec. 5]: with probability bsdf_fraction the
// BSDF is sampled, otherwise the guide, and the sample is weighted by the mixture's density, so
// the estimate stays unbiased wherever the BSDF alone could sample (the guide only moves samples).
// Dirac lobes are left to the BSDF: their samples keep the BSDF's weight over bsdf_fraction.
#pragma once
#include <cmath>

#include "core/frame.h"
#include "guiding/directional_quadtree.h"
#include "guiding/sd_tree.h"
#include "materials/bsdf.h"

namespace dualight {

// What guides one vertex: the distribution of its spatial leaf (null: none) and the probability of
// sampling the BSDF instead.
struct VertexGuide {
  const DirectionalQuadtree* directions = nullptr;
  float bsdf_fraction = 1.f;

  bool active() const { return directions != nullptr; }
  // The mixture's solid-angle density of world direction w, given the BSDF's.
  float mixture_pdf_w(float pdf_bsdf, const Vec3& w) const {
    return bsdf_fraction * pdf_bsdf + (1.f - bsdf_fraction) * directions->pdf_w(w);
  }
};

// The guide of `leaf` for a vertex with BSDF b: none for Dirac BSDFs, where the leaf learnt
// nothing, or where its BSDF fraction is 1.
inline VertexGuide vertex_guide(const SdTree::Leaf& leaf, const Bsdf& b) {
  if (leaf.directions.empty() || is_delta(b) || leaf.bsdf_fraction >= 1.f) return {};
  return {&leaf.directions, leaf.bsdf_fraction};
}

// Samples local wi from the mixture; u_select picks the strategy (drawn only when g is active, so
// an unguided walk uses the sampler as before). bs.pdf_w is the mixture's density. bsdf_ratio is
// the weight BSDF sampling alone would have given the direction over bs.weight (the mixture's
// density over the BSDF's; 1 unguided): Russian roulette plays on the throughput times it
// (russian_roulette.h).
inline bool sample_guided(const Bsdf& b, const Frame& frame, const VertexGuide& g, const Vec3& wo, float u_select,
                          Point2 u, TransportMode m, BsdfSample& bs, float& bsdf_ratio) {
  bsdf_ratio = 1.f;
  if (!g.active()) return sample(b, wo, u, m, bs);
  const float alpha = g.bsdf_fraction;
  Color f_cos;
  float pdf_bsdf, pdf;
  if (u_select < alpha) {
    if (!sample(b, wo, u, m, bs)) return false;
    if (bs.delta) {
      bs.weight = bs.weight / alpha;
      bs.pdf_w *= alpha;
      bsdf_ratio = alpha;
      return true;
    }
    // A non-Dirac sample's pdf_w is pdf_w(b, wo, wi) (bsdf.h), so f |cos| = weight pdf_w.
    f_cos = bs.weight * bs.pdf_w;
    pdf_bsdf = bs.pdf_w;
    pdf = g.mixture_pdf_w(pdf_bsdf, frame.to_world(bs.wi));
  } else {
    float pdf_guide;
    bs.wi = frame.to_local(g.directions->sample(u, &pdf_guide));
    bs.delta = false;
    bs.eta = refraction_eta(b, wo, bs.wi);  // Russian roulette undoes a refraction's 1 / eta^2
    f_cos = eval_f(b, wo, bs.wi, m) * std::abs(bs.wi.z);
    pdf_bsdf = pdf_w(b, wo, bs.wi, m);
    pdf = alpha * pdf_bsdf + (1.f - alpha) * pdf_guide;
  }
  if (is_black(f_cos) || !(pdf > 0.f)) return false;
  bs.weight = f_cos / pdf;
  bs.pdf_w = pdf;
  bsdf_ratio = pdf_bsdf > 0.f ? pdf / pdf_bsdf : 1.f;
  return true;
}

}  // namespace dualight
