// Shared between a long computation and whoever watches it: progress counters and a stop flag.
// Workers only read `cancel` and add to `done`, so relaxed atomics suffice.
#pragma once
#include <atomic>
#include <cstdint>

namespace dualight {

struct RenderControl {
  std::atomic<bool> cancel{false};
  std::atomic<uint64_t> done{0};
  std::atomic<uint64_t> total{0};

  bool cancelled() const { return cancel.load(std::memory_order_relaxed); }
};

}  // namespace dualight
