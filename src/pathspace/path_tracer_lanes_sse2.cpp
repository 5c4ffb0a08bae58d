// The path tracer in lanes (path_tracer_lanes.h) compiled for the x86-64 baseline (SSE2): every x86-64 CPU. Its headers come
// first, at the baseline, so that no inline function other units share is compiled for this
// instruction set; then the lanes and the kernel, in a namespace of their own, under the pragma.
#include "pathspace/path_tracer_lanes.h"

#pragma GCC push_options  // no target: the baseline
#define DUALIGHT_LANES_NS lanes_sse2
#define DUALIGHT_LANES_BITS 128
// clang-format off
#include "core/lanes.h"
#include "pathspace/path_lanes_kernel.h"
// clang-format on
#undef DUALIGHT_LANES_NS
#undef DUALIGHT_LANES_BITS
#pragma GCC pop_options

namespace dualight {

PathLanesKernels path_lanes_kernels_sse2() {
  return {"sse2", &lanes_sse2::trace_paths<IndependentSampler>, &lanes_sse2::trace_paths<SobolSampler>};
}

}  // namespace dualight
