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
