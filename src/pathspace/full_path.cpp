#include "pathspace/full_path.h"
#include "pathspace/shadow_ray.h"

#include <cmath>

#include "core/frame.h"

namespace dualight {

DeltaLobe specular_lobe(const Vertex& v, const Vec3& to_eye, const Vec3& to_light) {
  const Frame frame = shading_frame(v);
  return with_bsdf(v, [&](const Bsdf& b) { return delta_lobe(b, frame.to_local(to_eye), frame.to_local(to_light)); });
}

bool specular_direction(const Vertex& v, const Vec3& wo, bool refraction, Vec3& wi) {
  const Frame frame = shading_frame(v);
  const Vec3 w = frame.to_local(wo);
  if (w.z == 0.f) return false;
  Vec3 local;
  if (!with_bsdf(v, [&](const Bsdf& b) { return delta_direction(b, w, refraction, local); })) return false;
  // Refracted directions are renormalised (rounding in Snell's law); reflections keep their length.
  wi = refraction ? normalize(frame.to_world(local)) : frame.to_world(local);
  return true;
}

PathValue path_contribution(const PinholeCamera& camera, const Path& z, Point2& raster) {
  PathValue value;
  const size_t k = z.size() - 1;
  if (z.size() < 2 || !z[0].is_emitter()) return value;
  if (!raster_of(camera, z[k - 1], raster)) return value;
  // Per channel in double: the product of k BSDFs and geometry terms leaves float's range.
  const Color Le = emitted_towards(z[0], z[1].p);
  double f[3] = {Le.x, Le.y, Le.z};
  for (size_t i = 1; i < k; ++i) {
    const Vec3 to_eye = direction(z[i], z[i + 1]), to_light = direction(z[i], z[i - 1]);
    Color fs;
    if (is_specular(z[i])) {
      fs = specular_lobe(z[i], to_eye, to_light).coef;
    } else {
      fs = with_bsdf(z[i],
                     [&](const Bsdf& b) {
                       return eval_f_world(b, z[i].ns, to_eye, to_light, TransportMode::Radiance);
                     }) *
           shading_ratio(z[i].n, z[i].ns, to_light);
    }
    for (int c = 0; c < 3; ++c) f[c] *= fs[c];
  }
  double g = camera.importance(direction(z[k], z[k - 1]));
  for (size_t i = 0; i < k; ++i) g *= geometry_term(z[i], z[i + 1]);
  const double lum = (kLuminanceWeights[0] * f[0] + kLuminanceWeights[1] * f[1] + kLuminanceWeights[2] * f[2]) * g;
  if (!(lum > 0.0) || !std::isfinite(lum)) return value;
  value.f_lum = lum;
  value.color = Color(static_cast<float>(f[0] * g / lum), static_cast<float>(f[1] * g / lum),
                      static_cast<float>(f[2] * g / lum));
  return value;
}

double pdf_from_light(const Scene& scene, const Path& z, size_t i, bool forced) {
  if (i == 0) return pdf_light_origin(scene, z[0]);
  const Vertex& v = z[i - 1];
  const Vec3 w = direction(v, z[i]);
  if (i == 1) return solid_angle_to_area(emission_pdf_w(v, w), v, z[i]);
  const Vec3 to_light = direction(v, z[i - 2]);
  if (is_specular(v)) {
    const DeltaLobe lobe = specular_lobe(v, w, to_light);
    return (forced ? 1.0 : lobe.prob) * lobe.importance_ratio * geometry_term(v, z[i]);
  }
  return solid_angle_to_area(surface_pdf_w(v, to_light, w, TransportMode::Importance), v, z[i]);
}

double pdf_from_eye(const PinholeCamera& camera, const Path& z, size_t i, bool forced) {
  // No walk hits a vertex without a surface (a point emitter at x_0, one at infinity).
  if (!z[i].on_surface()) return 0.0;
  const Vertex& v = z[i + 1];
  const Vec3 w = direction(v, z[i]);
  if (i + 2 == z.size()) return solid_angle_to_area(camera.pdf_w(w), v, z[i]);
  const Vec3 to_eye = direction(v, z[i + 2]);
  if (is_specular(v)) {
    const DeltaLobe lobe = specular_lobe(v, to_eye, w);
    return (forced ? 1.0 : lobe.prob) * geometry_term(v, z[i]);
  }
  return solid_angle_to_area(surface_pdf_w(v, to_eye, w, TransportMode::Radiance), v, z[i]);
}

bool trace_vertex(const Scene& scene, const Vertex& from, const Vec3& d, Vertex& hit, TraceCounters& counters,
                  const Vec3& origin) {
  // Off a surface; from the eye past its clearance; from infinity at `origin`; from any other
  // point as it is.
  const Ray ray = from.on_surface() ? Ray{scene.spawn_origin(from.p, dot(d, from.n) > 0.f ? from.n : -from.n), d}
                  : from.type == VertexType::Camera ? scene.eye_ray(Ray{from.p, d})
                  : from.at_infinity                ? Ray{origin, d}
                                                    : Ray{from.p, d};
  SurfaceHit h;
  ++counters.rays;
  if (!scene.intersect(ray, h)) return false;
  hit = surface_vertex(h, d);
  return true;
}

bool sample_scatter(const Vertex& v, const Vec3& wo, TransportMode mode, Point2 u, Vec3& wi) {
  const Frame frame = shading_frame(v);
  BsdfSample bs;
  if (!with_bsdf(v, [&](const Bsdf& b) { return sample(b, frame.to_local(wo), u, mode, bs); })) return false;
  wi = frame.to_world(bs.wi);
  return true;
}

}  // namespace dualight
