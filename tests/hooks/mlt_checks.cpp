#include "hooks/mlt_checks.h"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "core/frame.h"
#include "hooks/bootstrap_checks.h"
#include "pathspace/mutations/bidirectional.h"
#include "pathspace/mutations/caustic_perturbation.h"
#include "pathspace/mutations/lens_perturbation.h"

namespace dualight {

namespace {

// The negative controls' acceptance ratios (TransitionRatio::Ignored, Inverted).
double ratio_ignored(const Transition&) { return 1.0; }
double ratio_inverted(const Transition& t) { return t.forward / t.reverse; }

MltChainHooks hooks_of(TransitionRatio transition_ratio) {
  switch (transition_ratio) {
    case TransitionRatio::Ignored:
      return {ratio_ignored};
    case TransitionRatio::Inverted:
      return {ratio_inverted};
    case TransitionRatio::Used:
      break;
  }
  return {};  // render_mlt's own acceptance
}

}  // namespace

PathMltResult render_single_mutation(const Scene& scene, const PinholeCamera& camera, MltOptions opt,
                                     const std::string& mutation, TransitionRatio transition_ratio) {
  float* const weights[] = {&opt.bidirectional, &opt.lens_subpath, &opt.lens_perturbation,
                            &opt.caustic_perturbation, &opt.multi_chain_perturbation};
  const char* const names[] = {"bidirectional", "lens_subpath", "lens_perturbation", "caustic_perturbation",
                               "multi_chain_perturbation"};
  bool found = false;
  for (size_t i = 0; i < 5; ++i) {
    const bool chosen = mutation == names[i];
    *weights[i] = chosen ? 1.f : 0.f;
    found = found || chosen;
  }
  if (!found) throw std::invalid_argument("unknown mutation: " + mutation);
  RenderControl control;
  return render_mlt(scene, camera, opt, control, hooks_of(transition_ratio));
}

namespace {

// One block of a perturbation's map: the offset is applied at z[from] (z[k]: on the film) and
// the walk follows the specular vertices between to the non-specular z[to].
struct Block {
  int from = 0, to = 0;
  int step() const { return to < from ? -1 : 1; }
};

// The blocks EyePerturbation::propose makes (film, then one per chain of a multi-chain).
std::vector<Block> eye_blocks(const Path& x) {
  std::vector<Block> blocks;
  int from = static_cast<int>(x.size()) - 1;
  for (;;) {
    int to = from - 1;
    while (to > 0 && is_specular(x[to])) --to;
    blocks.push_back({from, to});
    if (to == 0 || !is_specular(x[to - 1])) return blocks;
    from = to;
  }
}

// The block CausticPerturbation::propose makes: from the light-side diffuse vertex to x[k - 1].
Block caustic_block(const Path& x) {
  const int k = static_cast<int>(x.size()) - 1;
  int j = k - 3;
  while (j > 0 && is_specular(x[j])) --j;
  return {j, k - 1};
}

// The factor of the reported T(x -> y) that belongs to a block, as the mutations compute it:
// the area density of z[to] per unit film area (whole film) or per steradian at z[from], with
// the followed specular vertices' forced densities (Radiance form towards the camera, Importance
// form towards the light: full_path.h).
double reported_factor(const PinholeCamera& camera, const Scene& scene, const Path& z, const Block& b) {
  const int k = static_cast<int>(z.size()) - 1;
  double p = 1.0;
  if (b.step() < 0) {
    for (int i = b.to; i < b.from; ++i) {
      p *= (i + 1 == k || is_specular(z[i + 1])) ? pdf_from_eye(camera, z, static_cast<size_t>(i), true)
                                                 : solid_angle_to_area(1.f, z[i + 1], z[i]);
    }
  } else {
    p = solid_angle_to_area(1.f, z[b.from], z[b.from + 1]);
    for (int i = b.from + 2; i <= b.to; ++i) p *= pdf_from_light(scene, z, static_cast<size_t>(i), true);
  }
  return p;
}

// G with the segment folded at a flat mirror: the cosines at the two ends over the unfolded
// distance squared (no cosine at the pinhole).
double unfolded_geometry(const Vertex& a, const Vertex& s, const Vertex& b) {
  const double d = std::sqrt(static_cast<double>(dot(s.p - a.p, s.p - a.p))) +
                   std::sqrt(static_cast<double>(dot(b.p - s.p, b.p - s.p)));
  double g = 1.0 / (d * d);
  if (a.on_surface()) g *= std::abs(dot(a.n, direction(a, s)));
  return g * std::abs(dot(b.n, direction(b, s)));
}

// Area of the image on z[b.to]'s surface of a small square of film positions or directions
// (corners in order around it); 0 when a corner's walk leaves y's facets. `side` is the
// square's side (pixels or radians).
double image_area(const MutationContext& ctx, const Path& y, const Block& b, double side) {
  const int k = static_cast<int>(y.size()) - 1;
  Point2 centre{};
  Frame frame{};
  if (b.from == k) {
    if (!ctx.camera.raster_position(y[k - 1].p, centre)) return 0.0;
  } else {
    frame = Frame::from_normal(direction(y[b.from], y[b.from + b.step()]));
  }
  const float h = static_cast<float>(side / 2);
  const float corners[4][2] = {{-h, -h}, {h, -h}, {h, h}, {-h, h}};
  Vec3 p[4];
  for (int c = 0; c < 4; ++c) {
    const Vec3 d = b.from == k
                       ? ctx.camera.generate_ray(centre.u + corners[c][0], centre.v + corners[c][1]).d
                       : normalize(frame.n + frame.s * corners[c][0] + frame.t * corners[c][1]);
    Path z = y;
    if (!follow_specular_chain(ctx, y, z, b.from, b.to, d)) return 0.0;
    for (int i = b.from + b.step();; i += b.step()) {
      if (z[i].prim != y[i].prim) return 0.0;
      if (i == b.to) break;
    }
    p[c] = z[b.to].p;
  }
  // Diagonals in double: the corners are float and close together.
  const double d1[3] = {double(p[2].x) - p[0].x, double(p[2].y) - p[0].y, double(p[2].z) - p[0].z};
  const double d2[3] = {double(p[3].x) - p[1].x, double(p[3].y) - p[1].y, double(p[3].z) - p[1].z};
  const double cx = d1[1] * d2[2] - d1[2] * d2[1], cy = d1[2] * d2[0] - d1[0] * d2[2],
               cz = d1[0] * d2[1] - d1[1] * d2[0];
  return 0.5 * std::sqrt(cx * cx + cy * cy + cz * cz);
}

}  // namespace

std::vector<DensityCheck> check_perturbation_densities(const Scene& scene, const PinholeCamera& camera,
                                                       const MltOptions& opt, const std::string& mutation,
                                                       size_t samples, size_t proposals, double film_step,
                                                       double angle_step) {
  // The offsets' ranges as render_mlt's mutation set makes them.
  const float r_max = opt.lens_radius_max > 0.f ? opt.lens_radius_max : 0.1f * static_cast<float>(camera.width());
  const PerturbationRange film{std::min(opt.lens_radius_min, r_max), r_max};
  const PerturbationRange angle{opt.angle_min, opt.angle_max};
  std::unique_ptr<Mutation> m;
  if (mutation == "lens_perturbation" || mutation == "multi_chain_perturbation") {
    m = std::make_unique<EyePerturbation>(mutation == "multi_chain_perturbation", film, angle);
  } else if (mutation == "caustic_perturbation") {
    m = std::make_unique<CausticPerturbation>(angle);
  } else {
    throw std::invalid_argument("no density check for mutation: " + mutation);
  }
  const bool eye = mutation != "caustic_perturbation";
  const double pixels = static_cast<double>(camera.width()) * camera.height();
  TraceCounters counters;
  const MutationContext ctx{scene, camera, opt.direct_spp > 0 ? 3 : 1, opt.max_depth, counters};
  std::vector<DensityCheck> out;
  Pcg32 rng(opt.seed, 0x5eedull);
  for (const Path& x : bootstrap_paths(scene, camera, opt, samples)) {
    if (!m->suitable(x)) continue;
    for (size_t n = 0; n < proposals; ++n) {
      Path y;
      Transition t;
      if (!m->propose(ctx, x, rng, y, t) || !(t.forward > 0.0)) continue;
      const std::vector<Block> blocks = eye ? eye_blocks(y) : std::vector<Block>{caustic_block(y)};
      // Only chains of at most one reflection have a geometric density to compare with.
      bool comparable = true;
      for (const Block& b : blocks) {
        const int specular = std::abs(b.to - b.from) - 1;
        comparable = comparable && (specular == 0 || (specular == 1 && !uses_refraction(y, b.from + b.step())));
      }
      if (!comparable) continue;
      std::vector<DensityCheck> checks;
      double product = 1.0;
      for (size_t i = 0; i < blocks.size() && comparable; ++i) {
        const Block& b = blocks[i];
        const double area = image_area(ctx, y, b, b.from == static_cast<int>(y.size()) - 1 ? film_step : angle_step);
        if (!(area > 0.0)) {
          comparable = false;
          break;
        }
        DensityCheck c;
        c.block = static_cast<int>(i);
        c.specular = std::abs(b.to - b.from) - 1;
        const double raw = reported_factor(camera, scene, y, b);
        product *= raw;
        c.reported = raw;
        if (c.specular == 1) {
          const Vertex& s = y[b.from + b.step()];
          c.reported *= unfolded_geometry(y[b.from], s, y[b.to]) /
                        (geometry_term(y[b.from], s) * geometry_term(s, y[b.to]));
        }
        if (b.from == static_cast<int>(y.size()) - 1) {
          c.reported *= pixels;  // per pixel^2 instead of per whole film
          c.measured = film_step * film_step / area;
        } else {
          const double e = angle_step / 2;  // solid angle of the square at distance 1
          c.measured = 4.0 * std::atan(e * e / std::sqrt(1.0 + 2.0 * e * e)) / area;
        }
        const Vertex& end = y[b.to];
        c.cos_end = std::abs(dot(end.n, direction(end, y[b.to - b.step()])));
        checks.push_back(c);
      }
      // The blocks must be all of T(x -> y): otherwise the check would miss a factor.
      if (comparable && std::abs(product / t.forward - 1.0) > 1e-4) {
        throw std::logic_error("density check: the blocks' product differs from the reported T(x -> y)");
      }
      if (comparable) out.insert(out.end(), checks.begin(), checks.end());
    }
  }
  return out;
}

namespace {

constexpr float kGrazing = 1e-3f;  // |cos| below which a point is left out of the region

// Whether z, a candidate for the regenerated x'_v of x, lies in the check's region: for v = 0
// an emitter point in front of which x_1 lies; for v = 1 a non-specular point in front of the
// emitter point x_0, on the side of x_2 that x_2's walk samples (that of x_3), seen from both
// and not grazing any of them (both ways of regenerating it then have a non-zero density).
bool in_region(const Scene& scene, const Path& x, int v, const Vec3& p, const Vec3& n, uint32_t prim) {
  const Material& m = scene.material(prim);
  if (v == 0) {
    return scene.emitter_at(prim) != nullptr && dot(n, x[1].p - p) > 0.f;
  }
  if (is_delta(m.bsdf)) return false;
  const Vec3 w0 = normalize(p - x[0].p), w2 = normalize(p - x[2].p);
  if (dot(x[0].n, w0) <= kGrazing || std::abs(dot(n, w0)) <= kGrazing || std::abs(dot(n, w2)) <= kGrazing) {
    return false;
  }
  const float side = dot(x[2].n, x[3].p - x[2].p);
  if (dot(x[2].n, w2) * (side > 0.f ? 1.f : -1.f) <= kGrazing) return false;
  return scene.visible(x[0].p, x[0].n, p, prim) && scene.visible(x[2].p, x[2].n, p, prim);
}

}  // namespace

BidirectionalCheck check_bidirectional_density(const Scene& scene, const PinholeCamera& camera,
                                               const MltOptions& opt, int vertex, size_t proposals,
                                               size_t region_points) {
  if (vertex != 0 && vertex != 1) throw std::invalid_argument("vertex must be 0 or 1");
  BidirectionalCheck out;
  // For v = 1, uniform points over every triangle estimate the region's area.
  std::vector<double> areas(scene.triangle_count());
  double total_area = 0.0;
  for (uint32_t prim = 0; prim < scene.triangle_count(); ++prim) total_area += areas[prim] = scene.area(prim);
  const DiscreteDistribution by_area(areas);
  const auto region_fraction = [&](const Path& x, size_t count, uint64_t stream) {
    Pcg32 rng(opt.seed, stream);
    size_t inside = 0;
    for (size_t i = 0; i < count; ++i) {
      float u = rng.next_float();
      const auto prim = static_cast<uint32_t>(by_area.sample(u));
      const Point2 b = square_to_uniform_triangle(next_2d(rng));
      const Vec3 p =
          scene.vertex(prim, 0) * (1.f - b.u - b.v) + scene.vertex(prim, 1) * b.u + scene.vertex(prim, 2) * b.v;
      if (in_region(scene, x, vertex, p, scene.normal(prim), prim)) ++inside;
    }
    return static_cast<double>(inside) / static_cast<double>(count);
  };
  // x: for v = 0, x_1 sees the whole emitter; for v = 1, x_1 and x_2 are non-specular surface
  // points (x_2 not the camera) and the region is not empty.
  const Path* x = nullptr;
  const std::vector<Path> paths = bootstrap_paths(scene, camera, opt, 2000);
  double emitter_area = 0.0;
  for (uint32_t prim = 0; prim < scene.triangle_count(); ++prim) {
    if (scene.emitter_at(prim) != nullptr) emitter_area += scene.area(prim);
  }
  // On a grid over every emitter triangle: then both ways reach all of it.
  const auto sees_every_emitter_point = [&](const Path& p) {
    constexpr int kGrid = 8;
    for (uint32_t prim = 0; prim < scene.triangle_count(); ++prim) {
      if (scene.emitter_at(prim) == nullptr) continue;
      for (int a = 0; a < kGrid; ++a) {
        for (int b = 0; a + b < kGrid; ++b) {
          const float u = (a + 0.5f) / (kGrid + 1), w = (b + 0.5f) / (kGrid + 1);
          const Vec3 q = scene.vertex(prim, 0) * (1.f - u - w) + scene.vertex(prim, 1) * u + scene.vertex(prim, 2) * w;
          const float side = dot(p[1].n, p[2].p - p[1].p);
          if (!in_region(scene, p, 0, q, scene.normal(prim), prim) || dot(p[1].n, q - p[1].p) * side <= 0.f ||
              !scene.visible(p[1].p, p[1].n, q, prim)) {
            return false;
          }
        }
      }
    }
    return true;
  };
  for (const Path& p : paths) {
    if (p.size() < 4 || is_specular(p[1]) || is_specular(p[2])) continue;
    if (vertex == 0 && !sees_every_emitter_point(p)) continue;
    if (vertex == 1 && region_fraction(p, 1000, 0x5ee5ull) < 0.05) continue;
    x = &p;
    break;
  }
  if (x == nullptr) throw std::runtime_error("no suitable bootstrap path for the bidirectional check");
  if (vertex == 0) {
    out.area = emitter_area;
  } else {
    const double f = region_fraction(*x, region_points, 0xa5eaull);
    out.area = f * total_area;
    out.area_se = std::sqrt(f * (1.0 - f) / static_cast<double>(region_points)) * total_area;
  }
  TraceCounters counters;
  const MutationContext ctx{scene, camera, opt.direct_spp > 0 ? 3 : 1, opt.max_depth, counters};
  const BidirectionalMutation mutation;
  Pcg32 rng(opt.seed, 0xb1d1ull);
  out.proposals = proposals;
  for (size_t n = 0; n < proposals; ++n) {
    Path y;
    Transition t;
    if (!mutation.propose(ctx, *x, rng, y, t) || y.size() != x->size() || !(t.forward > 0.0)) continue;
    // The move that deletes and regenerates x_v alone keeps every other vertex.
    bool kept = true;
    for (size_t i = 0; i < y.size() && kept; ++i) {
      if (static_cast<int>(i) == vertex) continue;
      kept = y[i].p.x == (*x)[i].p.x && y[i].p.y == (*x)[i].p.y && y[i].p.z == (*x)[i].p.z;
    }
    const Vertex& z = y[vertex];
    if (!kept || z.material == nullptr || !in_region(scene, *x, vertex, z.p, z.n, z.prim)) continue;
    out.inv_t.push_back(1.0 / t.forward);
    out.move.push_back(t.forward / regeneration_density(ctx, y, vertex - 1, vertex + 1));
    out.pdf_light.push_back(pdf_from_light(scene, y, static_cast<size_t>(vertex)));
    out.pdf_eye.push_back(pdf_from_eye(camera, y, static_cast<size_t>(vertex)));
    out.cos.push_back(std::abs(dot(z.n, direction(z, y[vertex + 1]))));
  }
  return out;
}

}  // namespace dualight
