// What a scene holds, computed once when the Scene is built, so that estimators and solvers can
// skip work that cannot contribute (and say so in their statistics):
//   specular / dielectric   BSDFs with Dirac lobes, with transmission (MLT's caustic and
//   / all_diffuse           multi-chain perturbations need specular ones; radiosity needs all
//                           BSDFs diffuse reflectors), from the BSDFs' own flags;
//   closed                  every edge is shared by exactly two triangles, in opposite
//                           directions (a watertight, consistently oriented surface: no light
//                           leaves it);
//   convex_enclosure        every vertex lies on or in front of every triangle's plane. Then two
//                           points on the front sides of surfaces, or a front-side point and a
//                           point inside the enclosure (a camera), see each other whenever they
//                           face each other: the segment between them stays in the intersection
//                           of the front half-spaces, which no triangle's interior can cross.
//                           Shadow rays (and form-factor visibility rays) are then not needed.
#pragma once
#include <cstdint>
#include <vector>

#include "core/vec3.h"

namespace dualight {

struct Plane {
  Vec3 n;     // unit normal
  float d;    // dot(n, x) = d on the plane
};

// What the scene's materials are, from their flags (bsdf_flags.h).
struct MaterialFeatures {
  bool specular = false;      // some BSDF has a Dirac lobe
  bool transmission = false;  // some BSDF transmits (light can pass behind a surface)
  bool all_diffuse = true;    // every BSDF is a diffuse reflector only
  bool mixed_delta = false;   // some BSDF has Dirac and non-Dirac lobes (smooth plastic)
};

struct SceneFeatures {
  bool specular = false;    // some BSDF has a Dirac lobe (a mirror, glass)
  bool dielectric = false;  // some BSDF transmits (glass: light can pass behind a surface)
  bool diffuse_only = true;  // every BSDF is a diffuse reflector only (what radiosity solves)
  bool mixed_delta = false;  // some BSDF has Dirac and non-Dirac lobes (smooth plastic)
  bool closed = false;
  bool convex_enclosure = false;
  bool convexity_checked = false;  // false when the scene was too large to check (then not convex)
  uint64_t emitter_triangles = 0;
  std::vector<Plane> planes;  // the distinct triangle planes (for the enclosure test of a point)
  float tolerance = 0.f;      // distances below this count as "on the plane"

  bool all_diffuse() const { return diffuse_only; }
  // Whether any two path vertices that face each other are mutually visible: a convex enclosure
  // without glass (refraction would carry paths behind a surface, outside the enclosure).
  bool unoccluded() const { return convex_enclosure && !dielectric; }
  // Whether p lies strictly inside the convex enclosure (in front of every plane).
  bool encloses(const Vec3& p) const;
};

// positions: xyz per vertex; triangles: 3 indices each; normals: unit normal per triangle.
SceneFeatures compute_scene_features(const std::vector<float>& positions, const std::vector<uint32_t>& triangles,
                                     const std::vector<Vec3>& normals, const MaterialFeatures& materials,
                                     uint64_t emitter_triangles);

}  // namespace dualight
