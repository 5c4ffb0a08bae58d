#include "pathspace/full_path.h"
#include "pathspace/shadow_ray.h"

#include <cmath>

#include "core/frame.h"

namespace dualight {

SpecularLobe specular_lobe(const Vertex& v, const Vec3& to_eye, const Vec3& to_light) {
  SpecularLobe lobe;
  const Frame frame = Frame::from_normal(v.n);
  const Vec3 wo = frame.to_local(to_eye), wi = frame.to_local(to_light);
  lobe.refraction = !same_hemisphere(wo, wi);
  if (const auto* mirror = std::get_if<Mirror>(&v.material->bsdf)) {
    if (lobe.refraction) return lobe;
    lobe.coef = mirror->reflectance;
    lobe.prob = 1.f;
    return lobe;
  }
  const auto& glass = std::get<Dielectric>(v.material->bsdf);
  const Fresnel F = fresnel_dielectric(wo.z, glass.eta);
  if (!lobe.refraction) {
    lobe.coef = Color(F.R);
    lobe.prob = F.R;
    return lobe;
  }
  // Radiance scales by (eta on the eye side / eta on the light side)^2 = 1 / eta_ratio^2.
  lobe.importance_ratio = 1.f / (F.eta_ratio * F.eta_ratio);
  lobe.prob = 1.f - F.R;
  lobe.coef = Color(lobe.prob * lobe.importance_ratio);
  return lobe;
}

bool specular_direction(const Vertex& v, const Vec3& wo, bool refraction, Vec3& wi) {
  const Frame frame = Frame::from_normal(v.n);
  const Vec3 w = frame.to_local(wo);
  if (w.z == 0.f) return false;
  if (!refraction) {
    wi = frame.to_world(reflect_local(w));
    return true;
  }
  const auto* glass = std::get_if<Dielectric>(&v.material->bsdf);
  if (glass == nullptr) return false;
  const Fresnel F = fresnel_dielectric(w.z, glass->eta);
  if (F.R >= 1.f) return false;
  const float inv = 1.f / F.eta_ratio;
  wi = normalize(frame.to_world({-w.x * inv, -w.y * inv, w.z > 0.f ? -F.cos_t : F.cos_t}));
  return true;
}

PathValue path_contribution(const PinholeCamera& camera, const Path& z, Point2& raster) {
  PathValue value;
  const size_t k = z.size() - 1;
  if (z.size() < 2 || !z[0].is_emitter()) return value;
  if (!camera.raster_position(z[k - 1].p, raster)) return value;
  // Per channel in double: the product of k BSDFs and geometry terms leaves float's range.
  const Color Le = emitted_towards(z[0], z[1].p);
  double f[3] = {Le.x, Le.y, Le.z};
  for (size_t i = 1; i < k; ++i) {
    const Vec3 to_eye = direction(z[i], z[i + 1]), to_light = direction(z[i], z[i - 1]);
    Color fs;
    if (is_specular(z[i])) {
      fs = specular_lobe(z[i], to_eye, to_light).coef;
    } else {
      const Frame frame = Frame::from_normal(z[i].n);
      fs = eval_f(z[i].material->bsdf, frame.to_local(to_eye), frame.to_local(to_light), TransportMode::Radiance);
    }
    for (int c = 0; c < 3; ++c) f[c] *= fs[c];
  }
  double g = camera.importance(direction(z[k], z[k - 1]));
  for (size_t i = 0; i < k; ++i) g *= geometry_term(z[i], z[i + 1]);
  const double lum = (0.2126 * f[0] + 0.7152 * f[1] + 0.0722 * f[2]) * g;
  if (!(lum > 0.0) || !std::isfinite(lum)) return value;
  value.f_lum = lum;
  value.color = Color(static_cast<float>(f[0] * g / lum), static_cast<float>(f[1] * g / lum),
                      static_cast<float>(f[2] * g / lum));
  return value;
}

double pdf_from_light(const Scene& scene, const Path& z, size_t i, bool forced) {
  if (i == 0) return z[0].is_emitter() ? scene.emitter_pdf_a(z[0].prim) : 0.0;
  const Vertex& v = z[i - 1];
  const Vec3 w = direction(v, z[i]);
  if (i == 1) return solid_angle_to_area(cosine_hemisphere_pdf(dot(v.n, w)), v, z[i]);
  const Vec3 to_light = direction(v, z[i - 2]);
  if (is_specular(v)) {
    const SpecularLobe lobe = specular_lobe(v, w, to_light);
    return (forced ? 1.0 : lobe.prob) * lobe.importance_ratio * geometry_term(v, z[i]);
  }
  const Frame frame = Frame::from_normal(v.n);
  return solid_angle_to_area(
      pdf_w(v.material->bsdf, frame.to_local(to_light), frame.to_local(w), TransportMode::Importance), v, z[i]);
}

double pdf_from_eye(const PinholeCamera& camera, const Path& z, size_t i, bool forced) {
  const Vertex& v = z[i + 1];
  const Vec3 w = direction(v, z[i]);
  if (i + 2 == z.size()) return solid_angle_to_area(camera.pdf_w(w), v, z[i]);
  const Vec3 to_eye = direction(v, z[i + 2]);
  if (is_specular(v)) {
    const SpecularLobe lobe = specular_lobe(v, to_eye, w);
    return (forced ? 1.0 : lobe.prob) * geometry_term(v, z[i]);
  }
  const Frame frame = Frame::from_normal(v.n);
  return solid_angle_to_area(
      pdf_w(v.material->bsdf, frame.to_local(to_eye), frame.to_local(w), TransportMode::Radiance), v, z[i]);
}

bool trace_vertex(const Scene& scene, const Vertex& from, const Vec3& d, Vertex& hit, TraceCounters& counters) {
  const Vec3 o = from.on_surface() ? offset_ray_origin(from.p, dot(d, from.n) > 0.f ? from.n : -from.n) : from.p;
  SurfaceHit h;
  ++counters.rays;
  if (!scene.intersect(Ray{o, d}, h)) return false;
  hit = Vertex{};
  hit.type = VertexType::Surface;
  hit.p = h.p;
  hit.n = h.n;
  hit.wo = -d;
  hit.prim = h.prim;
  hit.material = h.material;
  return true;
}

bool connect_visible(const Scene& scene, const Vertex& a, const Vertex& b, TraceCounters& counters) {
  if (b.type == VertexType::Camera) return shadow_ray_visible_point(scene, a.p, a.n, b.p, counters);
  if (a.type == VertexType::Camera) return shadow_ray_visible_point(scene, b.p, b.n, a.p, counters);
  return shadow_ray_visible(scene, a.p, a.n, b.p, b.prim, counters);
}

bool sample_scatter(const Vertex& v, const Vec3& wo, TransportMode mode, Point2 u, Vec3& wi) {
  const Frame frame = Frame::from_normal(v.n);
  BsdfSample bs;
  if (!sample(v.material->bsdf, frame.to_local(wo), u, mode, bs)) return false;
  wi = frame.to_world(bs.wi);
  return true;
}

}  // namespace dualight
