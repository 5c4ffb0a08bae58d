#include "pathspace/path.h"

#include <algorithm>

#include "core/frame.h"

namespace dualight {

Color scattering_along(const Vertex& v, const Vec3& wi, TransportMode mode) {
  const Color f = with_bsdf(v, [&](const Bsdf& b) { return eval_f_world(b, v.ns, v.wo, wi, mode); });
  return f * shading_ratio(v.n, v.ns, mode == TransportMode::Radiance ? wi : v.wo);
}

float pdf_area(const PinholeCamera& camera, const Vertex& v, const Vertex* prev, const Vertex& next) {
  const Vec3 w = direction(v, next);
  return pdf_area_along(camera, v, v.type == VertexType::Surface && prev != nullptr ? direction(v, *prev) : Vec3{}, w,
                        next);
}

float pdf_area_along(const PinholeCamera& camera, const Vertex& v, const Vec3& wo, const Vec3& w, const Vertex& next) {
  float pdf_w = 0.f;
  switch (v.type) {
    case VertexType::Camera:
      pdf_w = camera.pdf_w(w);
      break;
    case VertexType::Light:
      pdf_w = emission_pdf_w(v, w);
      break;
    case VertexType::Surface:
      pdf_w = surface_pdf_w(v, wo, w, TransportMode::Radiance);
      break;
  }
  return solid_angle_to_area(pdf_w, v, next);
}

float pdf_light_origin(const Scene& scene, const Vertex& v) {
  return v.emitter != nullptr ? pdf_Le_position(*v.emitter, scene.emitter_pmf(*v.emitter), v.p) : 0.f;
}

float pdf_light(const Vertex& v, const Vertex& next) {
  return solid_angle_to_area(emission_pdf_w(v, direction(v, next)), v, next);
}

// Recomputes from the stored directions (wo), as the walk evaluated its densities at the directions
// it sampled; distances and cosines at the receiving vertex come from positions, as in the walk.
// (Directions from positions differ by the ray-origin offset, up to 1e-2 relative near corners.)
PathCheck verify(const PinholeCamera& camera, const Path& path, bool from_camera) {
  PathCheck check;
  check.vertices = path.size();
  const TransportMode mode = from_camera ? TransportMode::Radiance : TransportMode::Importance;
  // Solid-angle density with which vertex u, reached along u.wo, samples direction w.
  const auto pdf_w_at = [&](const Vertex& u, const Vec3& w) {
    switch (u.type) {
      case VertexType::Camera:
        return camera.pdf_w(w);
      case VertexType::Light:
        return emission_pdf_w(u, w);
      case VertexType::Surface:
        break;
    }
    return surface_pdf_w(u, u.wo, w, mode);
  };
  const auto record = [&](float& worst, float cached, float recomputed) {
    const float scale = std::max(std::abs(cached), std::abs(recomputed));
    const float error = scale > 0.f ? std::abs(cached - recomputed) / scale : 0.f;
    worst = std::max(worst, error);
    check.off += error > 1e-3f;
  };
  for (size_t i = 1; i < path.size(); ++i) {
    const Vertex& prev = path[i - 1];
    const Vertex& v = path[i];
    const Vec3 w = -v.wo;  // the direction prev sampled
    // Delta scattering stores 0 (its density is a discrete probability, not a density).
    record(check.pdf_fwd, v.pdf_fwd, prev.delta ? 0.f : solid_angle_to_area(pdf_w_at(prev, w), prev, v));
    // v's reverse density comes from sampling at i + 1 having arrived from i + 2.
    if (i + 2 < path.size()) {
      const Vertex& next = path[i + 1];
      const Vertex& after = path[i + 2];
      float pdf = 0.f;
      if (!next.delta) pdf = surface_pdf_w(next, -after.wo, next.wo, mode);
      record(check.pdf_rev, v.pdf_rev, solid_angle_to_area(pdf, next, v));
    }
    // beta(i) = beta(i - 1) * f |cos| / pdf_w at i - 1; at the subpath's start the factor is the
    // camera's We / pdf = 1, or the emitter's Le |cos| / pdf_w.
    Color factor(1.f);
    if (prev.type == VertexType::Light) {
      factor = emitted_towards(prev, v.p) * ((prev.on_surface() ? dot(prev.n, w) : 1.f) / pdf_w_at(prev, w));
    } else if (prev.type == VertexType::Surface) {
      if (prev.delta) continue;  // the discrete lobe's weight is not a density ratio
      const Frame frame = shading_frame(prev);
      const Vec3 wi = frame.to_local(w);
      const Color f = with_bsdf(prev, [&](const Bsdf& b) { return eval_f(b, frame.to_local(prev.wo), wi, mode); });
      factor = f * (std::abs(wi.z) * walk_weight_correction(prev.n, prev.ns, prev.wo, w, mode) / pdf_w_at(prev, w));
    }
    const Color beta = prev.beta * factor;
    for (int c = 0; c < 3; ++c) {
      const float scale = std::max(std::abs(v.beta[c]), std::abs(beta[c]));
      if (scale > 0.f) check.beta = std::max(check.beta, std::abs(v.beta[c] - beta[c]) / scale);
    }
  }
  return check;
}

}  // namespace dualight
