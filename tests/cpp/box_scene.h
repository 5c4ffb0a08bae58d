// A scene the C++ tests share: the unit cube seen from inside (normals inward), reflectance
// (0.7, 0.5, 0.3), with an emitting triangle (radiance 5, reflectance 0.2) at y = 0.95 facing down.
#pragma once
#include <utility>
#include <vector>

#include "geometry/scene.h"

namespace dualight {

inline Scene closed_box() {
  std::vector<float> p = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  std::vector<uint32_t> t = {0, 1, 2, 0, 2, 3, 4, 6, 5, 4, 7, 6, 0, 4, 5, 0, 5, 1,
                             3, 2, 6, 3, 6, 7, 0, 3, 7, 0, 7, 4, 1, 5, 6, 1, 6, 2};
  const uint32_t base = static_cast<uint32_t>(p.size() / 3);
  for (const float v : {0.4f, 0.95f, 0.4f, 0.6f, 0.95f, 0.4f, 0.5f, 0.95f, 0.6f}) p.push_back(v);
  for (const uint32_t i : {base, base + 1, base + 2}) t.push_back(i);
  std::vector<uint32_t> m(t.size() / 3, 0);
  m.back() = 1;
  return Scene(std::move(p), std::move(t), std::move(m),
               {Material{Lambertian{Color(0.7f, 0.5f, 0.3f)}, Color(0.f)},
                Material{Lambertian{Color(0.2f)}, Color(5.f)}});
}

}  // namespace dualight
