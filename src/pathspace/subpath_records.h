// Guide records from a finished subpath [Müller, Gross, Novák 2017, sec. 3.3; Vorba et al. 2014]:
// at each vertex that sampled a non-Dirac direction, the quantity that arrived back along it (the
// contributions of the vertices after it over the throughput there, guide_record.h), over the
// solid-angle density the direction was sampled with (the next vertex's pdf_fwd in solid angle
// again). The light tracer records importance this way from its particles' camera connections;
// guided BDPT records radiance on camera subpaths and importance on light subpaths from the
// MIS-weighted contributions of the strategies that used each vertex.
#pragma once
#include <cmath>
#include <vector>

#include "guiding/directional_quadtree.h"
#include "guiding/guide_record.h"
#include "pathspace/path.h"

namespace dualight {

// arrived[k]: what vertex k's strategies contributed (zero where none), as seen from the
// subpath's start. Vertex 0 (the camera, or the point on the emitter) records nothing: its
// direction is the camera's or the emitter's, not a BSDF's; a subpath needs three vertices to
// record anything.
inline void record_incident(const Path& path, const std::vector<Color>& arrived, TransportMode mode,
                            GuideRecords& out) {
  if (path.size() < 3) return;
  Color after(0.f);  // the contributions of vertices k + 1, k + 2, ...
  for (size_t k = path.size() - 1; k-- > 1;) {
    after += arrived[k + 1];
    const Vertex &v = path[k], &next = path[k + 1];
    if (v.delta || !(next.pdf_fwd > 0.f)) continue;
    Vec3 w;
    float pdf_w;
    if (next.at_infinity) {  // an environment a camera subpath escaped to: pdf_fwd is in solid angle
      w = next.p;
      pdf_w = next.pdf_fwd;
    } else {
      const Vec3 d = next.p - v.p;
      const float dist2 = dot(d, d);
      w = d / std::sqrt(dist2);
      pdf_w = next.pdf_fwd * dist2 / std::abs(dot(next.n, w));
    }
    const float pdf_bsdf = surface_pdf_w(v, v.wo, w, mode);
    // f |cos| (the shading-normal correction included), where beta is not 0.
    const auto fcos_of = [&](int c) { return v.beta[c] > 0.f ? next.beta[c] / v.beta[c] * pdf_w : 0.f; };
    const Color fcos(fcos_of(0), fcos_of(1), fcos_of(2));
    GuideRecord r;
    if (make_record(v.p, w, after, next.beta, fcos, pdf_bsdf, pdf_w, r)) out.push_back(r);
  }
}

}  // namespace dualight
