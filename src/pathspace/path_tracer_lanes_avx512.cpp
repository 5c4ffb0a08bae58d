// The path tracer in lanes (path_tracer_lanes.h) compiled for AVX-512. Its headers come
// first, at the baseline, so that no inline function other units share is compiled for this
// instruction set; then the lanes and the kernel, in a namespace of their own, under the pragma.
#include "pathspace/path_tracer_lanes.h"

#pragma GCC push_options
#pragma GCC target("avx512f,avx512dq,avx512bw,avx512vl,avx2,fma,bmi,bmi2,popcnt,f16c")
#define DUALIGHT_LANES_NS lanes_avx512
#define DUALIGHT_LANES_BITS 512
// clang-format off
#include "core/lanes.h"
#include "pathspace/path_lanes_kernel.h"
// clang-format on
#undef DUALIGHT_LANES_NS
#undef DUALIGHT_LANES_BITS
#pragma GCC pop_options

namespace dualight {

PathLanesKernels path_lanes_kernels_avx512() {
  return {"avx512", &lanes_avx512::trace_paths<IndependentSampler>, &lanes_avx512::trace_paths<SobolSampler>};
}

}  // namespace dualight
