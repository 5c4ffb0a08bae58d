// Runs f(i) for i in [0, n) on `threads` TBB workers (0 = all cores), one item per task, so
// callers own disjoint data per item and results do not depend on the schedule.
#pragma once
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

namespace dualight {

template <class F>
void parallel_for_each_index(int threads, size_t n, const F& f) {
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
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
