// Ray-triangle conventions of the Embree wrapper and the scene, and the ray offset.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <vector>

#include "box_scene.h"
#include "check.h"
#include "core/ray.h"
#include "core/sampler.h"
#include "geometry/camera.h"
#include "geometry/scene.h"
#include "geometry/surface_clearance.h"

using namespace dualight;

namespace {
Scene unit_triangle_scene(Color emission) {
  return Scene({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, {0}, {Material{Lambertian{Color(0.5f)}, emission}});
}

// Scene::visible for a packet of queries, through Scene::occluded with the segments built as the
// path tracer's lanes build them (path_lanes_kernel.h, visible): visible[i] is 1 or 0 (0 for
// inactive lanes).
void packet_visible(const Scene& scene, const Scene::ShadowPacket& q, int32_t* visible) {
  constexpr int kLanes = RayPacket::kLanes;
  RayHit16 segments{};
  for (int i = 0; i < kLanes; ++i) {
    if (q.active[i] == 0) continue;
    const Vec3 o0{q.o0x[i], q.o0y[i], q.o0z[i]}, d = Vec3{q.p1x[i], q.p1y[i], q.p1z[i]} - o0;
    const float stop = short_stop(d, scene.target_clearances()[q.target[i]]);
    segments.ox[i] = o0.x, segments.oy[i] = o0.y, segments.oz[i] = o0.z;
    segments.dx[i] = d.x, segments.dy[i] = d.y, segments.dz[i] = d.z;
    segments.tmin[i] = 0.f, segments.tmax[i] = stop > 0.f ? stop : 1.f;
  }
  scene.occluded(segments, q);
  for (int i = 0; i < kLanes; ++i) visible[i] = q.active[i] != 0 && segments.tmax[i] >= 0.f ? 1 : 0;
}
}  // namespace

TEST_CASE("hits_from_both_sides_with_right_hand_normal") {
  const Scene scene = unit_triangle_scene(Color(1.f));
  SurfaceHit hit;
  CHECK(scene.intersect(Ray{{0.2f, 0.3f, 2.f}, {0, 0, -1}}, hit));
  CHECK_NEAR(hit.t, 2.f, 1e-6f);
  CHECK_NEAR(hit.p.x, 0.2f, 1e-6f);
  CHECK_NEAR(hit.p.y, 0.3f, 1e-6f);
  CHECK(hit.n.z > 0.99f);  // (v1 - v0) x (v2 - v0) = +z
  CHECK(hit.emitter != nullptr);
  CHECK(!is_black(radiance(*hit.emitter, Vec3(0, 0, 1), hit.uv)));  // front side emits
  CHECK(is_black(radiance(*hit.emitter, Vec3(0, 0, -1), hit.uv)));  // back side does not
  CHECK(scene.intersect(Ray{{0.2f, 0.3f, -1.f}, {0, 0, 1}}, hit));
  CHECK(!scene.intersect(Ray{{0.6f, 0.6f, 1.f}, {0, 0, -1}}, hit));  // past the hypotenuse
  CHECK(!scene.intersect(Ray{{0.2f, 0.3f, 1.f}, {0, 0, 1}}, hit));   // behind the origin
  CHECK(!scene.intersect(Ray{{0.2f, 0.3f, 1.f}, {0, 0, -1}, 0.5f}, hit));  // beyond tmax
}

TEST_CASE("emitter_sampling_density_is_one_over_area") {
  const Scene scene = unit_triangle_scene(Color(2.f));
  const EmitterChoice choice = scene.choose_emitter(0.5f);
  CHECK(choice.emitter == scene.emitter_at(0));
  CHECK_NEAR(choice.pmf, 1.f, 1e-6f);
  const EmitterPoint s = sample_Le_position(*choice.emitter, choice.pmf, {0.3f, 0.6f});
  CHECK_NEAR(s.pdf_a, 2.f, 1e-5f);  // area 1/2
  CHECK_NEAR(pdf_Le_position(*choice.emitter, choice.pmf, s.p), 2.f, 1e-5f);
  CHECK(s.prim == 0);
  CHECK((s.p.x >= 0.f && s.p.y >= 0.f && s.p.x + s.p.y <= 1.f + 1e-6f && s.p.z == 0.f));
}

TEST_CASE("scene_rejects_malformed_input") {
  auto throws = [](auto make) {
    try {
      make();
    } catch (const std::invalid_argument&) {
      return true;
    }
    return false;
  };
  const Material m{Lambertian{Color(0.5f)}, Color(0.f)};
  CHECK(throws([&] { Scene({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 3}, {0}, {m}); }));            // index
  CHECK(throws([&] { Scene({0, 0, 0, 1, 0, 0, 2, 0, 0}, {0, 1, 2}, {0}, {m}); }));            // zero area
  CHECK(throws([&] { Scene({0, 0, NAN, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, {0}, {m}); }));          // NaN
  CHECK(throws([&] { Scene({}, {}, {}, {m}); }));                                             // empty
  CHECK(throws([&] { Scene({0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, {1}, {m}); }));            // material
}

TEST_CASE("offset_origin_leaves_the_surface_at_any_scale") {
  // Within a thousandth of the scene's size at every scale: a fixed 1/65536 near the origin
  // was a quarter of a scene 6e-5 across (issue 18).
  for (const float scale : {1e-8f, 1e-7f, 1e-5f, 1.f, 1e5f, 1e7f}) {
    const Scene scene({0, 0, 0, scale, 0, 0, 0, scale, 0}, {0, 1, 2}, {0},
                      {Material{Lambertian{Color(0.5f)}, Color(0.f)}});
    const Vec3 p(0.25f * scale, 0.25f * scale, 0.f);
    const Vec3 o = scene.spawn_origin(p, Vec3(0, 0, 1));
    CHECK(o.z > 0.f);
    CHECK(o.z < 1e-3f * scale);
    SurfaceHit hit;
    // A grazing ray leaving the surface must not hit it again.
    CHECK(!scene.intersect(Ray{o, normalize(Vec3(1.f, 0.f, 1e-3f))}, hit));
  }
}

TEST_CASE("camera_looks_along_forward_with_row_zero_on_top") {
  const PinholeCamera cam(Vec3(0, 0, 0), Vec3(0, 0, 1), Vec3(0, 1, 0), 90.f, 100, 50);
  const Ray centre = cam.generate_ray(50.f, 25.f);
  CHECK_NEAR(centre.d.z, 1.f, 1e-6f);
  CHECK(cam.generate_ray(50.f, 0.f).d.y > 0.f);    // top row looks up
  CHECK(cam.generate_ray(100.f, 25.f).d.x < 0.f);  // right edge is -x (right = forward x up)
  CHECK_NEAR(cam.generate_ray(100.f, 25.f).d.x, -std::sqrt(0.5f), 1e-6f);
}

TEST_CASE("occlusion_filter_ignores_chosen_hits") {
  // Triangles at z = 0 (prim 0) and z = -1 (prim 1); the filter ignores prim 0.
  const EmbreeAccel accel({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1, 1, 0, -1, 0, 1, -1}, {0, 1, 2, 3, 4, 5});
  const HitFilter ignore_first{[](const void*, uint32_t prim, float) { return prim == 0; }, nullptr};
  const Ray to_first{{0.2f, 0.2f, 1.f}, {0, 0, -1}, 1.5f}, to_second{{0.2f, 0.2f, 1.f}, {0, 0, -1}, 2.5f};
  CHECK(accel.occluded(to_first));
  CHECK(!accel.occluded(to_first, &ignore_first));
  CHECK(accel.occluded(to_second, &ignore_first));
}

TEST_CASE("visibility_is_blocked_by_a_wall_touching_the_target_surface") {
  // Floor y = 0 as two unit squares split at x = 1, and a wall square x = 1 standing on the
  // split: a floor point just past the wall is hidden from a point left of it, however close
  // it lies to the wall.
  const Material m{Lambertian{Color(0.5f)}, Color(0.f)};
  const Scene scene({0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1,    // left floor  0-3
                     1, 0, 0, 2, 0, 0, 2, 0, 1, 1, 0, 1,    // right floor 4-7
                     1, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1},   // wall        8-11
                    {0, 3, 2, 0, 2, 1,      // prims 0, 1 (normal +y)
                     4, 7, 6, 4, 6, 5,      // prims 2, 3 (normal +y)
                     8, 9, 10, 8, 10, 11},  // prims 4, 5
                    {0, 0, 0, 0, 0, 0}, {m});
  const Vec3 left(0.5f, 0.5f, 0.5f), right(1.5f, 0.5f, 0.5f);
  for (const float dx : {1e-2f, 1e-3f, 1e-4f, 1e-5f}) {  // the old end margin (1e-4) leaked at 1e-5
    const Vec3 target(1.f + dx, 0.f, 0.5f);  // on prim 2
    CHECK(!scene.visible(left, Vec3(1, 0, 0), target, 2));
    CHECK(scene.visible(right, Vec3(-1, 0, 0), target, 2));
  }
  CHECK(scene.visible(left, Vec3(1, 0, 0), Vec3(0.9f, 0.f, 0.5f), 1));
}

TEST_CASE("visibility_from_and_to_points_on_the_edge_where_two_walls_meet") {
  // The floor y = 0 (prims 0, 1) and the wall x = 0 (prims 2, 3) meet along the z axis, as the
  // walls of a furnace do; a back wall z = 1 (prims 4, 5) faces them. A point on that edge
  // lies in both planes. A segment from the back wall to a target on the edge reaches the
  // floor's plane only at its end, where Embree reported the floor (t = 1); a segment from a
  // path vertex on the edge, offset along the wall's normal, starts in the floor's plane, where
  // Embree reported the floor (t = 0). Both lost light in a furnace (issue 18). A wall z = 0.95
  // standing between still blocks them all, and so does the floor for a point below it: the
  // edge's wall is reached from there only through the floor (a closed cell's inner edge seen
  // from outside, which leaked while the target's plane alone was asked). That last case, a
  // segment reaching the floor exactly on its boundary edge, holds in Embree's robust mode
  // only: its fast mode (Mitsuba 3's default) let 741 of these 1521 through.
  const Material m{Lambertian{Color(0.5f)}, Color(0.f)};
  const std::vector<float> room{0, 0, 0, 0, 0, 1, 1, 0, 1, 1, 0, 0,   // floor, normal +y
                                0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1,   // wall x = 0, normal +x
                                0, 0, 1, 0, 1, 1, 1, 1, 1, 1, 0, 1};  // back wall z = 1, normal -z
  const std::vector<uint32_t> quads{0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 8, 9, 10, 8, 10, 11};
  std::vector<float> walled = room;
  walled.insert(walled.end(), {0, 0, 0.95f, 1, 0, 0.95f, 1, 1, 0.95f, 0, 1, 0.95f});
  std::vector<uint32_t> walled_quads = quads;
  walled_quads.insert(walled_quads.end(), {12, 13, 14, 12, 14, 15});
  for (const bool robust : {false, true}) {
    CAPTURE(robust);
    const Scene open(room, quads, {0, 0, 0, 0, 0, 0}, {m}, {}, {}, {}, robust);
    const Scene blocked(walled, walled_quads, {0, 0, 0, 0, 0, 0, 0, 0}, {m}, {}, {}, {}, robust);
    int reached = 0, hidden = 0, tried = 0, hidden_below = 0, tried_below = 0;
    for (int i = 1; i < 40; ++i) {
      for (int j = 1; j < 40; ++j) {
        const Vec3 edge(0.f, 0.f, 0.0237f * static_cast<float>(j) + 0.001f * static_cast<float>(i % 7));
        // On the back wall's first triangle (y > x), prim 4.
        const Vec3 back(0.05f + 0.005f * static_cast<float>(i), 0.3f + 0.015f * static_cast<float>(j), 1.f);
        tried += 2;
        reached += open.visible(back, Vec3(0, 0, -1), edge, 3);  // to the edge, on the wall's prim 3
        reached += open.visible(edge, Vec3(1, 0, 0), back, 4, 3);  // from the edge, a vertex on prim 3
        hidden += !blocked.visible(back, Vec3(0, 0, -1), edge, 3);
        hidden += !blocked.visible(edge, Vec3(1, 0, 0), back, 4, 3);
        const Vec3 below(0.3f + 0.0171f * static_cast<float>(i), -0.5f, 0.0123f * static_cast<float>(j));
        hidden_below += !open.visible(below, Vec3(0, -1, 0), edge, 3);
        ++tried_below;
      }
    }
    CHECK(hidden == tried);
    CHECK(reached == tried);
    if (robust) CHECK(hidden_below == tried_below);
  }
}

TEST_CASE("a_ray_leaving_the_plane_it_starts_in_does_not_hit_that_plane_at_t_zero") {
  // Two walls meeting at the edge y = 0, z = 0: the floor z = 0 (normal +z) and the wall
  // y = 0 (normal +y). A ray from the edge, offset along the floor's normal only, starts in the
  // wall's plane; going into the room (+y, +z) it must not hit the wall at t = 0 (issue 18: a
  // camera path continued from there along the wall and left a closed cell).
  const Material white{Lambertian{Color(0.5f)}, Color(0.f)};
  const Scene scene({0, 0, 0, 4, 0, 0, 4, 4, 0, 0, 4, 0,     // floor
                     0, 0, 0, 0, 0, 4, 4, 0, 4, 4, 0, 0},  // wall y = 0
                    {0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7}, {0, 0, 0, 0}, {white});
  const Vec3 on_edge(2.f, 0.f, 0.f);
  const Ray ray{scene.spawn_origin(on_edge, Vec3(0, 0, 1)), normalize(Vec3(0.f, 1.f, 1.f))};
  CHECK(ray.o.y == 0.f);  // in the wall's plane
  SurfaceHit hit;
  CHECK_FALSE(scene.intersect(ray, hit));  // nothing else in the room
  // The control: a ray into the wall from the room still hits it.
  CHECK(scene.intersect(Ray{Vec3(2.f, 1.f, 1.f), Vec3(0.f, -1.f, 0.f)}, hit));
  CHECK(hit.t == doctest::Approx(1.f));
}

TEST_CASE("rays_from_the_eye_ignore_surfaces_within_its_clearance") {
  // A pinhole lying on a wall sees past it, as light tracing's connections to it do.
  const Material white{Lambertian{Color(0.5f)}, Color(0.f)};
  const Scene scene({0, 0, 0, 4, 0, 0, 4, 4, 0, 0, 4, 0}, {0, 1, 2, 0, 2, 3}, {0, 0}, {white});
  CHECK(scene.eye_clearance() == doctest::Approx(4e-6f));
  SurfaceHit hit;
  const Ray just_behind{Vec3(2.f, 2.f, -2e-6f), Vec3(0.f, 0.f, 1.f)};
  CHECK(scene.intersect(just_behind, hit));  // an ordinary ray hits the wall 2e-6 away
  CHECK_FALSE(scene.intersect(scene.eye_ray(just_behind), hit));
  // Connections to an eye 2e-6 behind the wall pass it; 1e-3 behind, they do not (the control).
  CHECK(scene.visible_point(Vec3(2.f, 2.f, 1.f), Vec3(0, 0, 1), Vec3(2.f, 2.f, -2e-6f)));
  CHECK_FALSE(scene.visible_point(Vec3(2.f, 2.f, 1.f), Vec3(0, 0, 1), Vec3(2.f, 2.f, -1e-3f)));
}

TEST_CASE("ray_packets_find_what_single_rays_find") {
  // Random rays inside the closed box (some lanes inactive, one ray Embree would refuse) and
  // shadow queries between random points of its walls and the emitter: each lane of a packet
  // must equal the single-ray query, bit for bit.
  const Scene scene = closed_box();
  IndependentSampler sampler(3, 0, 0);
  for (int round = 0; round < 64; ++round) {
    RayPacket rays;
    Scene::ShadowPacket shadows;
    Vec3 p0s[RayPacket::kLanes], n0s[RayPacket::kLanes];
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      const Vec3 o{0.1f + 0.8f * sampler.next_1d(), 0.1f + 0.8f * sampler.next_1d(), 0.1f + 0.8f * sampler.next_1d()};
      const Vec3 d = normalize(Vec3{sampler.next_1d() - 0.5f, sampler.next_1d() - 0.5f, sampler.next_1d() - 0.5f});
      rays.set(i, Ray{o, i == 7 ? Vec3{2e19f, 0.f, 0.f} : d});
      rays.active[i] = i % 5 == 3 ? 0 : 1;
      const uint32_t origin = static_cast<uint32_t>(sampler.next_1d() * 12.f);
      const Vec3 p0 = scene.vertex(origin, 0) * 0.25f + scene.vertex(origin, 1) * 0.35f + scene.vertex(origin, 2) * 0.4f;
      const Vec3 n0 = scene.normal(origin), p1{0.45f + 0.1f * sampler.next_1d(), 0.95f, 0.45f + 0.1f * sampler.next_1d()};
      p0s[i] = p0, n0s[i] = n0;
      const Vec3 o0 = scene.shadow_origin(p0, n0, p1);
      shadows.o0x[i] = o0.x, shadows.o0y[i] = o0.y, shadows.o0z[i] = o0.z;
      shadows.p1x[i] = p1.x, shadows.p1y[i] = p1.y, shadows.p1z[i] = p1.z;
      shadows.target[i] = 12, shadows.origin[i] = origin, shadows.active[i] = rays.active[i];
    }
    HitPacket hits;
    scene.intersect(rays, hits);
    int32_t seen[RayPacket::kLanes];
    packet_visible(scene, shadows, seen);
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      SurfaceHit hit;
      const bool found = rays.active[i] != 0 && scene.intersect(rays.ray(i), hit);
      CHECK(found == (hits.prim[i] != RayHit::kNoHit));
      if (found) {
        CHECK(hits.prim[i] == hit.prim);
        CHECK(hits.t[i] == hit.t);
      }
      const bool visible = rays.active[i] != 0 && scene.visible(p0s[i], n0s[i],
                                                                  {shadows.p1x[i], shadows.p1y[i], shadows.p1z[i]}, 12,
                                                                  shadows.origin[i]);
      CHECK(visible == (seen[i] != 0));
    }
  }
}

TEST_CASE("ray_packets_of_every_width_find_the_same") {
  // Where the CPU lacks Embree's 16-wide queries, packets go as two of 8 or lane by lane: the
  // same hits and occlusion as the 16-wide queries (the narrower widths forced here).
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1, 1, 0, -1, 0, 1, -1};
  const std::vector<uint32_t> t = {0, 1, 2, 3, 4, 5};
  const HitFilter ignore_first{[](const void*, uint32_t prim, float) { return prim == 0; }, nullptr};
  const HitFilter* filters[RayPacket::kLanes] = {};
  RayPacket rays;
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    const float x = 0.05f * static_cast<float>(i);
    rays.set(i, Ray{{x, 0.1f, 1.f}, {0.f, 0.f, -1.f}, i % 3 == 0 ? 1.5f : 2.5f});
    rays.active[i] = i == 5 || i >= 12 ? 0 : 1;  // the second half of 8 lanes partly active
    filters[i] = i % 2 == 0 ? &ignore_first : nullptr;
  }
  const EmbreeAccel widest(p, t);
  HitPacket a;
  int32_t blocked_a[RayPacket::kLanes];
  widest.intersect(rays, a);
  widest.occluded(rays, filters, blocked_a);
  for (const int width : {8, 1}) {
    const EmbreeAccel narrow(p, t, true, width);
    HitPacket b;
    int32_t blocked_b[RayPacket::kLanes];
    narrow.intersect(rays, b);
    narrow.occluded(rays, filters, blocked_b);
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      CHECK(a.prim[i] == b.prim[i]);
      if (a.prim[i] != RayHit::kNoHit) CHECK(a.t[i] == b.t[i]);
      CHECK(blocked_a[i] == blocked_b[i]);
      CHECK(blocked_a[i] == (rays.active[i] != 0 && narrow.occluded(rays.ray(i), filters[i])));
    }
  }
}

