// Emitters without a surface as Python sees them (dualight._core.Emitter), shared by the emitter
// binding and the scene binding (which takes a list of them).
#pragma once
#include "lights/emitter.h"

namespace dualight::bindings {

struct EmitterObject {
  Emitter emitter;
};

}  // namespace dualight::bindings
