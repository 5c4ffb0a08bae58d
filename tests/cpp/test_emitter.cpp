// Emitters as a closed set (lights/): flags, the area emitter's densities against each other,
// and the scene's power-proportional choice.
#include <cmath>
#include <stdexcept>

#include "check.h"
#include "geometry/scene.h"
#include "lights/emitter.h"
#include "lights/emitter_sampler.h"

using namespace dualight;

namespace {

Emitter triangle_emitter(Color Le, float scale = 1.f) {
  const Vec3 p0(0.f, 0.f, 0.f), p1(scale, 0.f, 0.f), p2(0.f, scale, 0.f);
  return AreaEmitter{p0, p1, p2, Vec3(0.f, 0.f, 1.f), 0.5f * scale * scale, 0, Le};
}

}  // namespace

TEST_CASE("area_emitter_reports_a_surface_not_a_delta") {
  const Emitter e = triangle_emitter(Color(1.f));
  CHECK(flags(e) == EmitterFlags::Surface);
  CHECK((!is_delta_position(e) && !is_delta_direction(e)));
  CHECK(!is_black(radiance(e, Vec3(0.1f, 0.f, 1.f))));
  CHECK(is_black(radiance(e, Vec3(0.1f, 0.f, -1.f))));  // one-sided
  CHECK_NEAR(power(e), 0.5, 1e-9);
}

TEST_CASE("area_emitter_densities_agree") {
  const Emitter e = triangle_emitter(Color(2.f, 1.f, 0.5f), 2.f);
  const float pmf = 0.25f;
  const Vec3 ref(0.3f, 0.4f, 1.5f);
  for (const Point2 u : {Point2{0.1f, 0.2f}, Point2{0.7f, 0.9f}, Point2{0.5f, 0.05f}}) {
    LightSample ls;
    REQUIRE(sample_Li(e, pmf, ref, u, ls));
    CHECK(ls.on_surface);
    const float dist = std::sqrt(ls.dist2), cos_light = -dot(ls.n, ls.wi);
    CHECK_NEAR(ls.pdf_w / pdf_Li(e, pmf, dist, cos_light), 1.f, 1e-5f);
    CHECK_NEAR(length(ref + ls.wi * dist - ls.p), 0.f, 1e-5f);
    const EmitterPoint y = sample_Le_position(e, pmf, u);
    CHECK(y.pdf_a == pdf_Le_position(e, pmf));
    CHECK_NEAR(y.pdf_a, pmf / 2.f, 1e-7f);  // area 2
    EmitterDirection d;
    REQUIRE(sample_Le_direction(e, y.pdf_a, u, d));
    CHECK(d.pdf_w == pdf_Le_direction(e, d.w));
    // beta = Le |cos| / (pdf_a pdf_w).
    CHECK_NEAR(d.beta.x / (2.f * d.w.z / (y.pdf_a * d.pdf_w)), 1.f, 1e-5f);
  }
  LightSample behind;
  CHECK(!sample_Li(e, pmf, Vec3(0.3f, 0.4f, -1.f), {0.5f, 0.5f}, behind));  // faces away
}

TEST_CASE("power_sampler_chooses_in_proportion_to_power") {
  const std::vector<Emitter> emitters{triangle_emitter(Color(1.f)), triangle_emitter(Color(3.f))};
  const PowerEmitterSampler sampler(emitters);
  CHECK_NEAR(sampler.pmf(0), 0.25f, 1e-6f);
  CHECK_NEAR(sampler.pmf(1), 0.75f, 1e-6f);
  CHECK(sampler.sample(0.2f) == 0);
  CHECK(sampler.sample(0.3f) == 1);
}

TEST_CASE("scene_builds_one_area_emitter_per_emissive_triangle") {
  const std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const std::vector<uint32_t> triangles{0, 1, 2, 1, 3, 2};
  const std::vector<Material> materials{{Lambertian{Color(0.5f)}, Color(0.f)}, {Lambertian{Color(0.5f)}, Color(4.f)}};
  const Scene scene(positions, triangles, {0, 1}, materials);
  CHECK(scene.emitter_count() == 1);
  CHECK(scene.emitter_at(0) == nullptr);
  REQUIRE(scene.emitter_at(1) != nullptr);
  CHECK(scene.emitter_pmf(*scene.emitter_at(1)) == 1.f);
  CHECK(scene.choose_emitter(0.7f).emitter == scene.emitter_at(1));
  // Emitters on surfaces come from the materials; the extra list is for the others.
  bool threw = false;
  try {
    const Scene bad(positions, triangles, {0, 1}, materials, {triangle_emitter(Color(1.f))});
  } catch (const std::invalid_argument&) {
    threw = true;
  }
  CHECK(threw);
}

