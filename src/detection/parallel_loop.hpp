#pragma once
// Small helpers of the detection stage (internal): an index loop on TBB threads when asked, and stage timing.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstddef>

namespace clothcd::detail {

/// The clock of the stage timings.
using StageClock = std::chrono::steady_clock;

/// Milliseconds from `t` to now.
inline double milliseconds_since(StageClock::time_point t) {
  return std::chrono::duration<double, std::milli>(StageClock::now() - t).count();
}

/// Runs `body(i)` for i in [0, n): on TBB threads, in chunks of at least `grain` indices, when `parallel` and there
/// are at least two such chunks; otherwise in order on the calling thread.
template <class Function>
void for_each_index(std::size_t n, bool parallel, std::size_t grain, const Function& body) {
  if (!parallel || n < 2 * grain) {
    for (std::size_t i = 0; i < n; ++i) body(i);
    return;
  }
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i != r.end(); ++i) body(i);
  });
}

}  // namespace clothcd::detail
