#include "pathspace/path_tracer_lanes.h"

#include <stdexcept>
#include <string>

namespace dualight {

namespace {

// How the lanes compute material m's BSDF (kLaneLambertian, ...), and, for those they compute
// lane-wide, its parameters in `albedo` (may be null): the albedo, the mirror's reflectance, or
// the dielectric's eta in albedo[0]. Textured materials go lane by lane (their BSDF at each uv).
int32_t lane_bsdf(const Material& m, float* albedo) {
  const auto copy = [albedo](const Vec3& v) {
    if (albedo != nullptr) albedo[0] = v.x, albedo[1] = v.y, albedo[2] = v.z;
  };
  copy(Vec3(0.f));
  if (m.textured()) return kLaneOther;
  if (const auto* l = std::get_if<Lambertian>(&m.bsdf)) {
    copy(l->albedo);
    return kLaneLambertian;
  }
  if (const auto* r = std::get_if<Mirror>(&m.bsdf)) {
    copy(r->reflectance);
    return kLaneMirror;
  }
  if (const auto* d = std::get_if<Dielectric>(&m.bsdf)) {
    copy(Vec3(d->eta, 0.f, 0.f));
    return kLaneDielectric;
  }
  return kLaneOther;
}

void copy(const Vec3& v, float* out) { out[0] = v.x, out[1] = v.y, out[2] = v.z; }

// Untextured area, point, spot, directional and constant environment emitters lane-wide; the
// others (environment maps, textured area emitters) lane by lane through the scalar code.
LaneEmitter lane_emitter(const Scene& scene, const Emitter& e) {
  LaneEmitter le{};
  le.kind = kLaneScalarEmitter;
  const float pmf = scene.emitter_pmf(e);
  if (const auto* a = std::get_if<AreaEmitter>(&e); a != nullptr && a->texture == nullptr) {
    copy(a->p0, le.p[0]), copy(a->p1, le.p[1]), copy(a->p2, le.p[2]);
    copy(a->n, le.n);
    copy(a->Le, le.Le);
    le.pdf_a = pdf_Le_position(*a, pmf);
    le.prim = a->prim;
    le.kind = kLaneAreaEmitter;
  } else if (const auto* pt = std::get_if<PointEmitter>(&e)) {
    copy(pt->p, le.p[0]), copy(pt->I, le.Le);
    le.pdf_a = pmf;
    le.kind = kLanePointEmitter;
  } else if (const auto* spot = std::get_if<SpotEmitter>(&e)) {
    copy(spot->p, le.p[0]), copy(spot->I, le.Le);
    le.pdf_a = pmf;
    le.kind = kLaneSpotEmitter;
  } else if (const auto* d = std::get_if<DirectionalEmitter>(&e)) {
    copy(-d->frame.n, le.n), copy(d->E, le.Le), copy(d->scene.center, le.center);
    le.radius = d->scene.radius;
    le.pdf_a = pmf;
    le.kind = kLaneDirectionalEmitter;
  } else if (const auto* c = std::get_if<ConstantEmitter>(&e)) {
    copy(c->L, le.Le), copy(c->scene.center, le.center);
    le.radius = c->scene.radius;
    le.pdf_a = pdf_Li(*c, pmf, Vec3(0.f), 0.f, 1.f);
    le.kind = kLaneConstantEmitter;
  }
  return le;
}

bool cpu_runs(LaneIsa isa) {
  switch (isa) {
    case LaneIsa::Avx512:
      return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    case LaneIsa::Avx2:
      return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2");
    default:
      return true;
  }
}

PathLanesKernels kernels_for(LaneIsa isa) {
  switch (isa) {
    case LaneIsa::Avx512:
      return path_lanes_kernels_avx512();
    case LaneIsa::Avx2:
      return path_lanes_kernels_avx2();
    default:
      return path_lanes_kernels_sse2();
  }
}

}  // namespace

PathLanesChoice choose_path_lanes(const Scene& scene, const PathTracerOptions& options) {
  if (options.lanes == LaneIsa::Off) return {std::nullopt, "lanes='off'"};
  if (options.guiding) return {std::nullopt, "guiding"};
  if (options.lanes != LaneIsa::Auto && !cpu_runs(options.lanes)) {
    throw std::invalid_argument("this CPU cannot run the lanes' instruction set asked for");
  }
  if (scene.emitter_count() == 0) return {std::nullopt, "the scene has no emitters"};
  if (scene.emitter_count() > LaneTriangle::kMaxEmitters) return {std::nullopt, "more than 2^28 - 1 emitters"};
  if (scene.triangle_count() > kMaxLaneTriangles) return {std::nullopt, "more than 2^27 - 1 triangles"};
  if (options.lanes != LaneIsa::Auto) return {kernels_for(options.lanes), ""};
  // Materials the lanes do not compute lane-wide (kLaneOther) go lane by lane through the scalar
  // code, on any share of the scene: the packets still pay. One thread, 64x64, 128 spp, M
  // samples/s, one path at a time against AVX-512 lanes (AVX2): glossy Cornell box (30 % of its
  // area lane by lane) 0.64 against 0.81 (0.77), coated (30 %) 0.83 against 1.12 (1.02), textured
  // (44 %) 1.01 against 1.33 (1.22); the box with every wall rough plastic 0.58 against 0.71
  // (0.67), plastic 0.78 against 1.00 (0.93), rough conductor 0.50 against 0.55 (0.52).
  // AVX-512, else AVX2 (with Embree's 8-wide packets there). The SSE2 build, whose rays go to
  // Embree one at a time on CPUs without AVX, ran slower than one path at a time on the Cornell
  // box: it is there for checks, not chosen.
  for (const LaneIsa isa : {LaneIsa::Avx512, LaneIsa::Avx2}) {
    if (cpu_runs(isa)) return {kernels_for(isa), ""};
  }
  return {std::nullopt, "this CPU lacks AVX2 (the SSE2 build is slower than one path at a time)"};
}

PathLanesScene path_lanes_scene(const Scene& scene, const PinholeCamera& camera, const PathTracerOptions& options) {
  PathLanesScene ps;
  ps.scene = &scene;
  ps.camera = &camera;
  ps.options = &options;
  ps.triangles.resize(scene.triangle_count());
  for (uint32_t prim = 0; prim < scene.triangle_count(); ++prim) {
    LaneTriangle& t = ps.triangles[prim];
    for (int c = 0; c < 3; ++c) copy(scene.vertex(prim, c), t.p[c]);
    copy(scene.normal(prim), t.n);
    const int32_t bsdf = lane_bsdf(scene.material(prim), t.albedo);
    const bool smooth = scene.smooth_shaded(prim);
    ps.smooth = ps.smooth || smooth;
    const Emitter* e = scene.emitter_at(prim);
    const auto emitter_plus_one = e == nullptr ? 0 : static_cast<int32_t>(e - scene.emitters().data()) + 1;
    t.packed = emitter_plus_one << 3 | (smooth ? 4 : 0) | bsdf;
  }
  for (const Emitter& e : scene.emitters()) ps.emitters.push_back(lane_emitter(scene, e));
  ps.environment = scene.environment();
  if (ps.environment != nullptr) {
    const auto index = static_cast<int32_t>(ps.environment - scene.emitters().data());
    if (ps.emitters[static_cast<size_t>(index)].kind == kLaneConstantEmitter) ps.constant_environment = index;
  }
  if (scene.emitter_count() <= PathLanesScene::kCountedEmitters) ps.emitter_ends = scene.emitter_choice_ends();
  return ps;
}

}  // namespace dualight
