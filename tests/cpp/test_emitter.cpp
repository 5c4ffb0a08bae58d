// Emitters as a closed set (lights/): flags, the area emitter's densities against each other,
// and the scene's power-proportional choice; the members at infinity (directional, constant,
// envmap), with a chi-square test of the environment map's sampling and its density following
// the interpolated radiance.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include "check.h"
#include "core/rng.h"
#include "geometry/scene.h"
#include "lights/emitter.h"
#include "lights/emitter_sampler.h"
#include "lights/environment_map.h"

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
  CHECK(!is_black(radiance(e, Vec3(0.1f, 0.f, 1.f), {})));
  CHECK(is_black(radiance(e, Vec3(0.1f, 0.f, -1.f), {})));  // one-sided
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
    CHECK_NEAR(ls.pdf_w / pdf_Li(e, pmf, ls.wi, dist, cos_light), 1.f, 1e-5f);
    CHECK_NEAR(length(ref + ls.wi * dist - ls.p), 0.f, 1e-5f);
    const EmitterPoint y = sample_Le_position(e, pmf, u);
    CHECK(y.pdf_a == pdf_Le_position(e, pmf, y.p));
    CHECK_NEAR(y.pdf_a, pmf / 2.f, 1e-7f);  // area 2
    EmitterDirection d;
    REQUIRE(sample_Le_direction(e, y.pdf_a, y.p, y.uv, u, d));
    CHECK(d.pdf_w == pdf_Le_direction(e, d.w));
    // beta = Le |cos| / (pdf_a pdf_w).
    CHECK_NEAR(d.beta.x / (2.f * d.w.z / (y.pdf_a * d.pdf_w)), 1.f, 1e-5f);
  }
  LightSample behind;
  CHECK(!sample_Li(e, pmf, Vec3(0.3f, 0.4f, -1.f), {0.5f, 0.5f}, behind));  // faces away
}

