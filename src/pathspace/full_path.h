// Complete light paths x_0 ... x_k for path-space Metropolis light transport [Veach 1997, ch. 11]:
// x_0 on an emitter, x_k the pinhole camera, k the number of segments. The functions here give a
// path's measurement contribution f(x) and the area densities with which either side's random
// walk generates each vertex; the mutations combine those into transition densities.
//
// Specular (Dirac) vertices: a delta BSDF is coef * delta in projected solid angle at the vertex,
// in the form seen from the camera side (Radiance mode). f keeps every geometry term and uses coef
// in place of the BSDF; a walk from the camera side samples the vertex's lobe with probability
// prob, density prob * G (the same delta dropped); a walk from the light side has the delta in
// its own (Importance) form, which is (coef_radiance / coef_importance) times the camera side's,
// so its density is prob * that ratio * G. With this convention the deltas cancel in every
// ratio f / T that the acceptance probability takes [Veach 1997, sec. 5.2 and 11.4.3].
#pragma once
#include "pathspace/connect.h"
#include "pathspace/path.h"
#include "pathspace/render_stats.h"

namespace dualight {

inline bool is_specular(const Vertex& v) { return v.type == VertexType::Surface && is_delta(v.material->bsdf); }

// The Dirac lobe a specular vertex uses between the directions to the camera side and to the
// light side (world, unit): its BSDF's delta_lobe (bsdf_sample.h) in v's frame.
DeltaLobe specular_lobe(const Vertex& v, const Vec3& to_eye, const Vec3& to_light);

// The ideal direction of a specular vertex's lobe (`refraction` or reflection), leaving from the
// side `wo` points to; false under total internal reflection or for a mirror asked to refract.
bool specular_direction(const Vertex& v, const Vec3& wo, bool refraction, Vec3& wi);

// f(z) of the whole path, as its luminance f* and its colour per unit luminance (f / f*; f
// itself can be below float range: it is a density over up to k area measures, 1e-5 per
// segment in a scene modelled in millimetres). raster: the film position of z[k - 1]. f* is 0
// when z[0] does not emit towards z[1], a BSDF is 0 or z[k - 1] is outside the view. Visibility
// is not tested (mutations test the segments they make).
struct PathValue {
  Color color;        // f / f*
  double f_lum = 0.0;  // f*
};
PathValue path_contribution(const PinholeCamera& camera, const Path& z, Point2& raster);

// Area density with which the light side's walk generates z[i] (from z[i-1], having come from
// z[i-2]; i = 0: the emitter sample), and with which the camera side's walk generates z[i] (from
// z[i+1], having come from z[i+2]; from the camera when i + 1 = k). The mutations' camera-side
// walks end at surfaces (trace_vertex), never at a vertex at infinity: its camera-side density
// is 0, as a point light's. `forced`: the specular lobe
// was chosen, not sampled (perturbations follow the old path's lobes), so prob is 1.
double pdf_from_light(const Scene& scene, const Path& z, size_t i, bool forced = false);
double pdf_from_eye(const PinholeCamera& camera, const Path& z, size_t i, bool forced = false);

// The surface point a ray from `from` along unit d hits first, as a surface vertex (a ray that
// leaves the scene finds none). From a vertex at infinity the ray starts at `origin` on the
// distant disk (EmitterDirection::origin).
bool trace_vertex(const Scene& scene, const Vertex& from, const Vec3& d, Vertex& hit, TraceCounters& counters,
                  const Vec3& origin = {});


// Samples a scattering direction at surface vertex v arriving from direction wo (world, unit), as
// BSDF sampling in `mode` does; false when the BSDF absorbs.
bool sample_scatter(const Vertex& v, const Vec3& wo, TransportMode mode, Point2 u, Vec3& wi);

}  // namespace dualight