TEST_CASE("in_place_packets_find_what_copied_packets_find") {
  // RayHit16 in place (Embree's own layout on the 16-wide queries, copied on the narrower ones):
  // the hits and the unfiltered occlusion of the copying queries; a lane Embree refuses (a
  // negative tmax) counts as blocked and misses.
  const std::vector<float> p = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, -1, 1, 0, -1, 0, 1, -1};
  const std::vector<uint32_t> t = {0, 1, 2, 3, 4, 5};
  RayPacket rays;
  alignas(64) int32_t active[RayPacket::kLanes];
  for (int i = 0; i < RayPacket::kLanes; ++i) {
    const float x = 0.05f * static_cast<float>(i);
    rays.set(i, Ray{{i == 7 ? 3e19f : x, 0.1f, 1.f}, {0.f, 0.f, -1.f}, i % 3 == 0 ? 1.5f : 2.5f, i == 4 ? 1.2f : 0.f});
    rays.active[i] = active[i] = i == 5 || i >= 12 ? 0 : -1;
  }
  const auto in_place = [&] {
    RayHit16 packet;
    for (int i = 0; i < RayPacket::kLanes; ++i) packet.set(i, rays.ray(i));
    return packet;
  };
  for (const int width : {16, 8, 1}) {
    const EmbreeAccel accel(p, t, true, width);
    HitPacket hits;
    int32_t blocked[RayPacket::kLanes];
    accel.intersect(rays, hits);
    accel.occluded(rays, nullptr, blocked);
    RayHit16 closest = in_place(), shadow = in_place();
    accel.intersect(active, closest);
    accel.occluded(active, shadow);
    for (int i = 0; i < RayPacket::kLanes; ++i) {
      CHECK(closest.prim[i] == hits.prim[i]);
      if (hits.prim[i] != RayHit::kNoHit) CHECK((closest.tmax[i] == hits.t[i] && closest.u[i] == hits.u[i]));
      CHECK((active[i] != 0 && shadow.tmax[i] < 0.f) == (blocked[i] != 0));
    }
    CHECK(blocked[7] == 1);
  }
}

