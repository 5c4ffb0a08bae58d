// What an emitter is, as it reports itself (pbrt-v4's LightType, Mitsuba 3's EmitterFlags):
// whether its position or direction is a Dirac delta (no strategy but sampling the emitter can
// find such light: a path cannot hit a point light) and whether it sits on a surface.
#pragma once
#include <cstdint>

namespace dualight {

enum class EmitterFlags : uint8_t {
  None = 0,
  DeltaPosition = 1 << 0,   // a point: paths cannot hit it, only connect to it
  DeltaDirection = 1 << 1,  // one direction: connections to it carry nothing
  Surface = 1 << 2,         // emits from a scene surface, which paths can hit
  Infinite = 1 << 3,        // at infinity: rays that leave the scene see it
};

constexpr bool has_any(EmitterFlags f, EmitterFlags of) {
  return (static_cast<uint8_t>(f) & static_cast<uint8_t>(of)) != 0;
}
constexpr bool is_delta_position(EmitterFlags f) { return has_any(f, EmitterFlags::DeltaPosition); }
constexpr bool is_delta_direction(EmitterFlags f) { return has_any(f, EmitterFlags::DeltaDirection); }
constexpr bool is_delta_light(EmitterFlags f) {
  return has_any(f, static_cast<EmitterFlags>(static_cast<uint8_t>(EmitterFlags::DeltaPosition) |
                                              static_cast<uint8_t>(EmitterFlags::DeltaDirection)));
}

}  // namespace dualight
