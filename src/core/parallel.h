// Runs f(i) for i in [0, n) on `threads` TBB workers (0 = all cores), one item per task, so
// callers own disjoint data per item and results do not depend on the schedule.
#pragma once
#include <algorithm>
#include <thread>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace dualight {

// The workers a request for `threads` gets: at most one per core (a task arena or an OpenMP team
// of 100,000 threads crashed; more threads than cores only add overhead), 0 or less: every core.
inline int worker_count(int threads) {
  const int cores = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
  return threads > 0 ? std::min(threads, cores) : cores;
}

template <class F>
void parallel_for_each_index(int threads, size_t n, const F& f) {
  tbb::task_arena arena(worker_count(threads));
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, n, 1),
        [&](const tbb::blocked_range<size_t>& r) {
          for (size_t i = r.begin(); i != r.end(); ++i) f(i);
        },
        tbb::simple_partitioner());
  });
}

}  // namespace dualight