TEST_CASE("coherent_packets_find_what_incoherent_packets_find") {
  // Camera rays traced as a coherent packet (Embree's frustum traversal, the path tracer's camera
  // rays) find the same hits, to the bit, as the same packet traced ray by ray: a finely
  // tessellated bumpy surface (2 x 48 x 48 triangles) and two large triangles behind it; packets
  // of 16 jittered samples of one pixel (the path tracer's) and of rows of 16 pixels across the
  // view (mixed direction octants at its centre), some lanes inactive, in robust and fast mode,
  // 16 and 8 wide.
  constexpr int kGrid = 48;
  std::vector<float> p;
  std::vector<uint32_t> t;
  for (int j = 0; j <= kGrid; ++j) {
    for (int i = 0; i <= kGrid; ++i) {
      const float x = -2.f + 4.f * static_cast<float>(i) / kGrid, y = -2.f + 4.f * static_cast<float>(j) / kGrid;
      p.insert(p.end(), {x, y, -3.f + 0.3f * std::sin(3.f * x) * std::cos(2.f * y)});
    }
  }
  for (uint32_t j = 0; j < kGrid; ++j) {
    for (uint32_t i = 0; i < kGrid; ++i) {
      const uint32_t a = j * (kGrid + 1) + i, b = a + 1, c = a + kGrid + 1, d = c + 1;
      t.insert(t.end(), {a, b, d, a, d, c});
    }
  }
  const auto base = static_cast<uint32_t>(p.size() / 3);
  p.insert(p.end(), {-9, -9, -5, 9, -9, -5, 0, 9, -5, -9, -9, -1, 9, -9, -1, -9, -5, -1});
  t.insert(t.end(), {base, base + 1, base + 2, base + 3, base + 4, base + 5});
  const PinholeCamera camera({0, 0, 0}, {0, 0, -1}, {0, 1, 0}, 60.f, 64, 64);
  IndependentSampler jitter(7, 0, 0);
  for (const bool robust : {true, false}) {
    for (const int width : {16, 8}) {
      const EmbreeAccel accel(p, t, robust, width);
      size_t hits = 0, differences = 0;
      for (int row = 0; row < 64; row += 3) {
        for (int x0 = 0; x0 < 64; x0 += 8) {
          const bool one_pixel = x0 % 16 != 0;  // else a row of 16 pixels from x0
          alignas(64) int32_t active[RayHit16::kLanes];
          RayHit16 rays{};
          for (int i = 0; i < RayHit16::kLanes; ++i) {
            const Point2 u = jitter.next_2d();
            const float x = static_cast<float>(one_pixel ? x0 : x0 + i) + u.u;
            rays.set(i, camera.generate_ray(x, static_cast<float>(row) + u.v));
            active[i] = (row + i) % 7 == 0 ? 0 : -1;
          }
          RayHit16 coherent = rays, incoherent = rays, shifted = rays;
          accel.intersect(active, coherent, Coherence::kCoherent);
          accel.intersect(active, incoherent, Coherence::kIncoherent);
          // Control: the lanes' rays rotated by one lane; the comparison must see that.
          for (int i = 0; i < RayHit16::kLanes; ++i) {
            const int k = (i + 1) % RayHit16::kLanes;
            shifted.dx[i] = rays.dx[k], shifted.dy[i] = rays.dy[k], shifted.dz[i] = rays.dz[k];
          }
          accel.intersect(active, shifted, Coherence::kCoherent);
          for (int i = 0; i < RayHit16::kLanes; ++i) {
            CHECK(coherent.prim[i] == incoherent.prim[i]);
            if (incoherent.prim[i] == RayHit::kNoHit) continue;
            ++hits;
            CHECK((coherent.tmax[i] == incoherent.tmax[i] && coherent.u[i] == incoherent.u[i] &&
                   coherent.v[i] == incoherent.v[i]));
            differences += shifted.prim[i] != incoherent.prim[i] || shifted.tmax[i] != incoherent.tmax[i];
          }
        }
      }
      CHECK(hits > 1000);
      CHECK(differences > hits / 2);
    }
  }
}

