// The first shot of delta emitters without a surface (point, spot and directional lights) for radiosity: the
// irradiance each patch receives directly from them, with Embree visibility, averaged over
// the patch [Cohen and Wallace 1993, sec. 2.3: a point source enters the radiosity system as
// the reflected part of its direct illumination, E_i = rho_i H_i]. The patches scene holds
// one triangle per patch and these emitters in its emitter list.
#pragma once
#include <vector>

#include "core/render_control.h"
#include "geometry/scene.h"

namespace dualight {

// Mean irradiance over each patch from the delta emitters (position or direction) of `patches`, estimated at
// the centroids of an n x n split of the patch (n = points_per_axis, n^2 equal-area parts).
// Patches are one-sided: each takes light on its front (normal's) side only.
// `control` counts patches and can cancel (the rest stay 0).
std::vector<Color> direct_irradiance(const Scene& patches, int points_per_axis, int threads,
                                     RenderControl& control);

}  // namespace dualight
