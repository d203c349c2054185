// parallel_for runs small jobs on the calling thread alone (no pool thread
// woken, no item on another worker) and still spreads long jobs over the
// pool threads.
#include <gtest/gtest.h>

#include <time.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "uniparam/core/parallel.hpp"
#include "support/cpu_burn.hpp"

namespace uniparam {
namespace {

using test_support::burn;
using test_support::thread_cpu_ns;

// Fixed busy work without clock reads: burn()'s CPU-clock system calls
// cost microseconds each under the sanitizers, which would make these
// rounds as long as the dispatch threshold itself.
void spin(int iterations) {
  volatile std::uint64_t x = 1;
  for (int i = 0; i < iterations; ++i) x = x * 6364136223846793005ULL + 1;
}

// Many jobs of about a tenth of a millisecond each (the low-degree case): every item on
// the calling thread, and no pool thread ever woken.
TEST(ParallelInline, SmallJobsStayOnTheCallingThread) {
  // A job is dispatched after 0.5 ms of the caller's CPU time or 0.1 s of
  // wall time (a caller descheduled on a busy machine, or a slow sanitizer
  // build): only rounds that stayed well within both count. Rounds go on
  // until 250 have counted (on a busy machine many do not), up to 3000.
  int judged = 0;
  for (int round = 0; round < 3000 && judged < 250; ++round) {
    const std::uint64_t before = parallel_dispatches();
    long elsewhere = 0;
    std::vector<long> sum(4, 0);
    const auto t0 = std::chrono::steady_clock::now();
    const std::int64_t cpu0 = thread_cpu_ns();
    parallel_for(64, 4, [&](std::size_t w, std::size_t i) {
      if (w != 0) ++elsewhere;
      sum[w] += static_cast<long>(i);
      spin(1500);  // 64 items: about 0.12 ms of CPU in all
    });
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::int64_t cpu = thread_cpu_ns() - cpu0;
    EXPECT_EQ(sum[0] + sum[1] + sum[2] + sum[3], 64 * 63 / 2);
    if (wall > 0.05 || cpu > 300000) continue;
    ++judged;
    EXPECT_EQ(elsewhere, 0) << "round " << round;
    EXPECT_EQ(parallel_dispatches() - before, 0u) << "round " << round;
  }
  EXPECT_GE(judged, 250);
}

// A long job (items of 2 ms of CPU time each) is dispatched: another worker
// takes items, and every item runs once.
TEST(ParallelInline, LongJobsUseThePool) {
  const std::uint64_t before = parallel_dispatches();
  std::vector<std::atomic<int>> runs(8);
  std::atomic<long> elsewhere{0};
  parallel_for(8, 2, [&](std::size_t w, std::size_t i) {
    if (w != 0) ++elsewhere;
    ++runs[i];
    burn(2000000);
  });
  for (auto& r : runs) EXPECT_EQ(r.load(), 1);
  EXPECT_EQ(parallel_dispatches() - before, 1u);
  EXPECT_GT(elsewhere.load(), 0);
}

// Two long items (an operation's steps side by side): the second does not
// wait for the first, it goes to a pool thread while the first runs (once
// the process has seen jobs with long items while others were left, 8 ms
// of them in all, which starts the dispatcher: here one of 9 ms).
TEST(ParallelInline, TwoLongItemsRunSideBySide) {
  parallel_for(2, 2, [](std::size_t, std::size_t) { burn(9000000); });
  std::atomic<long> elsewhere{0};
  parallel_for(2, 2, [&](std::size_t w, std::size_t) {
    if (w != 0) ++elsewhere;
    burn(20000000);
  });
  EXPECT_EQ(elsewhere.load(), 1);
}

}  // namespace
}  // namespace uniparam
