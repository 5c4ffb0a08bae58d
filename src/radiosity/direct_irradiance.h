// The first shot of emitters without a surface for radiosity: the irradiance each patch
// receives directly from point, spot and directional lights and from the environment, with
// Embree visibility, averaged over the patch [Cohen and Wallace 1993, sec. 2.3: a point source
// enters the radiosity system as the reflected part of its direct illumination,
// E_i = rho_i H_i; a sky likewise, its irradiance an integral over the hemisphere, estimated
// by multiple importance sampling, Veach 1997 sec. 9.2]. The patches scene holds one triangle
// per patch and these emitters in its emitter list.
#pragma once
#include <cstdint>
#include <vector>

#include "core/render_control.h"
#include "core/rng.h"
#include "geometry/scene.h"

namespace dualight {

// The scene's emitters without a surface, and how their irradiance is averaged over a triangle:
// at the centroids of an n x n split of it (n = points_per_axis, n^2 equal-area parts); the
// environment's at each point from env_strata^2 stratified pairs of a cosine-weighted and an
// environment-sampled direction. Throws std::invalid_argument on counts outside [1, 64].
class FirstShot {
 public:
  FirstShot(const Scene& scene, int points_per_axis, int env_strata);
  // Whether the scene has such emitters (else every irradiance is 0).
  bool empty() const { return delta_lights_.empty() && environment_ == nullptr; }
  // Mean irradiance over triangle v (unit normal n; one-sided: its front) with visibility; rng
  // shifts the environment's strata.
  Color mean_irradiance(const Vec3 v[3], const Vec3& n, Pcg32& rng) const;

 private:
  const Scene& scene_;
  std::vector<const Emitter*> delta_lights_;
  const Emitter* environment_ = nullptr;
  std::vector<Point2> grid_;
  int env_strata_;
};

// Mean irradiance over each patch from the emitters without a surface of `patches`, at the
// centroids of an n x n split of the patch (n = points_per_axis, n^2 equal-area parts); the
// environment's at each point from env_strata^2 stratified pairs of a cosine-weighted and an
// environment-sampled direction (random shifts from seed and the patch). Patches are
// one-sided: each takes light on its front (normal's) side only. `control` counts patches and
// can cancel (the rest stay 0).
std::vector<Color> direct_irradiance(const Scene& patches, int points_per_axis, int env_strata, uint64_t seed,
                                     int threads, RenderControl& control);

}  // namespace dualight