// Mitsuba's `area` emitter with a `radiance` texture: every point emits the texture at its
// surface coordinates (here the barycentrics of corners 1 and 2, as the triangle has no uvs:
// the point's x and y); the emitter's power is the texture's mean over the triangle.
TEST_CASE("textured_area_emitter_emits_its_texture_at_each_point") {
  Material lamp{Lambertian{Color(0.f)}, Color(0.f)};
  const CheckerboardTexture checker{Color(2.f, 4.f, 6.f), Color(0.f), {}};
  lamp.emission_texture = Texture{checker};
  const Scene scene({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, {0}, {lamp});
  REQUIRE(scene.emitter_count() == 1);
  const Emitter& e = scene.emitters()[0];
  // colour0 covers the square [0, 1/2)^2, half of the triangle u + v < 1.
  CHECK_NEAR(power(e), 0.5 * 0.5 * 4.0, 0.03 * 4.0 * 0.25);
  CHECK_NEAR(std::get<AreaEmitter>(e).Le.y, 2.f, 0.06f);
  for (const Point2 u : {Point2{0.1f, 0.2f}, Point2{0.7f, 0.9f}, Point2{0.5f, 0.05f}, Point2{0.95f, 0.3f}}) {
    const EmitterPoint y = sample_Le_position(e, 1.f, u);
    CHECK_NEAR(y.uv.u, y.p.x, 1e-6f);
    CHECK_NEAR(y.uv.v, y.p.y, 1e-6f);
    const Color expected = eval_rgb(lamp.emission_texture.value(), y.uv);
    CHECK(radiance(e, Vec3(0.f, 0.f, 1.f), y.uv).y == expected.y);
    EmitterDirection d;
    REQUIRE(sample_Le_direction(e, y.pdf_a, y.p, y.uv, u, d));
    CHECK_NEAR(d.beta.y, expected.y * kPi / y.pdf_a, 1e-5f);
    LightSample ls;
    REQUIRE(sample_Li(e, 1.f, Vec3(0.3f, 0.3f, 1.f), u, ls));
    CHECK(ls.Le.y == eval_rgb(lamp.emission_texture.value(), {ls.p.x, ls.p.y}).y);
    SurfaceHit hit;  // the texture seen by a ray at the same point
    REQUIRE(scene.intersect(Ray{Vec3(y.p.x, y.p.y, 1.f), Vec3(0.f, 0.f, -1.f)}, hit));
    CHECK(radiance(e, Vec3(0.f, 0.f, 1.f), hit.uv).y == expected.y);
  }
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
  CHECK(pdf_Li(e, 0.5f, Vec3(0.f, 0.f, 1.f), 2.f, 1.f) == 0.f);  // no path hits it
  const EmitterPoint y = sample_Le_position(e, 0.5f, {0.1f, 0.9f});
  CHECK((!y.on_surface && y.pdf_a == 0.5f));
  // Light subpaths leave uniformly: beta = I / (pmf / (4 pi)), every direction.
  for (const Point2 u : {Point2{0.1f, 0.2f}, Point2{0.7f, 0.9f}, Point2{0.5f, 0.5f}}) {
    EmitterDirection d;
    REQUIRE(sample_Le_direction(e, y.pdf_a, y.p, y.uv, u, d));
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
  CHECK(radiance(e, towards(0.f), {}).x == 3.f);
  CHECK(radiance(e, towards(29.f), {}).x == 3.f);                      // inside the beam
  CHECK_NEAR(radiance(e, towards(35.f), {}).x, 1.5f, 1e-3f);           // half way, linear in angle
  CHECK(is_black(radiance(e, towards(41.f), {})));                     // beyond the cutoff
  CHECK(is_black(radiance(e, Vec3(0.f, 0.f, 1.f), {})));              // behind
  // Uniform in the cone: every sample inside it, density 1 / (2 pi (1 - cos 40)).
  const float expected_pdf = 1.f / (2.f * kPi * (1.f - std::cos(40.f * kDeg)));
  int n = 0;
  for (int i = 0; i < 64; ++i) {
    const Point2 u{(i % 8 + 0.5f) / 8.f, (i / 8 + 0.5f) / 8.f};
    EmitterDirection d;
    if (!sample_Le_direction(e, 1.f, Vec3(0.f), {}, u, d)) continue;
    ++n;
    CHECK(-d.w.z > std::cos(40.f * kDeg) - 1e-5f);
    CHECK_NEAR(d.pdf_w, expected_pdf, 1e-4f * expected_pdf);
    CHECK(d.pdf_w == pdf_Le_direction(e, d.w));
    CHECK_NEAR(d.beta.x, radiance(e, d.w, {}).x / d.pdf_w, 1e-4f * d.beta.x + 1e-6f);
  }
  CHECK(n >= 60);
  LightSample ls;
  CHECK(sample_Li(e, 1.f, Vec3(0.f, 0.f, -2.f), {0.5f, 0.5f}, ls));  // on the axis
  CHECK_NEAR(ls.Le.x, 3.f / 4.f, 1e-6f);
  CHECK(!sample_Li(e, 1.f, Vec3(0.f, 0.f, 2.f), {0.5f, 0.5f}, ls));  // behind it: no light
}

namespace {

// A 12 x 7 map: a dim sky brightening towards the zenith, a bright sun-like patch, one black
// cell row near the south pole (whose directions the sampler must never pick).
EnvironmentMap test_map(const Frame& to_world = Frame{Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f), Vec3(0.f, 0.f, 1.f)}) {
  const uint32_t w = 12, h = 7;
  std::vector<float> rgb(3 * w * h);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      const float sky = y >= h - 2 ? 0.f : 0.2f + 0.1f * static_cast<float>(h - y);
      const float sun = (x == 3 && y == 2) ? 40.f : 0.f;
      float* p = &rgb[3 * (y * w + x)];
      p[0] = sky + sun;
      p[1] = 0.5f * sky + sun;
      p[2] = 0.25f * sky;
    }
  }
  return EnvironmentMap(w, h, rgb, 1.5f, to_world);
}

// World direction w turned by half a texel of test_map's 12 columns about the map's axis (y of
// the map's frame `to_world`).
Vec3 half_texel_turned(const Frame& to_world, const Vec3& w) {
  const float c = std::cos(kPi / 12.f), s = std::sin(kPi / 12.f);
  const Vec3 local = to_world.to_local(w);
  return to_world.to_world(Vec3(c * local.x - s * local.z, local.y, s * local.x + c * local.z));
}

