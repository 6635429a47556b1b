#pragma once
// Every parallel loop of the compiler runs here, on oneTBB: work stealing, a thread limit per call, and an
// exception thrown by a body reaches the caller. One thread, or one item, runs inline: no tasks for work
// that cannot share.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cstddef>

namespace walk {

// body(first, last) for consecutive ranges of at most `grain` items covering [0, count), on at most
// `threads` threads (0: all cores). Ranges are fixed by count and grain alone, so work seeded per range
// gives the same result for any thread count.
template <class Body>
void parallel_ranges(std::size_t count, std::size_t grain, unsigned threads, Body&& body) {
  grain = std::max<std::size_t>(1, grain);
  if (threads == 1 || count <= grain) {
    for (std::size_t first = 0; first < count; first += grain) body(first, std::min(count, first + grain));
    return;
  }
  auto loop = [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, (count + grain - 1) / grain, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t k = r.begin(); k != r.end(); ++k)
            body(k * grain, std::min(count, (k + 1) * grain));
        },
        tbb::simple_partitioner());
  };
  // A limit below the machine's cores needs an arena of its own; otherwise the shared one serves.
  if (threads == 0 || static_cast<int>(threads) >= tbb::this_task_arena::max_concurrency()) {
    loop();
    return;
  }
  tbb::task_arena arena(static_cast<int>(threads));
  arena.execute(loop);
}

// body(i) for i in [0, count), one index at a time (cells and patches differ widely in cost, so fixed
// chunks would leave threads idle).
template <class Body>
void parallel_for(std::size_t count, unsigned threads, Body&& body) {
  parallel_ranges(count, 1, threads, [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) body(i);
  });
}

}  // namespace walk