TEST_CASE("point_emitter_is_a_delta_position_with_intensity_over_r2") {
  const Emitter e = PointEmitter{Vec3(1.f, 2.f, 3.f), Color(4.f, 2.f, 1.f)};
  CHECK(flags(e) == EmitterFlags::DeltaPosition);
  CHECK((is_delta_position(e) && !is_delta_direction(e)));
  CHECK_NEAR(power(e), 4.0 * 7.0 / 3.0, 1e-6);  // flux / pi = 4 pi I / pi
  LightSample ls;
  REQUIRE(sample_Li(e, 0.5f, Vec3(1.f, 2.f, 1.f), {0.3f, 0.3f}, ls));
  CHECK(!ls.on_surface);
  CHECK(ls.pdf_w == 0.5f);  // the choice's probability
  CHECK_NEAR(ls.Le.x, 4.f / 4.f, 1e-6f);  // I / r^2, r = 2
  CHECK_NEAR(ls.wi.z, 1.f, 1e-6f);
  CHECK(pdf_Li(e, 0.5f, 2.f, 1.f) == 0.f);  // no path hits it
  const EmitterPoint y = sample_Le_position(e, 0.5f, {0.1f, 0.9f});
  CHECK((!y.on_surface && y.pdf_a == 0.5f));
  // Light subpaths leave uniformly: beta = I / (pmf / (4 pi)), every direction.
  for (const Point2 u : {Point2{0.1f, 0.2f}, Point2{0.7f, 0.9f}, Point2{0.5f, 0.5f}}) {
    EmitterDirection d;
    REQUIRE(sample_Le_direction(e, y.pdf_a, u, d));
    CHECK_NEAR(length(d.w), 1.f, 1e-5f);
    CHECK(d.pdf_w == pdf_Le_direction(e, d.w));
    CHECK_NEAR(d.beta.x, 4.f * 4.f * kPi / 0.5f, 1e-3f);
  }
}

TEST_CASE("spot_emitter_falls_off_as_mitsuba_and_samples_its_cone") {
  constexpr float kDeg = kPi / 180.f;
  const SpotEmitter spot = make_spot(Vec3(0.f), Vec3(0.f, 0.f, -2.f), Color(3.f), 40.f * kDeg, 30.f * kDeg);
  const Emitter e = spot;
  CHECK(flags(e) == EmitterFlags::DeltaPosition);
  const auto towards = [](float degrees) {
    return Vec3(std::sin(degrees * kDeg), 0.f, -std::cos(degrees * kDeg));
  };
  CHECK(radiance(e, towards(0.f)).x == 3.f);
  CHECK(radiance(e, towards(29.f)).x == 3.f);                      // inside the beam
  CHECK_NEAR(radiance(e, towards(35.f)).x, 1.5f, 1e-3f);           // half way, linear in angle
  CHECK(is_black(radiance(e, towards(41.f))));                     // beyond the cutoff
  CHECK(is_black(radiance(e, Vec3(0.f, 0.f, 1.f))));              // behind
  // Uniform in the cone: every sample inside it, density 1 / (2 pi (1 - cos 40)).
  const float expected_pdf = 1.f / (2.f * kPi * (1.f - std::cos(40.f * kDeg)));
  int n = 0;
  for (int i = 0; i < 64; ++i) {
    const Point2 u{(i % 8 + 0.5f) / 8.f, (i / 8 + 0.5f) / 8.f};
    EmitterDirection d;
    if (!sample_Le_direction(e, 1.f, u, d)) continue;
    ++n;
    CHECK(-d.w.z > std::cos(40.f * kDeg) - 1e-5f);
    CHECK_NEAR(d.pdf_w, expected_pdf, 1e-4f * expected_pdf);
    CHECK(d.pdf_w == pdf_Le_direction(e, d.w));
    CHECK_NEAR(d.beta.x, radiance(e, d.w).x / d.pdf_w, 1e-4f * d.beta.x + 1e-6f);
  }
  CHECK(n >= 60);
  LightSample ls;
  CHECK(sample_Li(e, 1.f, Vec3(0.f, 0.f, -2.f), {0.5f, 0.5f}, ls));  // on the axis
  CHECK_NEAR(ls.Le.x, 3.f / 4.f, 1e-6f);
  CHECK(!sample_Li(e, 1.f, Vec3(0.f, 0.f, 2.f), {0.5f, 0.5f}, ls));  // behind it: no light
}
