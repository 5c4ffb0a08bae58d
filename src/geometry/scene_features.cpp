#include "geometry/scene_features.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <unordered_set>

namespace dualight {

namespace {

// Above this many plane-vertex tests the enclosure is not checked (and not assumed): about 50 ms.
constexpr uint64_t kMaxConvexityTests = 50'000'000;

uint64_t float_bits(float x) {
  uint32_t b = 0;
  x = x == 0.f ? 0.f : x;  // -0 and +0 are one position
  std::memcpy(&b, &x, sizeof b);
  return b;
}

struct PositionKey {
  uint64_t xy, z;
  bool operator==(const PositionKey& o) const { return xy == o.xy && z == o.z; }
};
struct PositionHash {
  size_t operator()(const PositionKey& k) const { return std::hash<uint64_t>()(k.xy * 0x9E3779B97F4A7C15ull ^ k.z); }
};

// Vertex ids merged by exact position: meshes often repeat a corner once per face.
std::vector<uint32_t> merged_vertex_ids(const std::vector<float>& positions) {
  const size_t n = positions.size() / 3;
  std::unordered_map<PositionKey, uint32_t, PositionHash> first;
  first.reserve(n);
  std::vector<uint32_t> id(n);
  for (size_t v = 0; v < n; ++v) {
    const PositionKey key{float_bits(positions[3 * v]) << 32 | float_bits(positions[3 * v + 1]),
                          float_bits(positions[3 * v + 2])};
    id[v] = first.emplace(key, static_cast<uint32_t>(v)).first->second;
  }
  return id;
}

bool is_closed(const std::vector<uint32_t>& triangles, const std::vector<uint32_t>& id) {
  // Each directed edge must appear once, and its reverse once: a consistently oriented manifold.
  std::unordered_map<uint64_t, int> directed;
  directed.reserve(triangles.size());
  for (size_t t = 0; t < triangles.size(); t += 3) {
    for (int c = 0; c < 3; ++c) {
      const uint64_t a = id[triangles[t + c]], b = id[triangles[t + (c + 1) % 3]];
      if (++directed[a << 32 | b] > 1) return false;
    }
  }
  for (const auto& [edge, count] : directed) {
    const uint64_t reverse = (edge & 0xFFFFFFFFull) << 32 | edge >> 32;
    if (directed.find(reverse) == directed.end()) return false;
  }
  return true;
}

}  // namespace

bool SceneFeatures::encloses(const Vec3& p) const {
  if (!convex_enclosure) return false;
  return std::all_of(planes.begin(), planes.end(),
                     [&](const Plane& pl) { return dot(pl.n, p) - pl.d > tolerance; });
}

SceneFeatures compute_scene_features(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                                     const std::vector<Vec3>& normals, const MaterialFeatures& materials,
                                     uint64_t emitter_triangles) {
  SceneFeatures f;
  f.specular = materials.specular;
  f.dielectric = materials.transmission;
  f.diffuse_only = materials.all_diffuse;
  f.mixed_delta = materials.mixed_delta;
  f.emitter_triangles = emitter_triangles;
  const std::vector<uint32_t> id = merged_vertex_ids(positions);
  f.closed = is_closed(triangles, id);

  float extent = 0.f;
  for (const float x : positions) extent = std::max(extent, std::abs(x));
  // Float rounding of a vertex's distance to a plane through points of this size.
  f.tolerance = 1e-5f * std::max(extent, 1e-30f);

  // Distinct planes (a tessellated wall is one plane), by rounded normal and offset.
  std::unordered_set<PositionKey, PositionHash> seen;
  for (size_t t = 0; t < normals.size(); ++t) {
    const Vec3 n = normals[t];
    const uint32_t v0 = triangles[3 * t];
    const float d = dot(n, Vec3(positions[3 * v0], positions[3 * v0 + 1], positions[3 * v0 + 2]));
    // Rounded to `step`; values too large to round (tiny steps) keep their exact bits.
    const auto q = [](float x, float step) {
      const double v = static_cast<double>(x) / step;
      return std::abs(v) < 9e18 ? static_cast<uint64_t>(std::llround(v)) : float_bits(x);
    };
    const PositionKey key{q(n.x, 1e-6f) << 42 ^ q(n.y, 1e-6f) << 21 ^ q(n.z, 1e-6f), q(d, f.tolerance)};
    if (seen.insert(key).second) f.planes.push_back({n, d});
  }
  std::vector<Vec3> vertices;
  for (size_t v = 0; v < id.size(); ++v) {
    if (id[v] == v) vertices.emplace_back(positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]);
  }
  // Non-convex scenes usually fail within the first planes; a budget bounds the convex ones.
  uint64_t tests = 0;
  f.convex_enclosure = true;
  for (const Plane& pl : f.planes) {
    if (tests + vertices.size() > kMaxConvexityTests) {
      f.convex_enclosure = false;
      f.planes.clear();
      return f;
    }
    tests += vertices.size();
    const bool all_in_front = std::all_of(vertices.begin(), vertices.end(),
                                          [&](const Vec3& v) { return dot(pl.n, v) - pl.d >= -f.tolerance; });
    if (!all_in_front) {
      f.convex_enclosure = false;
      break;
    }
  }
  f.convexity_checked = true;
  if (!f.convex_enclosure) f.planes.clear();
  return f;
}

}  // namespace dualight