// Pearson's chi-square of `counts` against `expected` (bins with expected < 5 pooled) and its
// degrees of freedom.
std::pair<double, int> chi_square(const std::vector<double>& counts, const std::vector<double>& expected) {
  double stat = 0.0, pool_c = 0.0, pool_e = 0.0;
  int bins = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    if (expected[i] < 5.0) {
      pool_c += counts[i];
      pool_e += expected[i];
      continue;
    }
    stat += (counts[i] - expected[i]) * (counts[i] - expected[i]) / expected[i];
    ++bins;
  }
  if (pool_e > 0.0) {
    stat += (pool_c - pool_e) * (pool_c - pool_e) / std::max(pool_e, 1e-12);
    ++bins;
  }
  return {stat, bins - 1};
}

// The chi-square quantile at 1 - 1e-4 (Wilson-Hilferty; z = 3.719).
double chi_square_limit(int dof) {
  const double k = dof, z = 3.719;
  const double c = 1.0 - 2.0 / (9.0 * k) + z * std::sqrt(2.0 / (9.0 * k));
  return k * c * c * c;
}

// Sampled directions binned on a (phi, cos theta) grid against `pdf` integrated over each bin.
template <class Pdf>
std::pair<double, int> env_sampling_chi_square(const EnvironmentMap& map, const Pdf& pdf) {
  constexpr int kPhi = 24, kCos = 16, kSub = 32;
  constexpr size_t kSamples = 400000;
  const auto bin_of = [&](const Vec3& d) {
    float phi = std::atan2(d.y, d.x);
    if (phi < 0.f) phi += 2.f * kPi;
    const int i = std::min(static_cast<int>(phi / (2.f * kPi) * kPhi), kPhi - 1);
    const int j = std::min(static_cast<int>((d.z + 1.f) * 0.5f * kCos), kCos - 1);
    return static_cast<size_t>(j * kPhi + i);
  };
  std::vector<double> counts(kPhi * kCos, 0.0), expected(kPhi * kCos, 0.0);
  uint64_t state = 0x853c49e6748fea9bull;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<float>(state >> 40) * 0x1p-24f;
  };
  for (size_t k = 0; k < kSamples; ++k) {
    float p = 0.f;
    const Vec3 d = map.sample({next(), next()}, p);
    counts[bin_of(d)] += 1.0;
  }
  // Midpoint rule on kSub x kSub points per bin (uniform in phi and z: equal solid angles).
  const double cell = 4.0 * kPi / (kPhi * kCos * kSub * kSub);
  for (int j = 0; j < kCos * kSub; ++j) {
    const float z = -1.f + 2.f * (static_cast<float>(j) + 0.5f) / (kCos * kSub);
    const float r = std::sqrt(std::max(0.f, 1.f - z * z));
    for (int i = 0; i < kPhi * kSub; ++i) {
      const float phi = 2.f * kPi * (static_cast<float>(i) + 0.5f) / (kPhi * kSub);
      const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
      expected[bin_of(d)] += pdf(d) * cell * kSamples;
    }
  }
  return chi_square(counts, expected);
}

}  // namespace