namespace {
// The unit box seen from inside, a light quad (prims 12, 13) at y = 0.95 facing down, a small
// horizontal occluder (prim 14) 0.02 below the light's middle, a tilted triangle (prim 15) by the
// light's edge, and a thin wall (prims 16, 17) standing on the floor. `lit`: the quad emits;
// `robust`: Embree's robust mode.
Scene lit_box(bool lit, bool robust = true) {
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  std::vector<uint32_t> t = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                             3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
  const auto add = [&](std::initializer_list<float> xyz, std::initializer_list<uint32_t> corners) {
    const uint32_t base = static_cast<uint32_t>(p.size() / 3);
    p.insert(p.end(), xyz);
    for (const uint32_t c : corners) t.push_back(base + c);
  };
  add({0.3f, 0.95f, 0.3f, 0.7f, 0.95f, 0.3f, 0.7f, 0.95f, 0.7f, 0.3f, 0.95f, 0.7f}, {0, 1, 2, 0, 2, 3});
  add({0.35f, 0.93f, 0.35f, 0.65f, 0.93f, 0.35f, 0.5f, 0.93f, 0.65f}, {0, 1, 2});
  add({0.75f, 0.9f, 0.3f, 0.85f, 0.97f, 0.5f, 0.75f, 0.9f, 0.7f}, {0, 1, 2});
  add({0.6f, 0.f, 0.1f, 0.6f, 0.f, 0.9f, 0.6f, 0.6f, 0.9f, 0.6f, 0.6f, 0.1f}, {0, 1, 2, 0, 2, 3});
  std::vector<uint32_t> m(t.size() / 3, 0);
  m[12] = m[13] = 1;
  return Scene(std::move(p), std::move(t), std::move(m),
               {Material{Lambertian{Color(0.5f)}, Color(0.f)},
                Material{Lambertian{Color(0.2f)}, Color(lit ? 5.f : 0.f)}},
               {}, {}, {}, robust);
}
}  // namespace

