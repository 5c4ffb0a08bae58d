// Scene features: closed and convex enclosures, the point-in-enclosure test, and the specular flags.
#include <vector>

#include "check.h"
#include "geometry/scene.h"

using namespace dualight;

namespace {

// An axis-aligned box [0, 1]^3 as 12 triangles facing in (inward = true) or out, corners shared.
struct Mesh {
  std::vector<float> positions;
  std::vector<uint32_t> triangles;
};
Mesh box(bool inward, float lo = 0.f, float hi = 1.f) {
  Mesh m;
  for (int i = 0; i < 8; ++i) {
    m.positions.insert(m.positions.end(), {i & 1 ? hi : lo, i & 2 ? hi : lo, i & 4 ? hi : lo});
  }
  // Quads with outward right-hand normals: -x, +x, -y, +y, -z, +z.
  const uint32_t quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    const uint32_t a = q[0], b = inward ? q[3] : q[1], c = q[2], d = inward ? q[1] : q[3];
    m.triangles.insert(m.triangles.end(), {a, b, c, a, c, d});
  }
  return m;
}

Scene make(const Mesh& m, Bsdf bsdf = Lambertian{Color(0.5f)}) {
  const std::vector<uint32_t> material_of(m.triangles.size() / 3, 0);
  return Scene(m.positions, m.triangles, material_of, {Material{bsdf, Color(1.f)}});
}

}  // namespace

TEST_CASE("a_box_seen_from_inside_is_a_closed_convex_enclosure") {
  const Scene scene = make(box(true));
  const SceneFeatures& f = scene.features();
  CHECK((f.closed && f.convex_enclosure && f.convexity_checked && f.unoccluded() && f.all_diffuse()));
  CHECK(f.emitter_triangles == 12);
  CHECK(f.planes.size() == 6);  // two triangles per face, one plane
  CHECK(f.encloses(Vec3(0.5f, 0.5f, 0.5f)));
  CHECK(!f.encloses(Vec3(0.5f, 0.5f, 1.5f)));  // outside
  CHECK(!f.encloses(Vec3(0.5f, 0.5f, 1.0f)));  // on a wall: not strictly inside
}

TEST_CASE("a_box_seen_from_outside_is_closed_but_not_an_enclosure") {
  const Scene scene = make(box(false));
  const SceneFeatures& f = scene.features();
  CHECK((f.closed && !f.convex_enclosure && f.convexity_checked));
  CHECK(!f.encloses(Vec3(0.5f, 0.5f, 0.5f)));
}

TEST_CASE("a_block_inside_a_room_breaks_convexity") {
  Mesh room = box(true);
  const Mesh block = box(false, 0.4f, 0.6f);
  const auto offset = static_cast<uint32_t>(room.positions.size() / 3);
  room.positions.insert(room.positions.end(), block.positions.begin(), block.positions.end());
  for (const uint32_t i : block.triangles) room.triangles.push_back(i + offset);
  const Scene scene = make(room);
  const SceneFeatures& f = scene.features();
  CHECK((f.closed && !f.convex_enclosure));
}

TEST_CASE("an_open_box_is_convex_but_not_closed") {
  Mesh open = box(true);
  open.triangles.resize(open.triangles.size() - 6);  // drop the +z face
  const Scene scene = make(open);
  const SceneFeatures& f = scene.features();
  CHECK((!f.closed && f.convex_enclosure));
  CHECK(f.encloses(Vec3(0.5f, 0.5f, 5.f)));  // the enclosure is open towards +z
}

TEST_CASE("glass_makes_a_convex_enclosure_occluding") {
  const SceneFeatures mirror = make(box(true), Mirror{Color(1.f)}).features();  // a copy: the scene is a temporary
  CHECK((mirror.specular && !mirror.dielectric && mirror.unoccluded()));
  const SceneFeatures glass = make(box(true), Dielectric{1.5f}).features();
  CHECK((glass.specular && glass.dielectric && glass.convex_enclosure && !glass.unoccluded()));
}
