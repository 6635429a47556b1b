#pragma once
// Runs body(i) for i in [0, count) on at most `threads` threads (0: all cores) with oneTBB, one index at a
// time (cells differ widely in cost, so fixed chunks would leave threads idle). An exception thrown by a
// body reaches the caller. One thread, or one index, runs inline: no tasks for work that cannot share.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/partitioner.h>
#include <tbb/task_arena.h>

#include <cstddef>

namespace walk::compiler {

template <class Body>
void parallel_for(std::size_t count, unsigned threads, Body&& body) {
  if (threads == 1 || count <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i);
    return;
  }
  auto loop = [&] {
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, count, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
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

}  // namespace walk::compiler