TEST_CASE("directional_emitter_is_a_delta_direction_at_infinity") {
  DirectionalEmitter d = make_directional(Vec3(0.f, 0.f, -2.f), Color(3.f, 2.f, 1.f));
  attach_scene(d, BoundingSphere{Vec3(1.f, 0.f, 0.f), 2.f});
  const Emitter e = d;
  CHECK((is_delta_direction(e) && is_infinite(e) && is_delta_light(e) && !is_delta_position(e)));
  CHECK_NEAR(power(e), 4.0 * 2.0, 1e-5);  // r^2 times the mean irradiance
  LightSample ls;
  REQUIRE(sample_Li(e, 0.5f, Vec3(1.5f, 0.f, 0.5f), {0.3f, 0.7f}, ls));
  CHECK((!ls.on_surface && ls.pdf_w == 0.5f && ls.Le.x == 3.f));
  CHECK_NEAR(ls.wi.z, 1.f, 1e-6f);
  CHECK(length(ls.p - Vec3(1.f, 0.f, 0.f)) > 2.f);  // the shadow ray ends beyond the sphere
  CHECK(pdf_Li(e, 0.5f, ls.wi, 1.f, 1.f) == 0.f);
  // Light subpaths: its direction at infinity with the choice's probability, then a point on
  // the distant disk (radius r, behind the sphere, facing the light), along the direction.
  const EmitterPoint y = sample_Le_position(e, 0.5f, {0.9f, 0.1f});
  CHECK((y.at_infinity && !y.on_surface && y.pdf_a == 0.5f));
  CHECK_NEAR(y.p.z, 1.f, 1e-6f);
  EmitterDirection dir;
  REQUIRE(sample_Le_direction(e, y.pdf_a, y.p, y.uv, {0.9f, 0.1f}, dir));
  CHECK_NEAR(dir.w.z, -1.f, 1e-6f);
  CHECK_NEAR(dir.origin.z, 2.f, 1e-5f);
  CHECK(length(dir.origin - Vec3(1.f, 0.f, 2.f)) <= 2.f + 1e-5f);
  CHECK_NEAR(dir.pdf_w, 1.f / (kPi * 4.f), 1e-7f);
  CHECK(dir.pdf_w == pdf_Le_direction(e, dir.w));
  CHECK_NEAR(dir.beta.x / (3.f / (0.5f * dir.pdf_w)), 1.f, 1e-5f);  // E / (pmf pdf_disk)
}

TEST_CASE("constant_emitter_samples_the_sphere_and_knows_its_density") {
  ConstantEmitter c{Color(0.5f), {}};
  attach_scene(c, BoundingSphere{Vec3(0.f), 3.f});
  const Emitter e = c;
  CHECK((is_infinite(e) && !is_delta_light(e)));
  CHECK_NEAR(power(e), 4.0 * kPi * 9.0 * 0.5, 1e-4);
  LightSample ls;
  REQUIRE(sample_Li(e, 0.25f, Vec3(0.f, 1.f, 0.f), {0.2f, 0.9f}, ls));
  CHECK_NEAR(ls.pdf_w, 0.25f / (4.f * kPi), 1e-7f);
  CHECK(ls.pdf_w == pdf_Li(e, 0.25f, ls.wi, 0.f, 1.f));
  CHECK(length(ls.p) > 3.f);
  // A light subpath's start samples directions as next-event estimation does.
  const EmitterPoint y = sample_Le_position(e, 0.25f, {0.2f, 0.9f});
  CHECK((y.at_infinity && y.pdf_a == ls.pdf_w && y.pdf_a == pdf_Le_position(e, 0.25f, y.p)));
  CHECK_NEAR(length(y.p - ls.wi), 0.f, 1e-6f);
  EmitterDirection dir;
  REQUIRE(sample_Le_direction(e, y.pdf_a, y.p, y.uv, {0.6f, 0.3f}, dir));
  CHECK_NEAR(dot(dir.w, y.p), -1.f, 1e-6f);
  CHECK_NEAR(dot(dir.origin, y.p), 3.f, 1e-5f);  // on the disk facing the light, r from the centre
  CHECK_NEAR(dir.beta.x / (0.5f / (y.pdf_a * dir.pdf_w)), 1.f, 1e-5f);
}

