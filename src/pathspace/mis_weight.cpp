#include "pathspace/mis_weight.h"

#include <algorithm>

namespace dualight {

namespace {

// Which guide a density follows: the radiance guide's (a camera subpath continuing) or the
// importance guide's (a light subpath continuing).
enum class GuideKind { Radiance, Importance };

// pdf_area_along (path.h) where surface vertex v samples a mixture of its BSDF and a guide:
// mixture(b, pdf_bsdf, w) is the mixture's solid-angle density of w given the BSDF's.
template <class Mixture>
float mixture_pdf_area(const Vertex& v, const Vec3& wo, const Vec3& w, const Vertex& next, const Mixture& mixture) {
  const float pdf_w =
      with_bsdf(v, [&](const Bsdf& b) { return mixture(b, pdf_w_world(b, v.ns, wo, w, TransportMode::Radiance), w); });
  return solid_angle_to_area(pdf_w, v, next);
}

// pdf_area_along with `guide` (null: none) mixed in at a surface vertex.
float pdf_area_along(const PinholeCamera& camera, const Vertex& v, const Vec3& wo, const Vec3& w, const Vertex& next,
                     const SdTree* guide) {
  if (guide == nullptr || v.type != VertexType::Surface) return pdf_area_along(camera, v, wo, w, next);
  return mixture_pdf_area(v, wo, w, next, [&](const Bsdf& b, float pdf_bsdf, const Vec3& wi) {
    const VertexGuide g = vertex_guide(guide->at(v.p), b);
    return g.active() ? g.mixture_pdf_w(pdf_bsdf, wi) : pdf_bsdf;
  });
}

// Chains of delta vertices. Where a path runs from a non-delta vertex a through delta vertices
// a1 .. b1 to a non-delta vertex b (a on the camera's side), the chain maps a direction leaving
// a to a point b, and one leaving b to a point a, through its generalised geometry term G_c
// [Jakob and Marschner 2012, sec. 4]: the density of b sampled from a is p_w(a) G_c / |cos a|,
// that of a sampled from b p_w(b) G_c' / |cos b|, with G_c' = G_c (eta_a / eta_b)^2 (etendue
// is conserved across refractions). Their ratio, all MIS needs, is free of G_c. The usual rule
// [Veach 1997, sec. 10.3.5; pbrt-v3 sec. 16.3.4] reads every density inside the chain as 1 but
// keeps the one-segment factors of its first segments, a -> a1 and b -> b1: its ratio across the
// chain is the true one divided by
//   chain_correction = G(a, a1) / G(b, b1) (eta_a / eta_b)^2
// (G of one segment: geometry_term, path.h), by which the product of ratios across the
// chain is multiplied here. Under a glass sphere, where a1 is close to the floor point a and b1
// far from the light point b, the usual rule gives the camera subpath that hits the light through
// the sphere much of the weight the light tracer would take.
// b at infinity (an environment's direction): the chain maps a direction leaving a to the
// direction w at infinity with some angular magnification M = |d omega_a / d omega_inf|, so
// the density of b is p_w(a) M; b's light subpath samples w, then a point on a disk across it
// (area density p_disk), and a's density is p(w) p_disk (eta_a / eta_b)^2 |cos a| M (the
// beam's etendue). M cancels in the ratio as G_c does, and the usual rule, whose first segment
// from infinity has only b1's cosine (geometry_term), errs by the same factor.
// `at(k)`: the chain in path order, a = at(0) .. b = at(m + 1), m >= 1 delta vertices between.
template <class At>
float chain_correction(const At& at, int m) {
  const Vertex& a = at(0);
  const Vertex& b = at(m + 1);
  float eta = 1.f;  // the IOR on b's side over a's
  for (int k = 1; k <= m; ++k) {
    const Vertex& v = at(k);
    const Frame frame = shading_frame(v);
    const Vec3 wo = frame.to_local(direction(v, at(k - 1))), wi = frame.to_local(direction(v, at(k + 1)));
    eta *= with_bsdf(v, [&](const Bsdf& bsdf) { return refraction_eta(bsdf, wo, wi); });
  }
  const double g_b = geometry_term(b, at(m));
  if (!(g_b > 0.0)) return 1.f;
  return static_cast<float>(geometry_term(a, at(1)) / g_b) / (eta * eta);
}

}  // namespace

float pdf_area(const PinholeCamera& camera, const Vertex& v, const Vertex* prev, const Vertex& next,
               const SdTree* guide) {
  if (guide == nullptr || v.type != VertexType::Surface) return pdf_area(camera, v, prev, next);
  return pdf_area_along(camera, v, direction(v, *prev), direction(v, next), next, guide);
}

namespace {

// pdf_area_along with `tree`'s guide of `kind` (null: none), from v's cached guides where
// set_vertex_guides set them; towards_previous: next is the vertex before v on its own subpath
// and the guide the other direction's, whose density there v caches.
float guided_pdf_area(const PinholeCamera& camera, const Vertex& v, const Vec3& wo, const Vec3& w, const Vertex& next,
                      const SdTree* tree, GuideKind kind, bool towards_previous) {
  if (tree == nullptr || v.type != VertexType::Surface || !v.guides_set) {
    return pdf_area_along(camera, v, wo, w, next, tree);
  }
  const VertexGuide& g = kind == GuideKind::Radiance ? v.radiance_guide : v.importance_guide;
  return mixture_pdf_area(v, wo, w, next, [&](const Bsdf&, float pdf_bsdf, const Vec3& wi) {
    if (!g.active()) return pdf_bsdf;
    if (towards_previous) return g.bsdf_fraction * pdf_bsdf + (1.f - g.bsdf_fraction) * v.reverse_guide_pdf_w;
    return g.mixture_pdf_w(pdf_bsdf, wi);
  });
}

}  // namespace

void set_vertex_guides(Path& path, const SubpathGuides& guides, TransportMode mode) {
  for (size_t k = 1; k < path.size(); ++k) {
    Vertex& v = path[k];
    if (v.type != VertexType::Surface) continue;
    const bool radiance = guides.radiance != nullptr && !v.radiance_guide_known;
    const bool importance = guides.importance != nullptr && !v.importance_guide_known;
    if (radiance || importance) {
      with_bsdf(v, [&](const Bsdf& b) {
        if (radiance) v.radiance_guide = vertex_guide(guides.radiance->at(v.p), b);
        if (importance) v.importance_guide = vertex_guide(guides.importance->at(v.p), b);
      });
    }
    const VertexGuide& reverse = mode == TransportMode::Radiance ? v.importance_guide : v.radiance_guide;
    if (reverse.active()) v.reverse_guide_pdf_w = reverse.directions->pdf_w(direction(v, path[k - 1]));
    v.guides_set = true;
  }
}

float mis_weight(const Scene& scene, const PinholeCamera& camera, const Path& light, const Path& cam,
                 const Vertex& sampled, int s, int t, MisHeuristic heuristic, Strategies strategies,
                 const SubpathGuides* guides) {
  if (s + t == 2) return 1.f;  // the only strategy kept for paths of one segment
  const SdTree* radiance = guides != nullptr ? guides->radiance : nullptr;
  const SdTree* importance = guides != nullptr ? guides->importance : nullptr;
  const Vertex* qs = s == 0 ? nullptr : (s == 1 ? &sampled : &light[s - 1]);
  const Vertex& pt = t == 1 ? sampled : cam[t - 1];
  const Vertex* qs_minus = s >= 2 ? &light[s - 2] : nullptr;
  const Vertex* pt_minus = t >= 2 ? &cam[t - 2] : nullptr;

  // Reverse densities at the connection under this strategy.
  // The light subpath continuing through qs and pt samples the importance guide; the camera
  // subpath continuing through pt and qs the radiance guide.
  // Each of the four densities reads two of four unit directions, normalized once here.
  constexpr GuideKind kImportance = GuideKind::Importance, kRadiance = GuideKind::Radiance;
  const Vec3 qs_to_pt = qs != nullptr ? direction(*qs, pt) : Vec3{};
  const Vec3 pt_to_qs = qs != nullptr ? direction(pt, *qs) : Vec3{};
  const Vec3 qs_back = qs_minus != nullptr ? direction(*qs, *qs_minus) : Vec3{};
  const Vec3 pt_back = pt_minus != nullptr ? direction(pt, *pt_minus) : Vec3{};
  const float pt_rev = qs != nullptr
                           ? guided_pdf_area(camera, *qs, qs_back, qs_to_pt, pt, importance, kImportance, false)
                           : pdf_light_origin(scene, pt);
  float pt_minus_rev = 0.f;
  if (pt_minus != nullptr) {
    pt_minus_rev = qs != nullptr
                       ? guided_pdf_area(camera, pt, pt_to_qs, pt_back, *pt_minus, importance, kImportance, true)
                       : pdf_light(pt, *pt_minus);
  }
  const float qs_rev =
      qs != nullptr ? guided_pdf_area(camera, pt, pt_back, pt_to_qs, *qs, radiance, kRadiance, false) : 0.f;
  const float qs_minus_rev =
      qs_minus != nullptr ? guided_pdf_area(camera, *qs, qs_to_pt, qs_back, *qs_minus, radiance, kRadiance, true) : 0.f;

  const auto remap0 = [](float pdf) { return pdf != 0.f ? pdf : 1.f; };
  const auto h = [heuristic](float r) { return heuristic == MisHeuristic::Power ? r * r : r; };

  // Each other strategy that can sample the path, by its number of light vertices and its
  // density relative to this one's: MIS sums h(ratio); one strategy alone keeps the most
  // preferred (strategies.h).
  float sum = 0.f;
  int best_rank = strategy_rank(strategies, s);
  // Both count the same strategies as able to sample the path (those not connecting at a delta
  // vertex), so one strategy alone keeps exactly one of them.
  const auto other = [&](int s_other, float ratio) {
    if (strategies == Strategies::Mis) {
      sum += h(ratio);
    } else {
      best_rank = std::min(best_rank, strategy_rank(strategies, s_other));
    }
  };
  // Strategies with fewer camera vertices: move the connection towards the camera. The camera
  // itself (i = 0) cannot be hit by a light subpath.
  float ratio = 1.f;
  int above = t - 1;  // the last vertex passed that is not delta
  for (int i = t - 1; i > 0; --i) {
    const float rev = i == t - 1 ? pt_rev : (i == t - 2 ? pt_minus_rev : cam[i].pdf_rev);
    ratio *= remap0(rev) / remap0(cam[i].pdf_fwd);
    const bool delta_i = i != t - 1 && cam[i].delta;  // the connection vertex is never delta
    if (delta_i) continue;
    if (above > i + 1) ratio *= chain_correction([&](int k) -> const Vertex& { return cam[i + k]; }, above - i - 1);
    above = i;
    if (!cam[i - 1].delta) other(s + t - i, ratio);
  }
  // Strategies with fewer light vertices: move the connection towards the emitter.
  ratio = 1.f;
  above = s - 1;
  for (int i = s - 1; i >= 0; --i) {
    const Vertex& v = (s == 1 && i == 0) ? sampled : light[i];
    const float rev = i == s - 1 ? qs_rev : (i == s - 2 ? qs_minus_rev : light[i].pdf_rev);
    ratio *= remap0(rev) / remap0(v.pdf_fwd);
    const bool delta_i = i != s - 1 && light[i].delta;
    if (delta_i) continue;
    if (above > i + 1) {
      ratio /= chain_correction([&](int k) -> const Vertex& { return light[above - k]; }, above - i - 1);
    }
    above = i;
    // Before the emitter vertex: a delta position or direction (a point light, a directional
    // one) cannot be hit by a camera path.
    const bool delta_before = i > 0 ? light[i - 1].delta : is_delta_light(*v.emitter);
    if (!delta_i && !delta_before) other(i, ratio);
  }
  if (strategies != Strategies::Mis) return best_rank == strategy_rank(strategies, s) ? 1.f : 0.f;
  return 1.f / (1.f + sum);
}

}  // namespace dualight
