// The path tracer's bounces for a chunk of lanes (path_tracer_lanes.h; kLanes of core/lanes.h):
// extend_path of path_tracer.cpp (unidirectional path tracing with next-event estimation and MIS
// [Veach 1997, ch. 9]) lane-wide for area, point, spot, directional and constant environment
// emitters and Lambertian, mirror and smooth dielectric surfaces [pbrt-v4 sec. 9.5], and lane by
// lane through the scalar code for every other BSDF and emitter.
// Each step names the scalar function it mirrors; the order of operations is that function's, so
// the bits are too. Deliberately without include guard or includes: see core/lanes.h.

namespace dualight::DUALIGHT_LANES_NS {

// The rays of the lanes' current segment.
struct LaneRays {
  V3 o, d;
  vf tmin, tmax;
};

// A lane's path between two vertices (CameraPathState, unguided).
struct LanePaths {
  vi active;
  V3 beta, L;
  vf prev_pdf_w;
  vi prev_delta;
  vf roulette_scale;
};

// The vertex each lane's ray found, gathered from the scene's tables (Scene::intersect).
struct LaneVertex {
  V3 p, n, ns, albedo;  // n: geometric normal, ns: shading normal (SurfaceHit's)
  vf t, b1, b2;  // b1, b2: the hit's barycentrics of corners 1 and 2
  vi prim, emitter;  // emitter -1: none
  vi bsdf;           // kLaneLambertian, ...
};

// two_strategy_weight (strategies.h): MIS's power heuristic, or one strategy alone.
inline vf two_strategy_weight(Strategies chosen, Strategies own, vf pdf_own, vf pdf_other) {
  if (chosen == Strategies::Mis) {
    const vf a2 = pdf_own * pdf_own, b2 = pdf_other * pdf_other;
    return select(a2 > 0.f, a2 / (a2 + b2), splat(0.f));
  }
  if (chosen == own) return splat(1.f);
  return select(pdf_other > 0.f, splat(0.f), splat(1.f));
}

// A float field (at `offset` bytes) of the table rows `index` names, per lane; row 0 where a
// lane is not `active`.
template <class Table>
vf gather_field(const Table* table, vi index, vi active, size_t offset) {
  static_assert(sizeof(Table) % 4 == 0 && std::is_standard_layout_v<Table>);
  return gather(reinterpret_cast<const float*>(table) + offset / 4,
                select(active, index, splat_i(0)) * static_cast<int32_t>(sizeof(Table) / 4));
}
template <class Table>
vi gather_int(const Table* table, vi index, vi active, size_t offset) {
  return float_to_bits(gather_field(table, index, active, offset));
}
template <class Table>
V3 gather3(const Table* table, vi index, vi active, size_t offset) {
  return {gather_field(table, index, active, offset), gather_field(table, index, active, offset + 4),
          gather_field(table, index, active, offset + 8)};
}
// b0 p0 + b1 p1 + b2 p2 with b0 = 1 - b1 - b2, in Scene::intersect's (and sample_Le_position's) order.
template <class Table>
V3 barycentric_point(const Table* table, vi index, vi active, vf b1, vf b2) {
  constexpr size_t p = offsetof(Table, p);
  return gather3(table, index, active, p) * ((1.f - b1) - b2) + gather3(table, index, active, p + 12) * b1 +
         gather3(table, index, active, p + 24) * b2;
}

// The lanes' random numbers: each lane's own sampler's, its generator stepped with the others'
// (core/lanes.h), for the independent sampler...
template <class Sampler>
struct LaneNumbers;
template <>
struct LaneNumbers<IndependentSampler> {
  LanePcg32 rng{vu64{}, vu64{} + 1u};  // lanes not started never advance
  vf next_1d(vi active) { return rng.next_float(active); }
  void next_2d(vi active, vf& u, vf& v) {
    u = rng.next_float(active);
    v = rng.next_float(active);
  }
};
// ... and for the Sobol sampler.
template <>
struct LaneNumbers<SobolSampler> {
  LaneSobol sobol;
  void start(int i, const SobolSampler& sampler) {
    sobol.pixel_seed[i] = sampler.pixel_seed();
    sobol.reversed_index[i] = sampler.reversed_index();
    sobol.dimension[i] = sampler.dimension();
  }
  vf next_1d(vi active) { return sobol.next_1d(active); }
  void next_2d(vi active, vf& u, vf& v) { sobol.next_2d(active, u, v); }
};

// Frame::from_normal [Duff et al. 2017].
struct LaneFrame {
  V3 s, t, n;
  V3 to_local(const V3& v) const { return {dot(v, s), dot(v, t), dot(v, n)}; }
  V3 to_world(const V3& v) const { return s * v.x + t * v.y + n * v.z; }
};
inline LaneFrame frame_from_normal(const V3& n) {
  const vf sign = copysign_one(n.z);
  const vf a = -1.f / (sign + n.z);
  const vf b = n.x * n.y * a;
  return {{1.f + sign * n.x * n.x * a, sign * b, -sign * n.x}, {b, sign + n.y * n.y * a, -n.y}, n};
}

// square_to_cosine_hemisphere (core/sampling.h): the concentric disk, Cephes' sine and cosine.
inline V3 square_to_cosine_hemisphere(vf u, vf v) {
  const vf a = 2.f * u - 1.f, b = 2.f * v - 1.f;
  const vi centre = (a == 0.f) & (b == 0.f);
  const vi x_sector = a * a > b * b;
  const vf r = select(x_sector, a, b);
  const vf x = (kPi / 4.f) * (select(x_sector, b, a) / r);
  const vf z = x * x;
  const vf s = x + x * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
  const vf c =
      1.f - 0.5f * z + z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
  const vf du = select(centre, splat(0.f), select(x_sector, r * c, r * s));
  const vf dv = select(centre, splat(0.f), select(x_sector, r * s, r * c));
  return {du, dv, sqrt(max(splat(0.f), 1.f - du * du - dv * dv))};
}
inline vf cosine_hemisphere_pdf(vf cos_theta) { return select(cos_theta > 0.f, cos_theta * kInvPi, splat(0.f)); }

// offset_ray_origin (core/ray.h), one component.
inline vf offset_component(vf v, vf nv, float scene_scale) {
  const float origin = (1.f / 32.f) * scene_scale, float_scale = (1.f / 65536.f) * scene_scale;
  const vi of = __builtin_convertvector(256.f * nv, vi);
  const vf shifted = bits_to_float(float_to_bits(v) + select(v < 0.f, -of, of));
  return select(abs(v) < origin, v + float_scale * nv, shifted);
}
inline V3 offset_ray_origin(const V3& p, const V3& n, float scene_scale) {
  return {offset_component(p.x, n.x, scene_scale), offset_component(p.y, n.y, scene_scale),
          offset_component(p.z, n.z, scene_scale)};
}

// The shading normals of a vertex's lanes: on the `smooth` lanes the scene's interpolated
// vertex normals (Scene::shading_normal, lane by lane), elsewhere v.n.
inline V3 shading_normals(const PathLanesScene& ps, const LaneVertex& v, vi smooth) {
  if (!any(smooth)) return v.n;
  alignas(64) float ns[3][kLanes];
  store(ns[0], v.n.x), store(ns[1], v.n.y), store(ns[2], v.n.z);
  for (int i = 0; i < kLanes; ++i) {
    if (smooth[i] == 0) continue;
    const Vec3 n = ps.scene->shading_normal(static_cast<uint32_t>(v.prim[i]), v.b1[i], v.b2[i]);
    ns[0][i] = n.x, ns[1][i] = n.y, ns[2][i] = n.z;
  }
  return {load(ns[0]), load(ns[1]), load(ns[2])};
}

inline Vec3 lane(const V3& v, int i) { return {v.x[i], v.y[i], v.z[i]}; }

// Adds estimate(i), the scalar code's, to L of each lane i in `lanes` (L += C, as extend_path).
template <class Estimate>
void add_scalar_estimates(vi lanes, LanePaths& paths, const Estimate& estimate) {
  alignas(64) float c[3][kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (lanes[i] == 0) continue;
    const Color ci = estimate(i);
    c[0][i] = ci.x, c[1][i] = ci.y, c[2][i] = ci.z;
  }
  paths.L = select(lanes, paths.L + V3{load(c[0]), load(c[1]), load(c[2])}, paths.L);
}

// Lanes' rays from o along d, between tmin and tmax, in Embree's packet.
inline void store_rays(RayHit16& packet, const V3& o, const V3& d, vf tmin, vf tmax) {
  store(packet.ox, o.x), store(packet.oy, o.y), store(packet.oz, o.z);
  store(packet.dx, d.x), store(packet.dy, d.y), store(packet.dz, d.z);
  store(packet.tmin, tmin), store(packet.tmax, tmax);
}

// environment_seen (next_event.h) of a constant environment for the lanes in `escaped`: its
// radiance, weighted against next-event estimation's density pdf_Li, times the throughput.
[[gnu::noinline]]  // off the area emitters' path (inlined, it cost the caustic box 2 %)
inline void add_constant_environment_seen(const PathLanesScene& ps, LanePaths& paths, vi escaped) {
  const LaneEmitter& env = ps.emitters[static_cast<size_t>(ps.constant_environment)];
  const Vec3 Le{env.Le[0], env.Le[1], env.Le[2]};
  const V3 beta_Le = paths.beta * splat(Le);
  V3 C = beta_Le;
  if (!is_black(Le)) {
    const vf w = two_strategy_weight(ps.options->strategies, Strategies::Bsdf, paths.prev_pdf_w, splat(env.pdf_a));
    C = select(paths.prev_delta, beta_Le, paths.beta * (splat(Le) * w));
  }
  paths.L = select(escaped, paths.L + C, paths.L);
}

// The lanes whose ray's hit is known already (their camera rays', CameraRays), and that hit.
// regenerate sets it before every bounce: the lanes it started, none else.
struct KnownHits {
  vi lanes = splat_i(0);
  alignas(64) float t[kLanes] = {}, u[kLanes] = {}, v[kLanes] = {};
  alignas(64) int32_t prim[kLanes] = {};
};

// Scene::intersect for the active lanes (but those whose hit is `known`): those that find
// nothing end, seeing the environment where the scene has one (environment_seen: lane-wide for
// a constant one, else by the scalar code).
inline LaneVertex intersect(const PathLanesScene& ps, const LaneRays& r, const KnownHits& known, LanePaths& paths,
                            TraceCounters& counters) {
  RayHit16 packet;
  if constexpr (kLanes < RayHit16::kLanes) packet = RayHit16{};
  alignas(64) int32_t active[RayHit16::kLanes] = {};
  store_rays(packet, r.o, r.d, r.tmin, r.tmax);
  const vi trace = paths.active & ~known.lanes;
  store(active, trace);
  if (any(trace)) {
    ps.scene->intersect(active, packet);
  } else {  // as the query leaves the lanes it does not trace: no hit
    std::fill(std::begin(packet.prim), std::end(packet.prim), RayHit::kNoHit);
  }
  counters.rays += count(paths.active);
  LaneVertex v;
  v.prim = select(known.lanes, load(known.prim), load(reinterpret_cast<const int32_t*>(packet.prim)));
  const vi escaped = paths.active & (v.prim == -1);
  if (ps.constant_environment >= 0 && any(escaped)) {
    add_constant_environment_seen(ps, paths, escaped);
  } else if (ps.environment != nullptr && any(escaped)) {
    add_scalar_estimates(escaped, paths, [&](int i) {
      return environment_seen(*ps.scene, *ps.environment, lane(r.d, i), lane(paths.beta, i), paths.prev_pdf_w[i],
                              paths.prev_delta[i] != 0, ps.options->strategies);
    });
  }
  paths.active &= ~escaped;
  const LaneTriangle* tri = ps.triangles.data();
  const vi packed = gather_int(tri, v.prim, paths.active, offsetof(LaneTriangle, packed));
  v.emitter = select(paths.active, (packed >> 3) - 1, splat_i(-1));
  v.t = select(known.lanes, load(known.t), load(packet.tmax));
  v.b1 = select(known.lanes, load(known.u), load(packet.u));
  v.b2 = select(known.lanes, load(known.v), load(packet.v));
  v.p = barycentric_point(tri, v.prim, paths.active, v.b1, v.b2);
  v.n = gather3(tri, v.prim, paths.active, offsetof(LaneTriangle, n));
  v.ns = v.n;
  if (ps.smooth) {
    const vi smooth = -((packed >> 2) & 1);
    v.ns = shading_normals(ps, v, paths.active & smooth);
  }
  v.albedo = gather3(tri, v.prim, paths.active, offsetof(LaneTriangle, albedo));
  v.bsdf = packed & 3;
  return v;
}

// The BSDFs of the lanes of kind kLaneOther, which the scalar code evaluates lane by lane: the
// material's, or a textured material's at the hit's surface coordinates (extend_path's `bsdf`),
// kept in `textured` (the lanes' own storage, which outlives the bounce: nothing to clear per bounce).
using TexturedBsdfs = std::optional<Bsdf>[kLanes];
struct ScalarBsdfs {
  TexturedBsdfs& textured;
  const Bsdf* of[kLanes];  // set on the `other` lanes only
  vi other{}, delta{};     // the lanes of kind kLaneOther; those whose every lobe is a Dirac delta
  explicit ScalarBsdfs(TexturedBsdfs& storage) : textured(storage) {}
};
inline void find_scalar_bsdfs(const PathLanesScene& ps, const LaneVertex& v, vi active, ScalarBsdfs& b) {
  b.other = active & (v.bsdf == kLaneOther);
  if (!any(b.other)) return;
  alignas(64) int32_t delta[kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (b.other[i] == 0) continue;
    const auto prim = static_cast<uint32_t>(v.prim[i]);
    const Material& m = ps.scene->material(prim);
    b.of[i] = m.textured() ? &b.textured[i].emplace(m.bsdf_at(ps.scene->surface_uv(prim, v.b1[i], v.b2[i]))) : &m.bsdf;
    delta[i] = is_delta(*b.of[i]) ? -1 : 0;
  }
  b.delta = load(delta);
}

// Lane i's vertex as the scalar tracer's hit.
inline SurfaceHit scalar_hit(const PathLanesScene& ps, const LaneVertex& v, int i) {
  return ps.scene->surface_hit(static_cast<uint32_t>(v.prim[i]), v.b1[i], v.b2[i], v.t[i]);
}

// emission_seen: the emitters the lanes hit, weighted against next-event estimation; textured
// ones by the scalar code.
inline void add_emission(const PathLanesScene& ps, const LaneVertex& v, const V3& wo, LanePaths& paths) {
  const vi any_hit = paths.active & (v.emitter >= 0);
  if (!any(any_hit)) return;
  const LaneEmitter* em = ps.emitters.data();
  const vi kind = gather_int(em, v.emitter, any_hit, offsetof(LaneEmitter, kind));
  const vi scalar = any_hit & (kind == kLaneScalarEmitter);  // a textured area emitter
  if (any(scalar)) {
    add_scalar_estimates(scalar, paths, [&](int i) {
      return emission_seen(*ps.scene, scalar_hit(ps, v, i), lane(wo, i), lane(paths.beta, i), paths.prev_pdf_w[i],
                           paths.prev_delta[i] != 0, ps.options->strategies);
    });
  }
  const vi hit = any_hit & (kind == kLaneAreaEmitter);
  if (!any(hit)) return;
  const V3 e_n = gather3(em, v.emitter, hit, offsetof(LaneEmitter, n));
  const V3 Le = select(dot(e_n, wo) > 0.f, gather3(em, v.emitter, hit, offsetof(LaneEmitter, Le)), splat(Vec3(0.f)));
  const vf cos_light = abs(dot(v.n, wo));
  const vf pdf_light_w = gather_field(em, v.emitter, hit, offsetof(LaneEmitter, pdf_a)) * v.t * v.t / cos_light;
  const vf w = two_strategy_weight(ps.options->strategies, Strategies::Bsdf, paths.prev_pdf_w, pdf_light_w);
  const V3 beta_Le = paths.beta * Le;
  const V3 C = select(is_black(Le), splat(Vec3(0.f)), select(paths.prev_delta, beta_Le, beta_Le * w));
  paths.L = select(hit, paths.L + C, paths.L);
}

// The start of the shadow rays from v to y of the lanes in `lanes`: false where there is none to
// trace (no lane, or connections unoccluded: each counted skipped, and visible); else each
// counted, and o0 is its origin (Scene::shadow_origin).
inline bool shadow_origins(const PathLanesScene& ps, const LaneVertex& v, const V3& y, vi lanes,
                           TraceCounters& counters, V3& o0) {
  if (counters.unoccluded) {
    counters.skipped_shadow_rays += count(lanes);
    return false;
  }
  if (!any(lanes)) return false;
  counters.rays += count(lanes);
  o0 = offset_ray_origin(v.p, select(dot(v.n, y - v.p) > 0.f, v.n, -v.n), ps.scene->offset_scale());
  return true;
}

// Scene::visible for the lanes in `shadow`, or no ray where connections are unoccluded
// (shadow_ray_visible): each segment up to its short stop (short_stop, scene.cpp, computed
// lane-wide), or to the target where it has none, through the filter (Scene::occluded).
inline vi visible(const PathLanesScene& ps, const LaneVertex& v, const V3& y, vi target, vi shadow,
                  TraceCounters& counters) {
  V3 o0;
  if (!shadow_origins(ps, v, y, shadow, counters, o0)) return shadow;
  const V3 d = y - o0;
  const vf margin = 0.5f * gather(ps.scene->target_clearances(), select(shadow, target, splat_i(0))) / sqrt(dot(d, d));
  const vf tmax = select(margin >= 1e-5f, 1.f - min(margin, splat(0.5f)), splat(1.f));
  RayHit16 packet;
  Scene::ShadowPacket q;
  if constexpr (kLanes < RayHit16::kLanes) {
    packet = RayHit16{};
    std::fill(std::begin(q.active), std::end(q.active), 0);
  }
  store_rays(packet, o0, d, splat(0.f), tmax);
  store(q.o0x, o0.x), store(q.o0y, o0.y), store(q.o0z, o0.z);
  store(q.p1x, y.x), store(q.p1y, y.y), store(q.p1z, y.z);
  store(reinterpret_cast<int32_t*>(q.target), target), store(reinterpret_cast<int32_t*>(q.origin), v.prim);
  store(q.active, shadow);
  ps.scene->occluded(packet, q);
  return shadow & (load(packet.tmax) >= 0.f);
}

// Scene::visible_point for the lanes in `lanes` (targets in free space: point emitters, points
// beyond the scene towards directions at infinity), or no ray where connections are
// unoccluded: each segment up to its stop short of the target, without a filter.
inline vi visible_points(const PathLanesScene& ps, const LaneVertex& v, const V3& y, vi lanes,
                         TraceCounters& counters) {
  V3 o0;
  if (!shadow_origins(ps, v, y, lanes, counters, o0)) return lanes;
  const V3 d = y - o0;
  const vf stop = 1.f - ps.scene->eye_clearance() / sqrt(dot(d, d));
  const vi trace = lanes & (stop > 0.f);  // none where the stop is not ahead: visible
  if (!any(trace)) return lanes;
  RayHit16 packet;
  if constexpr (kLanes < RayHit16::kLanes) packet = RayHit16{};
  alignas(64) int32_t active[RayHit16::kLanes] = {};
  store_rays(packet, o0, d, splat(0.f), stop);
  store(active, trace);
  ps.scene->occluded_points(active, packet);
  return lanes & ~(trace & (load(packet.tmax) < 0.f));
}

// eval_f_world and pdf_w_world of the lanes in `lanes` (of kind kLaneOther), by the scalar code,
// into f and pdf_w.
inline void evaluate_scalar_bsdfs(const LaneVertex& v, const ScalarBsdfs& b, vi lanes, const V3& wo, const V3& wi,
                                  V3& f, vf& pdf_w) {
  alignas(64) float fx[kLanes], fy[kLanes], fz[kLanes], pdf[kLanes];
  store(fx, f.x), store(fy, f.y), store(fz, f.z), store(pdf, pdf_w);
  for (int i = 0; i < kLanes; ++i) {
    if (lanes[i] == 0) continue;
    const Vec3 ns = lane(v.ns, i), wo_i = lane(wo, i), wi_i = lane(wi, i);
    const Color fi = eval_f_world(*b.of[i], ns, wo_i, wi_i, TransportMode::Radiance);
    fx[i] = fi.x, fy[i] = fi.y, fz[i] = fi.z;
    pdf[i] = pdf_w_world(*b.of[i], ns, wo_i, wi_i, TransportMode::Radiance);
  }
  f = {load(fx), load(fy), load(fz)};
  pdf_w = load(pdf);
}

// Scene::choose_emitter's choice for the `active` lanes: its comparisons counted lane-wide where
// the scene has few emitters, else its search lane by lane.
inline vi choose_emitter(const PathLanesScene& ps, vf u, vi active) {
  if (!ps.emitter_ends.empty()) {
    vi passed = splat_i(0);
    for (const float end : ps.emitter_ends) passed -= u >= end;
    const auto last = static_cast<int32_t>(ps.emitter_ends.size()) - 1;
    return select(passed < last, passed, splat_i(last));
  }
  alignas(64) int32_t chosen[kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (active[i] == 0) continue;
    chosen[i] = static_cast<int32_t>(ps.scene->choose_emitter(u[i]).emitter - ps.scene->emitters().data());
  }
  return load(chosen);
}

// light_connection (next_event.h) after sample_Li, lane-wide for the lanes in `sampled` (light
// directions wi of densities pdf_w; `delta`: the lanes whose emitter is a delta light): f and
// wi's cosine about the shading normal (eval_f_world and pdf_w_world: the Lambertian's two
// cosines lane-wide, other members by the scalar code), the black ones counted skipped, the MIS
// weight against BSDF sampling (full for delta lights); `shadow`: the lanes whose shadow ray to
// trace.
struct LaneLightConnection {
  V3 f;
  vf cos_i, weight;
  vi shadow;
};
inline LaneLightConnection light_connections(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b,
                                             const V3& wo, const V3& wi, vi sampled, vf pdf_w, vi delta,
                                             TraceCounters& counters) {
  LaneLightConnection c;
  const vf cos_o = dot(wo, v.ns);
  c.cos_i = dot(wi, v.ns);
  const vi same_side = cos_o * c.cos_i > 0.f;
  c.f = select(same_side, v.albedo * kInvPi, splat(Vec3(0.f)));
  vf pdf_bsdf_w = select(same_side, cosine_hemisphere_pdf(abs(c.cos_i)), splat(0.f));
  if (any(sampled & b.other)) evaluate_scalar_bsdfs(v, b, sampled & b.other, wo, wi, c.f, pdf_bsdf_w);
  const vi black = is_black(c.f);
  counters.skipped_connections += count(sampled & black);
  c.weight = splat(1.f);
  if (any(sampled & ~delta)) {
    const vf mis = two_strategy_weight(ps.options->strategies, Strategies::Light, pdf_w, pdf_bsdf_w);
    c.weight = select(delta, c.weight, mis);
  }
  c.shadow = sampled & ~black & (c.weight != 0.f);
  return c;
}

// light_contribution (next_event.h) of connections c with radiance Le: beta f Le |cos| weight / pdf_w.
inline V3 light_contributions(const LanePaths& paths, const LaneLightConnection& c, const V3& Le, vf pdf_w) {
  return paths.beta * c.f * Le * (abs(c.cos_i) * c.weight / pdf_w);
}

// next_event of the lanes in `lanes`, whose emitters (`e`, of `kind`) are a point, a spot or a
// direction: sample_Li (point_emitter.h, spot_emitter.h; light_sample_at_infinity,
// distant_disk.h), then light_connection and light_contribution (next_event.h) with their
// arithmetic in their order, a delta light keeping full weight; a spot's falloff lane by lane.
[[gnu::noinline]]  // off the area emitters' path (inlined, it cost the caustic box 2 %)
inline void add_delta_light_next_events(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b,
                                        const V3& wo, vi lanes, vi e, vi kind, LanePaths& paths,
                                        TraceCounters& counters) {
  const LaneEmitter* em = ps.emitters.data();
  const vi directional = lanes & (kind == kLaneDirectionalEmitter);
  const vi positional = lanes & ((kind == kLanePointEmitter) | (kind == kLaneSpotEmitter));
  // A point or spot: towards its position, its 1 / r^2 in Le.
  const V3 position = gather3(em, e, positional, offsetof(LaneEmitter, p));
  const V3 to_light = position - v.p;
  const vf dist2 = dot(to_light, to_light);
  // A direction: the segment ends beyond the scene's bounding sphere (reach_beyond).
  const V3 towards = gather3(em, e, directional, offsetof(LaneEmitter, n));
  const V3 from_center = v.p - gather3(em, e, directional, offsetof(LaneEmitter, center));
  const vf reach = 2.f * gather_field(em, e, directional, offsetof(LaneEmitter, radius)) +
                   sqrt(dot(from_center, from_center));
  const V3 wi = select(directional, towards, to_light / sqrt(dist2));
  const V3 y = select(directional, v.p + towards * reach, position);
  alignas(64) float falloff[kLanes];
  store(falloff, splat(1.f));
  const vi spot = positional & (kind == kLaneSpotEmitter);
  for (int i = 0; i < kLanes; ++i) {
    if (spot[i] == 0) continue;
    falloff[i] = spot_falloff(std::get<SpotEmitter>(ps.scene->emitters()[static_cast<size_t>(e[i])]), -lane(wi, i));
  }
  const V3 I = gather3(em, e, lanes, offsetof(LaneEmitter, Le));
  const V3 Le = select(directional, I, I * load(falloff) / dist2);
  const vi sampled = directional | (positional & (dist2 > 0.f) & ~(spot & is_black(Le)));
  const vf pmf = gather_field(em, e, sampled, offsetof(LaneEmitter, pdf_a));
  const LaneLightConnection c = light_connections(ps, v, b, wo, wi, sampled, pmf, sampled, counters);
  if (!any(c.shadow)) return;
  const V3 C = light_contributions(paths, c, Le, pmf);
  const vi seen = visible_points(ps, v, y, c.shadow, counters);
  paths.L = select(seen, paths.L + C, paths.L);
}

// next_event of the lanes in `lanes`, whose emitter is a constant environment: sample_Li
// (constant_emitter.h: a uniform direction, lane by lane since square_to_uniform_sphere's sine
// and cosine are the C library's; light_sample_at_infinity), then light_connection and
// light_contribution (next_event.h) in their order, MIS-weighted against BSDF sampling.
[[gnu::noinline]]  // off the area emitters' path (inlined, it cost the caustic box 2 %)
inline void add_constant_environment_next_events(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b,
                                                 const V3& wo, vi lanes, vi e, vf u, vf w, LanePaths& paths,
                                                 TraceCounters& counters) {
  alignas(64) float d[3][kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (lanes[i] == 0) continue;
    const Vec3 di = square_to_uniform_sphere({u[i], w[i]});
    d[0][i] = di.x, d[1][i] = di.y, d[2][i] = di.z;
  }
  const V3 wi{load(d[0]), load(d[1]), load(d[2])};
  const LaneEmitter* em = ps.emitters.data();
  const V3 from_center = v.p - gather3(em, e, lanes, offsetof(LaneEmitter, center));
  const vf reach = 2.f * gather_field(em, e, lanes, offsetof(LaneEmitter, radius)) +
                   sqrt(dot(from_center, from_center));
  const vf pdf_w = gather_field(em, e, lanes, offsetof(LaneEmitter, pdf_a));
  const LaneLightConnection c = light_connections(ps, v, b, wo, wi, lanes, pdf_w, splat_i(0), counters);
  if (!any(c.shadow)) return;
  const V3 C = light_contributions(paths, c, gather3(em, e, c.shadow, offsetof(LaneEmitter, Le)), pdf_w);
  const vi seen = visible_points(ps, v, v.p + wi * reach, c.shadow, counters);
  paths.L = select(seen, paths.L + C, paths.L);
}

// next_event of the lanes in `lanes` (emitters `e` of kind kLaneScalarEmitter): each emitter's
// sample_Li by the scalar code, lane by lane, then light_connection and light_contribution
// (next_event.h) lane-wide with their arithmetic in their order, the shadow rays in packets.
[[gnu::noinline]]  // off the area emitters' path (inlined, it cost the caustic box 2 %)
inline void add_scalar_next_events(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b, const V3& wo,
                                   vi lanes, vi e, vf u, vf w, LanePaths& paths, TraceCounters& counters) {
  alignas(64) float wi[3][kLanes] = {}, y[3][kLanes] = {}, Le[3][kLanes] = {}, pdf_w[kLanes] = {};
  alignas(64) int32_t target[kLanes] = {}, sampled[kLanes] = {}, on_surface[kLanes] = {}, delta[kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (lanes[i] == 0) continue;
    const Emitter& emitter = ps.scene->emitters()[static_cast<size_t>(e[i])];
    LightSample ls;
    if (!sample_Li(emitter, ps.scene->emitter_pmf(emitter), lane(v.p, i), {u[i], w[i]}, ls)) continue;
    for (int k = 0; k < 3; ++k) wi[k][i] = ls.wi[k], y[k][i] = ls.p[k], Le[k][i] = ls.Le[k];
    pdf_w[i] = ls.pdf_w;
    target[i] = static_cast<int32_t>(ls.prim);
    sampled[i] = -1;
    on_surface[i] = ls.on_surface ? -1 : 0;
    delta[i] = is_delta_light(emitter) ? -1 : 0;  // full weight, as light_connection's
  }
  const V3 WI{load(wi[0]), load(wi[1]), load(wi[2])};
  const vf pdf = load(pdf_w);
  const LaneLightConnection c = light_connections(ps, v, b, wo, WI, load(sampled), pdf, load(delta), counters);
  if (!any(c.shadow)) return;
  const V3 C = light_contributions(paths, c, V3{load(Le[0]), load(Le[1]), load(Le[2])}, pdf);
  const V3 Y{load(y[0]), load(y[1]), load(y[2])};
  const vi surface = load(on_surface);
  const vi seen = visible(ps, v, Y, load(target), c.shadow & surface, counters) |
                  visible_points(ps, v, Y, c.shadow & ~surface, counters);
  paths.L = select(seen, paths.L + C, paths.L);
}

// next_event: a light sample per lane (sample_Li of the area emitter the scene's choice picks),
// MIS-weighted against BSDF sampling, through its shadow ray; points, spots and directions by
// add_delta_light_next_events, a constant environment by add_constant_environment_next_events,
// other emitters by the scalar code.
template <class Sampler>
void add_next_event(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b, const V3& wo,
                    LaneNumbers<Sampler>& numbers, LanePaths& paths, TraceCounters& counters) {
  // No light sample can meet a specular lobe.
  const vi delta = (v.bsdf == kLaneMirror) | (v.bsdf == kLaneDielectric) | b.delta;
  counters.skipped_connections += count(paths.active & delta);
  const vi lit = paths.active & ~delta;
  if (!any(lit)) return;
  const vf u_select = numbers.next_1d(lit);
  vf u, w;
  numbers.next_2d(lit, u, w);
  const vi e = choose_emitter(ps, u_select, lit);
  const LaneEmitter* em = ps.emitters.data();
  // Each lane by its emitter's kind: the scalar code's, a constant environment, a point, spot or
  // direction, or an area emitter.
  const vi kind = gather_int(em, e, lit, offsetof(LaneEmitter, kind));
  const vi scalar = lit & (kind == kLaneScalarEmitter);
  if (any(scalar)) add_scalar_next_events(ps, v, b, wo, scalar, e, u, w, paths, counters);
  const vi constant = lit & (kind == kLaneConstantEmitter);
  if (any(constant)) add_constant_environment_next_events(ps, v, b, wo, constant, e, u, w, paths, counters);
  const vi delta_lights =
      lit & ((kind == kLanePointEmitter) | (kind == kLaneSpotEmitter) | (kind == kLaneDirectionalEmitter));
  if (any(delta_lights)) add_delta_light_next_events(ps, v, b, wo, delta_lights, e, kind, paths, counters);
  const vi active = lit & (kind == kLaneAreaEmitter);
  if (!any(active)) return;
  // pdf_Le_position: the choice's pmf over the area, the emitter's pmf.
  const vf pdf_a = gather_field(em, e, active, offsetof(LaneEmitter, pdf_a));
  const vf su = sqrt(u);                     // square_to_uniform_triangle
  const V3 y = barycentric_point(em, e, active, w * su, 1.f - su);
  const V3 to_light = y - v.p;
  const vf dist2 = dot(to_light, to_light);
  const V3 wi = to_light / sqrt(dist2);
  const vf cos_light = -dot(gather3(em, e, active, offsetof(LaneEmitter, n)), wi);
  const vi sampled = active & (cos_light > 0.f) & (dist2 > 0.f);
  const vf pdf_w = pdf_a * dist2 / cos_light;
  const LaneLightConnection c = light_connections(ps, v, b, wo, wi, sampled, pdf_w, splat_i(0), counters);
  if (!any(c.shadow)) return;
  const vi seen = visible(ps, v, y, gather_int(em, e, c.shadow, offsetof(LaneEmitter, prim)), c.shadow, counters);
  const V3 C = light_contributions(paths, c, gather3(em, e, seen, offsetof(LaneEmitter, Le)), pdf_w);
  paths.L = select(seen, paths.L + C, paths.L);
}

// A BSDF sample per lane: `sample` of each lane's member (bsdf.h), all three computed and the
// lane's chosen.
struct LaneBsdfSample {
  V3 wi, weight;
  vf pdf_w, eta;
  vi ok;
};

// Lambertian: a cosine-weighted direction on wo's side.
inline LaneBsdfSample sample_lambertian(const V3& albedo, const V3& wo, vf u1, vf u2) {
  LaneBsdfSample s;
  s.wi = square_to_cosine_hemisphere(u1, u2);
  s.wi.z = select(wo.z < 0.f, -s.wi.z, s.wi.z);
  s.pdf_w = cosine_hemisphere_pdf(abs(s.wi.z));
  s.weight = albedo;
  s.eta = splat(1.f);
  s.ok = s.pdf_w > 0.f;
  return s;
}

// Smooth dielectric of relative index eta: Fresnel-weighted reflection or refraction
// (fresnel_dielectric, refract_local; radiance scales by 1 / eta_ratio^2 across).
inline LaneBsdfSample sample_dielectric(vf eta, const V3& wo, vf u1) {
  const vf eta_ratio = select(wo.z >= 0.f, eta, 1.f / eta);
  const vf ci = min(abs(wo.z), splat(1.f));
  const vf sin2_t = (1.f - ci * ci) / (eta_ratio * eta_ratio);
  const vi total = sin2_t >= 1.f;
  const vf ct = select(total, splat(0.f), sqrt(1.f - sin2_t));
  const vf rs = (ci - eta_ratio * ct) / (ci + eta_ratio * ct);
  const vf rp = (eta_ratio * ci - ct) / (eta_ratio * ci + ct);
  const vf R = select(total, splat(1.f), 0.5f * (rs * rs + rp * rp));
  const vi reflect = u1 < R;
  const vf inv = 1.f / eta_ratio;
  LaneBsdfSample s;
  s.wi = select(reflect, V3{-wo.x, -wo.y, wo.z}, V3{-wo.x * inv, -wo.y * inv, select(wo.z > 0.f, -ct, ct)});
  s.pdf_w = select(reflect, R, 1.f - R);
  s.weight = select(reflect, splat(Vec3(1.f)), V3{inv * inv, inv * inv, inv * inv});
  s.eta = select(reflect, splat(1.f), eta_ratio);
  s.ok = reflect | (s.pdf_w > 0.f);
  return s;
}

inline LaneBsdfSample select(vi m, const LaneBsdfSample& a, const LaneBsdfSample& b) {
  return {select(m, a.wi, b.wi), select(m, a.weight, b.weight), select(m, a.pdf_w, b.pdf_w), select(m, a.eta, b.eta),
          select(m, a.ok, b.ok)};
}

// `sample` of the lanes in `lanes` (of kind kLaneOther) by the scalar code; `delta`: whether
// each sampled a Dirac lobe.
inline LaneBsdfSample sample_scalar_bsdfs(const ScalarBsdfs& b, vi lanes, const V3& wo, vf u1, vf u2, vi& delta) {
  alignas(64) float wi[3][kLanes] = {}, weight[3][kLanes] = {}, pdf[kLanes] = {}, eta[kLanes] = {};
  alignas(64) int32_t ok[kLanes] = {}, dirac[kLanes] = {};
  for (int i = 0; i < kLanes; ++i) {
    if (lanes[i] == 0) continue;
    BsdfSample bs;
    ok[i] = sample(*b.of[i], lane(wo, i), Point2{u1[i], u2[i]}, TransportMode::Radiance, bs) ? -1 : 0;
    for (int k = 0; k < 3; ++k) wi[k][i] = bs.wi[k], weight[k][i] = bs.weight[k];
    pdf[i] = bs.pdf_w, eta[i] = bs.eta, dirac[i] = bs.delta ? -1 : 0;
  }
  delta = load(dirac) & load(ok);
  return {{load(wi[0]), load(wi[1]), load(wi[2])}, {load(weight[0]), load(weight[1]), load(weight[2])}, load(pdf),
          load(eta), load(ok)};
}

// The lanes' BSDF samples and Russian roulette (extend_path's `leave`): the next segment's rays;
// lanes whose path ends there leave `active`.
template <class Sampler>
void leave(const PathLanesScene& ps, const LaneVertex& v, const ScalarBsdfs& b, const LaneFrame& frame,
           const V3& wo_local, vi depth, LaneNumbers<Sampler>& numbers, LanePaths& paths, LaneRays& rays) {
  vf u1, u2;
  numbers.next_2d(paths.active, u1, u2);
  const vi mirror = v.bsdf == kLaneMirror, dielectric = v.bsdf == kLaneDielectric;
  LaneBsdfSample s = sample_lambertian(v.albedo, wo_local, u1, u2);
  if (any(paths.active & (mirror | dielectric))) {
    const LaneBsdfSample m{{-wo_local.x, -wo_local.y, wo_local.z}, v.albedo, splat(1.f), splat(1.f), splat_i(-1)};
    s = select(mirror, m, select(dielectric, sample_dielectric(v.albedo.x, wo_local, u1), s));
  }
  // The three members refuse wo.z = 0 themselves; the scalar code's members decide their own.
  s.ok &= wo_local.z != 0.f;
  vi scalar_delta{};
  const vi scalar = paths.active & b.other;
  if (any(scalar)) s = select(scalar, sample_scalar_bsdfs(b, scalar, wo_local, u1, u2, scalar_delta), s);
  paths.active &= s.ok;
  paths.beta = paths.beta * s.weight;
  paths.roulette_scale = paths.roulette_scale * (s.eta * s.eta * 1.f);  // roulette_scale, unguided
  paths.prev_pdf_w = s.pdf_w;
  paths.prev_delta = mirror | dielectric | scalar_delta;
  rays.d = frame.to_world(s.wi);
  // leaves_front (shading_normal.h): by the geometric normal where the shading normal differs
  // (smooth triangles only).
  vi front = s.wi.z > 0.f;
  if (ps.smooth) {
    const vi flat = (v.n.x == v.ns.x) & (v.n.y == v.ns.y) & (v.n.z == v.ns.z);
    front = select(flat, front, dot(rays.d, v.n) > 0.f);
  }
  rays.o = offset_ray_origin(v.p, select(front, v.n, -v.n), ps.scene->offset_scale());
  rays.tmin = splat(0.f);
  rays.tmax = splat(std::numeric_limits<float>::infinity());
  const vi roulette = paths.active & (depth >= ps.options->rr_depth);
  if (any(roulette)) {
    const vf q = min(max_component(paths.beta) * paths.roulette_scale, splat(0.95f));  // roulette_survival
    const vi go_on = numbers.next_1d(roulette) < q;
    paths.active &= go_on | ~roulette;
    paths.beta = select(roulette, paths.beta / q, paths.beta);
  }
}

// The lanes' paths, the pixel sample each traces (-1: none) and their random numbers.
template <class Sampler>
struct LaneState {
  LaneRays rays{};
  KnownHits known;
  LanePaths paths{splat_i(0), splat(Vec3(1.f)), splat(Vec3(0.f)), splat(0.f), splat_i(-1), splat(1.f)};
  vi depth = splat_i(1);  // the vertex the next ray finds is the path's depth-th
  int32_t sample[kLanes];
  LaneNumbers<Sampler> numbers;
  TexturedBsdfs textured;  // ScalarBsdfs' storage
  LaneState() { std::fill(std::begin(sample), std::end(sample), -1); }
};

// The pixel samples of a batch estimate (pixel_driver.h), and the next one no lane has taken.
struct LaneBatch {
  uint64_t seed;
  int film_width;
  const PixelSample* samples;
  size_t n, next;
};

// The random streams of camera rays' samples, until lanes take them (regenerate): their
// samplers...
template <class Sampler>
struct StartedStreams {
  std::optional<Sampler> samplers[kLanes];
  void hand_over(int k, int lane, LaneNumbers<Sampler>& numbers) const { numbers.start(lane, *samplers[k]); }
};
// ... or, for the independent sampler, whose samples start lane-wide, their generators.
template <>
struct StartedStreams<IndependentSampler> {
  alignas(64) uint64_t state[kLanes], inc[kLanes];
  void hand_over(int k, int lane, LaneNumbers<IndependentSampler>& numbers) const {
    numbers.rng.state[lane] = state[k];
    numbers.rng.inc[lane] = inc[k];
  }
};

// Camera rays traced ahead of the lanes that take their samples, kLanes at a time. A batch's
// consecutive samples are one pixel's (pixel_driver.h, render_tile), so their rays leave the
// camera through one pixel, or a few neighbouring ones: a coherent packet, which Embree traces
// by the packet's frustum (Coherence::kCoherent) instead of ray by ray, as Mitsuba 3's LLVM
// variant traces its camera rays. Mixed into the lanes' packets of later segments, they went ray
// by ray like those. The same hits, so the same bits. (Packets of 16 neighbouring pixels instead
// of one pixel's samples gained less on the Cornell box and the door at 64x64, and lost 3 % on
// the caustic box, whose finely tessellated sphere fills much of such a frustum.)
template <class Sampler>
struct CameraRays {
  RayHit16 packet{};  // the rays, and after tracing their hits (lanes from kLanes on unused)
  alignas(64) float tmax[kLanes] = {};  // the rays' own
  int32_t sample[kLanes];
  StartedStreams<Sampler> streams;
  int size = 0, next = 0;
};

// trace_path's start (start_sample, then the camera ray through the film position it picks) of
// the batch's next q.size samples, one after another...
template <class Sampler>
void start_camera_rays(const PathLanesScene& ps, const LaneBatch& batch, CameraRays<Sampler>& q) {
  for (int k = 0; k < q.size; ++k) {
    const Point2 position =
        start_sample(batch.seed, batch.film_width, batch.samples[batch.next + static_cast<size_t>(k)],
                     q.streams.samplers[k]);
    const Ray r = ps.scene->eye_ray(ps.camera->generate_ray(position.u, position.v));
    q.packet.set(k, r);
    q.tmax[k] = r.tmax;
  }
}

// in_pixel (pixel_driver.h): x + jitter, below x + 1 (std::nextafter toward 0 steps a nonzero
// float's bits down by one).
inline vf in_pixel(vi x, vf jitter) {
  const vf next = __builtin_convertvector(x + 1, vf);
  const vf below = select(next == 0.f, next, bits_to_float(float_to_bits(next) - 1));
  return min(__builtin_convertvector(x, vf) + jitter, below);
}

// ... or, for the independent sampler, lane-wide: each lane's Pcg32 seeded as
// IndependentSampler's constructor does, its first 2D sample's film position, and
// PinholeCamera::generate_ray's ray through it from the eye (Scene::eye_ray). The scalar code's
// operations in its order: its bits. (One sample at a time, these took 3.4 % of the caustic box's
// profile, mostly the latency of generate_ray's divisions and square root; lane-wide its
// samples per second rose 2.3 %, the Cornell box's 4.0 %, the door's 3.2 %.)
inline void start_camera_rays(const PathLanesScene& ps, const LaneBatch& batch, CameraRays<IndependentSampler>& q) {
  alignas(64) int32_t x[kLanes], y[kLanes], s[kLanes];
  for (int k = 0; k < kLanes; ++k) {  // lanes from q.size on repeat the first sample
    const PixelSample& p = batch.samples[batch.next + static_cast<size_t>(k < q.size ? k : 0)];
    x[k] = p.x, y[k] = p.y, s[k] = static_cast<int32_t>(p.s);
  }
  const vi px = load(x), py = load(y);
  const vu64 stream = __builtin_convertvector((vu)load(s), vu64);
  const vu64 pixel = (vu64)__builtin_convertvector(py, vi64) * static_cast<uint64_t>(batch.film_width) +
                     (vu64)__builtin_convertvector(px, vi64);
  LanePcg32 rng{hash_combine(hash_combine(vu64{} + batch.seed, pixel), stream), (stream << 1u) | 1u};
  const vi all = splat_i(-1);
  rng.next_float(all);  // the step of Pcg32's constructor
  const vf u = rng.next_float(all);
  const vf v = rng.next_float(all);
  std::memcpy(q.streams.state, &rng.state, sizeof q.streams.state);
  std::memcpy(q.streams.inc, &rng.inc, sizeof q.streams.inc);
  const PinholeCamera& c = *ps.camera;
  const vf sx = (2.f * in_pixel(px, u) / static_cast<float>(c.width()) - 1.f) * c.tan_half_x();
  const vf sy = (1.f - 2.f * in_pixel(py, v) / static_cast<float>(c.height())) * c.tan_half_y();
  const V3 w = splat(c.forward()) + splat(c.right()) * sx + splat(c.up()) * sy;
  const vf infinity = splat(std::numeric_limits<float>::infinity());
  store_rays(q.packet, splat(c.origin()), w / sqrt(dot(w, w)), splat(ps.scene->eye_clearance()), infinity);
  store(q.tmax, infinity);
}

// The batch's next (up to) kLanes samples started and their camera rays traced, into `q`.
template <class Sampler>
[[gnu::noinline]]  // once per kLanes samples: out of trace_paths' flattened loop
void trace_camera_rays(const PathLanesScene& ps, LaneBatch& batch, CameraRays<Sampler>& q) {
  q.size = static_cast<int>(std::min(static_cast<size_t>(kLanes), batch.n - batch.next));
  q.next = 0;
  if (q.size == 0) return;
  alignas(64) int32_t active[RayHit16::kLanes] = {};
  for (int k = 0; k < q.size; ++k) {
    q.sample[k] = static_cast<int32_t>(batch.next + static_cast<size_t>(k));
    active[k] = -1;
  }
  start_camera_rays(ps, batch, q);
  batch.next += static_cast<size_t>(q.size);
  ps.scene->intersect(active, q.packet, Coherence::kCoherent);
}

// Path regeneration [Novák et al. 2010]: each lane whose path has ended writes its estimate,
// and takes the batch's next sample (trace_path's start: its sampler, film position and camera
// ray, with the ray's hit, from `camera`; a new path, extend_path's initial state). Returns
// whether any lane's path goes on.
template <class Sampler>
bool regenerate(const PathLanesScene& ps, LaneBatch& batch, CameraRays<Sampler>& camera, LaneState<Sampler>& st,
                Color* values) {
  alignas(64) float o[3][kLanes], d[3][kLanes], tmin[kLanes], tmax[kLanes];
  store(o[0], st.rays.o.x), store(o[1], st.rays.o.y), store(o[2], st.rays.o.z);
  store(d[0], st.rays.d.x), store(d[1], st.rays.d.y), store(d[2], st.rays.d.z);
  store(tmin, st.rays.tmin), store(tmax, st.rays.tmax);
  alignas(64) int32_t fresh[kLanes] = {};
  KnownHits& known = st.known;
  // The ended lanes by their bits (a branch per lane, mispredicted, cost 0.6 % of the time).
  for (uint32_t ended = lane_bits(~st.paths.active); ended != 0; ended &= ended - 1) {
    const int i = __builtin_ctz(ended);
    if (st.sample[i] >= 0) values[st.sample[i]] = Color(st.paths.L.x[i], st.paths.L.y[i], st.paths.L.z[i]);
    st.sample[i] = -1;
    if (camera.next == camera.size) trace_camera_rays(ps, batch, camera);
    if (camera.next == camera.size) continue;
    const int k = camera.next++;
    const RayHit16& c = camera.packet;
    st.sample[i] = camera.sample[k];
    camera.streams.hand_over(k, i, st.numbers);  // the lanes' generator takes the sampler's state
    const Ray r = c.ray(k);
    for (int j = 0; j < 3; ++j) o[j][i] = r.o[j], d[j][i] = r.d[j];
    tmin[i] = r.tmin, tmax[i] = camera.tmax[k], fresh[i] = -1;
    known.t[i] = r.tmax, known.u[i] = c.u[k], known.v[i] = c.v[k];
    known.prim[i] = static_cast<int32_t>(c.prim[k]);
  }
  const vi start = load(fresh);
  known.lanes = start;
  if (!any(start)) return any(st.paths.active);
  st.rays = {{load(o[0]), load(o[1]), load(o[2])}, {load(d[0]), load(d[1]), load(d[2])}, load(tmin), load(tmax)};
  LanePaths& p = st.paths;
  p.active |= start;
  p.beta = select(start, splat(Vec3(1.f)), p.beta);
  p.L = select(start, splat(Vec3(0.f)), p.L);
  p.prev_pdf_w = select(start, splat(0.f), p.prev_pdf_w);
  p.prev_delta = select(start, splat_i(-1), p.prev_delta);
  p.roulette_scale = select(start, splat(1.f), p.roulette_scale);
  st.depth = select(start, splat_i(1), st.depth);
  return true;
}

// extend_path's step for every running lane: the vertex its ray finds, the emission seen there,
// and (where the path may grow) next-event estimation and the next ray.
template <class Sampler>
void bounce(const PathLanesScene& ps, LaneState<Sampler>& st, TraceCounters& counters) {
  LanePaths& paths = st.paths;
  const LaneVertex v = intersect(ps, st.rays, st.known, paths, counters);
  const V3 wo = -st.rays.d;
  add_emission(ps, v, wo, paths);
  const int max_depth = ps.options->max_depth;
  if (max_depth >= 0) paths.active &= st.depth < max_depth;  // depth_allows(depth + 1)
  if (!any(paths.active)) return;
  ScalarBsdfs b(st.textured);
  find_scalar_bsdfs(ps, v, paths.active, b);
  const LaneFrame frame = frame_from_normal(v.ns);
  const V3 wo_local = frame.to_local(wo);
  add_next_event(ps, v, b, wo, st.numbers, paths, counters);
  leave(ps, v, b, frame, wo_local, st.depth, st.numbers, paths, st.rays);
  st.depth = st.depth + 1;
}

// TracePathLanes (path_tracer_lanes.h): the batch's samples, kLanes paths at a time.
template <class Sampler>
[[gnu::flatten]] void trace_paths(const PathLanesScene& ps, uint64_t seed, int film_width, const PixelSample* samples,
                                  size_t n, TraceCounters& counters, Color* values) {
  if (ps.options->max_depth == 0) {  // paths of no segments end where they start, with no radiance
    std::fill(values, values + n, Color(0.f));
    return;
  }
  LaneBatch batch{seed, film_width, samples, n, 0};
  CameraRays<Sampler> camera;
  LaneState<Sampler> st;
  while (regenerate(ps, batch, camera, st, values)) bounce(ps, st, counters);
}

}  // namespace dualight::DUALIGHT_LANES_NS
