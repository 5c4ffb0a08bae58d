// What every emitter's sampling returns (lights/emitter.h): a point on it, a direction of
// emission, a light sample seen from a reference point. Densities include the scene's
// selection probability of the emitter.
#pragma once
#include <cstdint>

#include "core/sampling.h"
#include "core/vec3.h"

namespace dualight {

// A point on an emitter, with its area density (selection included).
struct EmitterPoint {
  Vec3 p, n;
  float pdf_a = 0.f;     // area density, or the probability of a point emitter's point
  uint32_t prim = 0;     // the scene triangle it lies on (when on_surface)
  bool on_surface = true;  // false: a point in free space (no cosine, no material there)
  // A point on the sphere at infinity: p = n = the unit direction from the scene towards it,
  // pdf_a a solid-angle density (or a direction's discrete probability).
  bool at_infinity = false;
  Point2 uv{0.f, 0.f};  // its surface coordinates where its radiance is a texture (else 0, unread)
};
// A direction of emission from an emitter point.
struct EmitterDirection {
  Vec3 w;             // unit
  float pdf_w = 0.f;  // solid-angle density; from infinity the planar density of `origin`
  Color beta;         // Le |cos| / (pdf_a pdf_w): the light subpath's throughput after it
  Vec3 origin;        // from infinity: the ray's start on the distant disk (lights/distant_disk.h)
};
// Next-event estimation: a point on the emitter seen from a reference point.
struct LightSample {
  Vec3 p, n;
  Vec3 wi;            // unit, from the reference point towards p
  float dist2 = 0.f;  // squared distance to p
  float pdf_w = 0.f;  // solid-angle density at the reference point (selection included)
  Color Le;                // radiance arriving from p
  uint32_t prim = 0;       // the emitting triangle (the shadow ray's target), when on_surface
  bool on_surface = true;  // false: p is in free space (the shadow ray ends at p)
};

}  // namespace dualight
