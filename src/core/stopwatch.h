// Seconds since construction on the steady clock: the clock every render's time limit, start-up
// shares and reported seconds count on. Callable, so it passes as std::function<double()>.
#pragma once
#include <chrono>

namespace dualight {

class Stopwatch {
 public:
  double operator()() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

}  // namespace dualight
