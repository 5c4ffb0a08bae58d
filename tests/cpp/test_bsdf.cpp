// Fresnel reflectance of a smooth dielectric and the delta BSDFs' sampled geometry. The
// statistical tests (lobe frequencies, chi-square of the Lambertian) are in tests/test_materials.py.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "check.h"
#include "materials/bsdf.h"

using namespace dualight;

namespace {

const float kEtas[] = {1.5f, 1.33f, 2.4f, 0.75f};

Vec3 direction(float cos_theta, float phi) {
  const float s = std::sqrt(std::max(0.f, 1.f - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

}  // namespace

TEST_CASE("fresnel_at_normal_incidence_from_both_sides") {
  for (const float eta : kEtas) {
    const float r0 = ((eta - 1.f) / (eta + 1.f)) * ((eta - 1.f) / (eta + 1.f));
    const Fresnel out = fresnel_dielectric(1.f, eta), in = fresnel_dielectric(-1.f, eta);
    CHECK_NEAR(out.R, r0, 1e-6f);
    CHECK_NEAR(in.R, r0, 1e-6f);
    CHECK_NEAR(out.cos_t, 1.f, 1e-6f);
    CHECK_NEAR(out.eta_ratio, eta, 1e-6f);
    CHECK_NEAR(in.eta_ratio, 1.f / eta, 1e-6f);
  }
}

TEST_CASE("fresnel_is_total_beyond_the_critical_angle") {
  // TIR on the side with the higher index: the interior when eta > 1, the exterior when eta < 1.
  for (const float eta : kEtas) {
    const float n_dense_over_thin = eta > 1.f ? eta : 1.f / eta;
    const float sin_c = 1.f / n_dense_over_thin;
    const float cos_c = std::sqrt(1.f - sin_c * sin_c);
    const float side = eta > 1.f ? -1.f : 1.f;  // sign of cos_i on the dense side
    for (int k = 1; k < 100; ++k) {
      const float cos_i = cos_c * (1.f - k / 100.f) * 0.999f;  // more oblique than critical
      const Fresnel F = fresnel_dielectric(side * cos_i, eta);
      CHECK(F.R == 1.f);
      CHECK(F.cos_t == 0.f);
    }
    // Just before the critical angle some light still gets through.
    CHECK(fresnel_dielectric(side * std::min(1.f, cos_c * 1.01f), eta).R < 1.f);
    // From the thin side there is never total reflection except at grazing incidence.
    CHECK(fresnel_dielectric(-side * 0.01f, eta).R < 1.f);
  }
}

TEST_CASE("fresnel_is_continuous_and_in_the_unit_interval") {
  // R(cos_i) on [-1, 1]: bounded, and its largest step shrinks as the grid is refined: near
  // the critical angle R approaches 1 like a square root, so a 100x finer grid has about 10x
  // smaller steps, where a jump would keep its size.
  for (const float eta : kEtas) {
    float max_step[2] = {0.f, 0.f};
    const int sizes[2] = {20000, 2000000};
    bool in_range = true;
    for (int g = 0; g < 2; ++g) {
      float prev = fresnel_dielectric(-1.f, eta).R;
      for (int i = 1; i <= sizes[g]; ++i) {
        const float cos_i = -1.f + 2.f * static_cast<float>(i) / sizes[g];
        const float R = fresnel_dielectric(cos_i, eta).R;
        in_range &= R >= 0.f && R <= 1.f;
        max_step[g] = std::max(max_step[g], std::abs(R - prev));
        prev = R;
      }
    }
    CHECK(in_range);
    CHECK(max_step[1] < 0.02f);
    CHECK(max_step[1] < 0.2f * max_step[0]);
    std::printf("    eta %.2f: largest step of R %.4f (h = 1e-4), %.4f (h = 1e-6)\n", eta, max_step[0], max_step[1]);
    // Grazing incidence reflects everything from either side (continuity across cos_i = 0).
    CHECK_NEAR(fresnel_dielectric(1e-7f, eta).R, 1.f, 1e-5f);
    CHECK_NEAR(fresnel_dielectric(-1e-7f, eta).R, 1.f, 1e-5f);
  }
}

TEST_CASE("fresnel_is_reciprocal_across_the_interface") {
  // Light refracted from theta_i outside to theta_t inside: reflectance is the same for the
  // reverse path arriving from inside at theta_t. Up to 85 degrees: closer to grazing, float
  // rounding of cos_t (from 1 - sin^2) moves the steep R by more than the tolerance.
  for (const float eta : kEtas) {
    for (int k = 0; k <= 85; ++k) {
      const float cos_i = std::cos(k * kPi / 180.f);
      const Fresnel out = fresnel_dielectric(cos_i, eta);
      if (out.R == 1.f) continue;  // no refracted ray (eta < 1 beyond the critical angle)
      const Fresnel in = fresnel_dielectric(-out.cos_t, eta);
      CHECK_NEAR(in.R, out.R, 2e-5f);
      CHECK_NEAR(in.cos_t, cos_i, 1e-4f);
      CHECK_NEAR(in.eta_ratio * out.eta_ratio, 1.f, 1e-6f);
    }
  }
}

TEST_CASE("dielectric_sampling_follows_reflection_and_snell") {
  for (const float eta : kEtas) {
    const Bsdf glass = Dielectric{eta};
    for (int k = 0; k < 40; ++k) {
      const float cos_o = -0.975f + 0.05f * k;  // both sides, never grazing
      const Vec3 wo = direction(cos_o, 0.3f + 0.1f * k);
      const Fresnel F = fresnel_dielectric(wo.z, eta);
      BsdfSample r, t;
      CHECK(sample(glass, wo, {0.f, 0.5f}, TransportMode::Radiance, r));  // u < R: reflection
      CHECK((r.delta && r.wi.x == -wo.x && r.wi.y == -wo.y && r.wi.z == wo.z));
      CHECK_NEAR(r.pdf_w, F.R, 1e-6f);
      if (F.R == 1.f) continue;
      CHECK(sample(glass, wo, {0.9999f, 0.5f}, TransportMode::Radiance, t));
      if (t.wi.z * wo.z >= 0.f) continue;  // R > 0.9999: reflected after all
      const float n_o = wo.z > 0.f ? 1.f : eta, n_i = wo.z > 0.f ? eta : 1.f;
      const float sin_o = std::hypot(wo.x, wo.y), sin_i = std::hypot(t.wi.x, t.wi.y);
      CHECK_NEAR(n_o * sin_o, n_i * sin_i, 2e-6f);
      CHECK_NEAR(length(t.wi), 1.f, 2e-6f);
      CHECK_NEAR(t.wi.x * wo.y - t.wi.y * wo.x, 0.f, 1e-6f);  // in the plane of incidence
      CHECK(t.wi.x * wo.x + t.wi.y * wo.y <= 0.f);            // on the far side of the normal
      CHECK_NEAR(t.pdf_w, 1.f - F.R, 1e-6f);
      BsdfSample ti;
      CHECK(sample(glass, wo, {0.9999f, 0.5f}, TransportMode::Importance, ti));
      CHECK_NEAR(ti.weight.x / t.weight.x, (n_i / n_o) * (n_i / n_o), 1e-5f);
      CHECK(ti.weight.x == 1.f);
    }
  }
}

TEST_CASE("delta_bsdfs_have_no_density_and_mirror_reflects") {
  const Bsdf mirror = Mirror{Color(0.9f, 0.5f, 0.1f)}, glass = Dielectric{1.5f};
  const Vec3 wo = normalize(Vec3(0.3f, -0.2f, 0.9f)), wi = reflect_local(wo);
  for (const Bsdf* b : {&mirror, &glass}) {
    CHECK(is_delta(*b));
    CHECK(is_black(eval_f(*b, wo, wi, TransportMode::Radiance)));
    CHECK(pdf_w(*b, wo, wi, TransportMode::Importance) == 0.f);
  }
  CHECK(!is_delta(Bsdf{Lambertian{Color(0.5f)}}));
  for (const float side : {1.f, -1.f}) {
    const Vec3 w{wo.x, wo.y, side * wo.z};
    BsdfSample s;
    CHECK(sample(mirror, w, {0.7f, 0.2f}, TransportMode::Radiance, s));
    CHECK((s.delta && s.pdf_w == 1.f && s.wi.z == w.z && s.wi.x == -w.x && s.wi.y == -w.y));
    CHECK((s.weight.x == 0.9f && s.weight.y == 0.5f && s.weight.z == 0.1f));
  }
  BsdfSample s;
  CHECK(!sample(mirror, Vec3(1.f, 0.f, 0.f), {0.5f, 0.5f}, TransportMode::Radiance, s));
  CHECK(!sample(glass, Vec3(1.f, 0.f, 0.f), {0.5f, 0.5f}, TransportMode::Radiance, s));
}

TEST_CASE("bsdfs_report_their_own_flags") {
  const Bsdf lambertian = Lambertian{Color(0.5f)}, mirror = Mirror{Color(0.9f)}, glass = Dielectric{1.5f};
  CHECK(flags(lambertian) == BsdfFlags::DiffuseReflection);
  CHECK(flags(mirror) == BsdfFlags::SpecularReflection);
  CHECK(flags(glass) == (BsdfFlags::SpecularReflection | BsdfFlags::SpecularTransmission));
  CHECK((!is_delta(lambertian) && is_delta(mirror) && is_delta(glass)));
  CHECK((is_diffuse_reflector(flags(lambertian)) && !is_diffuse_reflector(flags(mirror)) &&
         !is_diffuse_reflector(flags(glass))));
  CHECK((!has_transmission(flags(mirror)) && has_transmission(flags(glass))));
  // A lobe that is diffuse and specular at once is not delta: connections can still reach it.
  CHECK(!is_delta(BsdfFlags::DiffuseReflection | BsdfFlags::SpecularReflection));
  CHECK(diffuse_reflectance(lambertian).y == 0.5f);
  CHECK(is_black(diffuse_reflectance(mirror)));
}

TEST_CASE("delta_lobes_match_sampling") {
  const Vec3 wo = normalize(Vec3(0.3f, -0.2f, 0.9f));
  const DeltaLobe m = delta_lobe(Bsdf{Mirror{Color(0.8f)}}, wo, reflect_local(wo));
  CHECK((!m.refraction && m.prob == 1.f && m.coef.x == 0.8f && m.importance_ratio == 1.f));
  CHECK(delta_lobe(Bsdf{Mirror{Color(0.8f)}}, wo, -wo).prob == 0.f);  // a mirror does not refract
  Vec3 wi;
  CHECK(!delta_direction(Bsdf{Mirror{Color(0.8f)}}, wo, true, wi));
  CHECK(!delta_direction(Bsdf{Lambertian{Color(0.5f)}}, wo, false, wi));
  for (const float eta : kEtas) {
    const Bsdf glass = Dielectric{eta};
    const Fresnel F = fresnel_dielectric(wo.z, eta);
    Vec3 refracted;
    REQUIRE(delta_direction(glass, wo, true, refracted));
    const DeltaLobe t = delta_lobe(glass, wo, refracted);
    CHECK((t.refraction && t.prob == 1.f - F.R));
    CHECK_NEAR(t.importance_ratio, 1.f / (F.eta_ratio * F.eta_ratio), 1e-6f);
    // Sampling the refraction gives the same direction and lobe probability.
    BsdfSample s;
    REQUIRE(sample(glass, wo, {0.99999f, 0.5f}, TransportMode::Importance, s));
    CHECK(s.pdf_w == t.prob);
    CHECK_NEAR(length(s.wi - refracted), 0.f, 1e-6f);
    const DeltaLobe r = delta_lobe(glass, wo, reflect_local(wo));
    CHECK((!r.refraction && r.prob == F.R && r.coef.x == F.R));
  }
  // Total internal reflection: no refracted direction from inside beyond the critical angle.
  CHECK(!delta_direction(Bsdf{Dielectric{1.5f}}, normalize(Vec3(0.9f, 0.f, -0.2f)), true, wi));
}

// A refraction's BsdfSample::eta is the factor its Radiance weight carries as 1 / eta^2 (so
// Russian roulette can take it out, russian_roulette.h): for the same random numbers, the Radiance
// weight times eta^2 is the Importance weight; a reflection has eta 1 and equal weights. Smooth
// and rough glass, from both sides.
TEST_CASE("a_refraction_says_its_eta_and_radiance_weight_times_eta_squared_is_importance") {
  const Bsdf smooth = Dielectric{1.5f};
  const Bsdf rough = RoughDielectric{Microfacet{MicrofacetType::GGX, 0.3f, 0.3f}, 1.5f};
  int refractions = 0, reflections = 0;
  for (const Bsdf* b : {&smooth, &rough}) {
    for (int i = 0; i < 400; ++i) {
      const float cos_theta = (i % 2 == 0 ? 1.f : -1.f) * (0.05f + 0.9f * ((i * 37) % 100) / 100.f);
      const Vec3 wo = direction(cos_theta, 0.7f * static_cast<float>(i));
      const Point2 u{((i * 53) % 97 + 0.5f) / 97.f, ((i * 29) % 89 + 0.5f) / 89.f};
      BsdfSample radiance, importance;
      if (!sample(*b, wo, u, TransportMode::Radiance, radiance)) continue;
      REQUIRE(sample(*b, wo, u, TransportMode::Importance, importance));
      REQUIRE(radiance.eta == importance.eta);
      const bool refracted = radiance.wi.z * wo.z < 0.f;
      if (refracted) {
        ++refractions;
        CHECK_NEAR(radiance.eta, wo.z > 0.f ? 1.5f : 1.f / 1.5f, 1e-6f);
      } else {
        ++reflections;
        CHECK(radiance.eta == 1.f);
      }
      CHECK_NEAR(radiance.weight[0] * radiance.eta * radiance.eta, importance.weight[0],
                 1e-5f * std::max(1.f, importance.weight[0]));
    }
  }
  CHECK(refractions > 300);
  CHECK(reflections > 20);
}