TEST_CASE("emitter_clearance_is_a_lower_bound_on_the_distance_to_other_surfaces") {
  const Scene scene = lit_box(true);
  const std::vector<float> c = emitter_clearances(scene);
  // The occluder 0.02 below is the nearest; the quad's other half (coplanar) does not count.
  CHECK_NEAR(c[12], 0.02f, 1e-6f);
  CHECK_NEAR(c[13], 0.02f, 1e-6f);
  CHECK(c[12] <= 0.02f);
  for (uint32_t prim = 0; prim < c.size(); ++prim) {
    if (prim != 12 && prim != 13) CHECK(c[prim] == 0.f);  // not emitters
  }
  // Against sampled points: no point of another surface closer to the light than its clearance.
  IndependentSampler sampler(5, 0, 0);
  const auto point_on = [&](uint32_t prim) {
    const float u = sampler.next_1d(), v = sampler.next_1d(), su = std::sqrt(u);
    return scene.vertex(prim, 0) * (1.f - su) + scene.vertex(prim, 1) * (su * (1.f - v)) +
           scene.vertex(prim, 2) * (su * v);
  };
  float nearest = 1e30f;
  for (int i = 0; i < 20000; ++i) {
    const uint32_t other = 14 + static_cast<uint32_t>(sampler.next_1d() * 4.f) % 4;
    nearest = std::min(nearest, length(point_on(12 + i % 2) - point_on(other)));
  }
  CHECK(nearest >= c[12]);
  // Controls: a light touching a wall, or too many pairs to bound, gets 0.
  CHECK(emitter_clearances(scene, 1)[12] == 0.f);
  const Scene touching({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1}, {0, 1, 2, 3, 4, 5}, {1, 0},
                       {Material{Lambertian{Color(0.5f)}, Color(0.f)}, Material{Lambertian{Color(0.2f)}, Color(5.f)}});
  CHECK(emitter_clearances(touching)[0] == 0.f);
}