TEST_CASE("envmap_uses_mitsubas_lat_long_conventions") {
  const EnvironmentMap map = test_map();
  // Texel (x, y) sits at u = (x + 0.5) / width, v = y / (height - 1); direction
  // (sin phi sin theta, cos theta, -cos phi sin theta) for phi = 2 pi u, theta = pi v.
  const auto direction = [](float u, float v) {
    const float phi = 2.f * kPi * u, theta = kPi * v;
    return Vec3(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
  };
  const Color sun = map.eval(direction(3.5f / 12.f, 2.f / 6.f));
  CHECK_NEAR(sun.x, 1.5f * (40.f + 0.2f + 0.1f * 5.f), 1e-3f);
  // Halfway to the next column: the mean of the two texels.
  const Color half = map.eval(direction(4.f / 12.f, 2.f / 6.f));
  CHECK_NEAR(half.x, 1.5f * (20.f + 0.2f + 0.1f * 5.f), 1e-3f);
  // Rotated: the map's frame carried along.
  const Frame turn{Vec3(0.f, 0.f, 1.f), Vec3(0.f, 1.f, 0.f), Vec3(-1.f, 0.f, 0.f)};  // +90 degrees about y
  const EnvironmentMap rotated = test_map(turn);
  const Vec3 d = direction(3.5f / 12.f, 2.f / 6.f);
  CHECK_NEAR(rotated.eval(turn.to_world(d)).x, sun.x, 1e-3f);
  CHECK(rotated.eval(d).x < 0.5f * sun.x);
}

TEST_CASE("envmap_sampling_matches_its_density_chi_square") {
  const EnvironmentMap map = test_map();
  // Its density integrates to one and agrees with what sample() reports.
  float p = 0.f;
  for (const Point2 u : {Point2{0.1f, 0.3f}, Point2{0.6f, 0.27f}, Point2{0.95f, 0.5f}}) {
    const Vec3 d = map.sample(u, p);
    CHECK_NEAR(p / map.pdf(d), 1.f, 1e-3f);
    CHECK(!is_black(map.eval(d)));
  }
  const auto [stat, dof] = env_sampling_chi_square(map, [&](const Vec3& d) { return map.pdf(d); });
  MESSAGE("chi-square " << stat << " with " << dof << " degrees of freedom, limit " << chi_square_limit(dof));
  CHECK(stat < chi_square_limit(dof));
  // Negative control: the samples against the density of the map turned by 90 degrees fail.
  const Frame turn{Vec3(0.f, 0.f, 1.f), Vec3(0.f, 1.f, 0.f), Vec3(-1.f, 0.f, 0.f)};
  const EnvironmentMap rotated = test_map(turn);
  const auto [wrong, wrong_dof] = env_sampling_chi_square(map, [&](const Vec3& d) { return rotated.pdf(d); });
  CHECK(wrong > chi_square_limit(wrong_dof));
}

// Around the sun (the texel of 40), the four bilinear patches it is a corner of, radiance falls
// from 40 to the sky's 1.5 or less across each: sampled in proportion to the interpolated
// radiance (times sin(theta), which the solid angle takes out again), luminance over density stays
// within the band sin(theta) spans there. Negative control: a density uniform within each patch
// (its mean) lets the ratio follow the radiance, over a range of more than 20.
TEST_CASE("envmap_density_follows_the_interpolated_radiance") {
  const EnvironmentMap map = test_map();
  const auto direction = [](float u, float v) {
    const float phi = 2.f * kPi * u, theta = kPi * v;
    return Vec3(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
  };
  double ratio_min = 1e30, ratio_max = 0.0, flat_min = 1e30, flat_max = 0.0;
  for (const uint32_t cx : {2u, 3u}) {
    for (const uint32_t cy : {1u, 2u}) {
      std::vector<Vec3> points;
      for (int i = 0; i < 9; ++i) {
        for (int j = 0; j < 9; ++j) {
          const float s = 0.05f + 0.1125f * static_cast<float>(i), t = 0.05f + 0.1125f * static_cast<float>(j);
          points.push_back(direction((static_cast<float>(cx) + 0.5f + s) / 12.f, (static_cast<float>(cy) + t) / 6.f));
        }
      }
      double mean_pdf = 0.0;
      for (const Vec3& d : points) mean_pdf += map.pdf(d) / static_cast<double>(points.size());
      for (const Vec3& d : points) {
        const double L = luminance(map.eval(d)), r = L / map.pdf(d), flat = L / mean_pdf;
        ratio_min = std::min(ratio_min, r), ratio_max = std::max(ratio_max, r);
        flat_min = std::min(flat_min, flat), flat_max = std::max(flat_max, flat);
      }
    }
  }
  MESSAGE("luminance / density from " << ratio_min << " to " << ratio_max << "; uniform within patches from "
                                      << flat_min << " to " << flat_max);
  CHECK(ratio_max / ratio_min < 2.0);  // sin(theta) spans 0.5 to 1 across these patches
  CHECK(flat_max / flat_min > 20.0);
}

// sample() reads the radiance at its sample's place in its cell: eval() of the direction it
// returns, to rounding, at random samples of a rotated map. Control: the place half a texel off
// in u (what reading texels from the cell's corner instead of its texel centres gives) differs.
TEST_CASE("envmap_sample_reads_the_radiance_eval_finds") {
  const Frame turn{Vec3(0.f, 0.f, -1.f), Vec3(0.f, 1.f, 0.f), Vec3(1.f, 0.f, 0.f)};
  const EnvironmentMap map = test_map(turn);
  Pcg32 rng(21, 22);
  double worst = 0.0, control = 0.0;
  for (int i = 0; i < 4000; ++i) {
    const Point2 u{rng.next_float(), rng.next_float()};
    float pdf = 0.f;
    Color L;
    const Vec3 w = map.sample(u, pdf, &L);
    if (!(pdf > 0.f)) continue;
    const Color E = map.eval(w);
    worst = std::max(worst, static_cast<double>(max_component(vmax(L - E, E - L)) / max_component(E)));
    const Color H = map.eval(half_texel_turned(turn, w));
    control = std::max(control, static_cast<double>(max_component(vmax(L - H, H - L)) / max_component(E)));
  }
  MESSAGE("largest relative difference " << worst << "; half a texel off " << control);
  CHECK(worst < 1e-4);
  CHECK(control > 1e-2);
}

// eval(d, pdf) finds d's place in the map once for both: eval(d) and pdf(d) to rounding, at
// random directions of a rotated map (poles included). Control: eval half a texel off differs.
TEST_CASE("envmap_eval_with_its_pdf_is_eval_and_pdf") {
  const Frame turn{Vec3(0.f, 0.f, -1.f), Vec3(0.f, 1.f, 0.f), Vec3(1.f, 0.f, 0.f)};
  const EnvironmentMap map = test_map(turn);
  Pcg32 rng(23, 24);
  double worst_L = 0.0, worst_pdf = 0.0, control = 0.0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 d = i < 2 ? Vec3(0.f, i == 0 ? 1.f : -1.f, 0.f)
                         : square_to_uniform_sphere({rng.next_float(), rng.next_float()});
    float pdf = -1.f;
    const Color L = map.eval(d, pdf);
    const Color E = map.eval(d);
    const float p = map.pdf(d);
    const double scale = std::max(max_component(E), 1e-6f);
    worst_L = std::max(worst_L, static_cast<double>(max_component(vmax(L - E, E - L))) / scale);
    worst_pdf = std::max(worst_pdf, std::abs(static_cast<double>(pdf) - p) / std::max(p, 1e-6f));
    const Color H = map.eval(half_texel_turned(turn, d));
    control = std::max(control, static_cast<double>(max_component(vmax(L - H, H - L))) / scale);
  }
  MESSAGE("largest relative differences: radiance " << worst_L << ", density " << worst_pdf << "; half a texel off "
                                                     << control);
  CHECK(worst_L < 1e-4);
  CHECK(worst_pdf < 1e-4);
  CHECK(control > 1e-2);
}

TEST_CASE("envmap_rejects_bad_images") {
  const Frame id{Vec3(1.f, 0.f, 0.f), Vec3(0.f, 1.f, 0.f), Vec3(0.f, 0.f, 1.f)};
  CHECK_THROWS_AS(EnvironmentMap(2, 2, std::vector<float>(12, 0.f), 1.f, id), std::invalid_argument);  // black
  CHECK_THROWS_AS(EnvironmentMap(2, 2, std::vector<float>(11, 1.f), 1.f, id), std::invalid_argument);
  std::vector<float> nan(12, 1.f);
  nan[4] = std::nanf("");
  CHECK_THROWS_AS(EnvironmentMap(2, 2, nan, 1.f, id), std::invalid_argument);
  // A 1 x 1 image is padded to 2 x 3, as Mitsuba: a constant environment.
  const EnvironmentMap one(1, 1, {0.5f, 0.5f, 0.5f}, 2.f, id);
  CHECK_NEAR(one.eval(Vec3(0.3f, 0.8f, 0.52f) / length(Vec3(0.3f, 0.8f, 0.52f))).x, 1.f, 1e-6f);
  CHECK_NEAR(one.mean_radiance(), 1.0, 1e-5);
}
