#include "radiosity/direct_irradiance.h"

#include <cmath>
#include <stdexcept>

#include "core/frame.h"
#include "core/parallel.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "core/triangle_grid.h"

namespace dualight {

namespace {

// Irradiance at p (on a patch of normal n) from one delta emitter, visibility included. Patches
// are one-sided, as the form factors and Mitsuba's diffuse BSDF: light behind the patch (a sun
// on a wall's outside) does not count.
Color irradiance_from(const Scene& scene, const Emitter& e, const Vec3& p, const Vec3& n) {
  LightSample ls;
  if (!sample_Li(e, 1.f, p, {0.5f, 0.5f}, ls)) return Color(0.f);
  const float cos_theta = dot(n, ls.wi);
  if (!(cos_theta > 0.f)) return Color(0.f);
  return scene.visible_point(p, n, ls.p) ? ls.Le * cos_theta : Color(0.f);
}

// Irradiance at p (normal n, front side) from the environment, visibility included: m x m
// stratified pairs of one cosine-weighted direction and one the environment samples, combined
// by the balance heuristic [Veach 1997, sec. 9.2], strata shifted by rng (Cranley-Patterson).
Color environment_irradiance(const Scene& scene, const Emitter& env, const Vec3& p, const Vec3& n, int m, Pcg32& rng) {
  const Frame frame = Frame::from_normal(n);
  const Point2 shift{rng.next_float(), rng.next_float()};
  const auto stratum = [&](int a, int b) {
    const float u = (static_cast<float>(a) + shift.u) / static_cast<float>(m);
    const float v = (static_cast<float>(b) + shift.v) / static_cast<float>(m);
    return Point2{u, v};
  };
  // One direction's share: L cos V / (pdf_cos + pdf_env), the balance heuristic's estimate.
  const auto share = [&](const Vec3& w) {
    const float cos_theta = dot(n, w);
    if (!(cos_theta > 0.f)) return Color(0.f);
    const float pdf = cos_theta * kInvPi + pdf_Li(env, 1.f, w, 0.f, 1.f);
    const Color L = radiance(env, -w, {}) * (cos_theta / pdf);
    if (is_black(L) || !scene.visible_point(p, n, scene.beyond(p, w))) return Color(0.f);
    return L;
  };
  Color sum(0.f);
  for (int a = 0; a < m; ++a) {
    for (int b = 0; b < m; ++b) {
      sum += share(frame.to_world(square_to_cosine_hemisphere(stratum(a, b))));
      LightSample ls;
      if (sample_Li(env, 1.f, p, stratum(b, a), ls)) sum += share(ls.wi);
    }
  }
  return sum / static_cast<float>(m * m);
}

}  // namespace

FirstShot::FirstShot(const Scene& scene, int points_per_axis, int env_strata)
    : scene_(scene), environment_(scene.environment()), env_strata_(env_strata) {
  if (points_per_axis < 1 || points_per_axis > 64) throw std::invalid_argument("points_per_axis must be in [1, 64]");
  if (env_strata < 1 || env_strata > 64) throw std::invalid_argument("env_strata must be in [1, 64]");
  for (const Emitter& e : scene.emitters()) {
    if (is_delta_light(e)) delta_lights_.push_back(&e);
  }
  grid_ = centroid_grid(points_per_axis);
}

Color FirstShot::mean_irradiance(const Vec3 v[3], const Vec3& n, Pcg32& rng) const {
  if (empty()) return Color(0.f);
  Color sum(0.f);
  for (const Point2 b : grid_) {
    const Vec3 p = v[0] * (1.f - b.u - b.v) + v[1] * b.u + v[2] * b.v;
    for (const Emitter* e : delta_lights_) sum += irradiance_from(scene_, *e, p, n);
    if (environment_ != nullptr) sum += environment_irradiance(scene_, *environment_, p, n, env_strata_, rng);
  }
  return sum / static_cast<float>(grid_.size());
}

std::vector<Color> direct_irradiance(const Scene& patches, int points_per_axis, int env_strata, uint64_t seed,
                                     int threads, RenderControl& control) {
  const FirstShot first_shot(patches, points_per_axis, env_strata);
  const size_t n = patches.triangle_count();
  std::vector<Color> H(n, Color(0.f));
  control.total.store(n);
  if (first_shot.empty()) return H;
  parallel_for_each_index(threads, n, [&](size_t k) {
    if (control.cancelled()) return;
    const uint32_t prim = static_cast<uint32_t>(k);
    const Vec3 v[3] = {patches.vertex(prim, 0), patches.vertex(prim, 1), patches.vertex(prim, 2)};
    Pcg32 rng(seed, k);
    H[k] = first_shot.mean_irradiance(v, patches.normal(prim), rng);
    control.done.fetch_add(1, std::memory_order_relaxed);
  });
  return H;
}

}  // namespace dualight