TEST_CASE("visibility_short_of_a_clear_target_equals_the_filtered_answer") {
  // The same geometry twice: with the light emitting, shadow rays to it stop short by half its
  // clearance without the filter (surface_clearance.h); without, they are filtered to t = 1.
  // Every answer must agree, from random points of every surface to random points of the
  // light, singly and in packets. The occluder 0.02 under the light sets the clearance: a stop
  // any nearer the light would miss it (as a stop at 1 - clearance / length would, by rounding).
  // In Embree's fast mode too (bench_peers' "fast"), whose misses must not differ either.
  for (const bool robust : {true, false}) {
    CAPTURE(robust);
    const Scene lit = lit_box(true, robust), unlit = lit_box(false, robust);
    IndependentSampler sampler(9, 0, 0);
    int visible = 0, hidden = 0, differ = 0;
    for (int round = 0; round < 600; ++round) {
      Scene::ShadowPacket q;
      Vec3 p0s[RayPacket::kLanes], n0s[RayPacket::kLanes], p1s[RayPacket::kLanes];
      for (int i = 0; i < RayPacket::kLanes; ++i) {
        const uint32_t origin = static_cast<uint32_t>(sampler.next_1d() * 18.f) % 18;
        const uint32_t target = 12 + (i & 1);
        const float a = sampler.next_1d(), b = sampler.next_1d() * (1.f - a);
        p0s[i] = lit.vertex(origin, 0) * (1.f - a - b) + lit.vertex(origin, 1) * a + lit.vertex(origin, 2) * b;
        n0s[i] = lit.normal(origin);
        const float u = sampler.next_1d(), v = sampler.next_1d() * (1.f - u);
        p1s[i] = lit.vertex(target, 0) * (1.f - u - v) + lit.vertex(target, 1) * u + lit.vertex(target, 2) * v;
        const Vec3 o0 = lit.shadow_origin(p0s[i], n0s[i], p1s[i]);
        q.o0x[i] = o0.x, q.o0y[i] = o0.y, q.o0z[i] = o0.z;
        q.p1x[i] = p1s[i].x, q.p1y[i] = p1s[i].y, q.p1z[i] = p1s[i].z;
        q.target[i] = target, q.origin[i] = origin, q.active[i] = i % 7 == 6 ? 0 : 1;
      }
      int32_t seen[RayPacket::kLanes];
      packet_visible(lit, q, seen);
      for (int i = 0; i < RayPacket::kLanes; ++i) {
        if (q.active[i] == 0) {
          CHECK(seen[i] == 0);
          continue;
        }
        const bool short_stop = lit.visible(p0s[i], n0s[i], p1s[i], q.target[i], q.origin[i]);
        const bool filtered = unlit.visible(p0s[i], n0s[i], p1s[i], q.target[i], q.origin[i]);
        differ += short_stop != filtered || short_stop != (seen[i] != 0) ? 1 : 0;
        visible += filtered ? 1 : 0;
        hidden += filtered ? 0 : 1;
      }
    }
    CHECK(differ == 0);
    CHECK(visible > 1000);
    CHECK(hidden > 1000);
  }
}
