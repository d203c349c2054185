// parallel_for wakes the pool threads only for work that can pay for them:
// a job found long near its end, with too little left for another worker
// (the last item, which the calling thread takes itself, or a few short
// ones), finishes on the calling thread, without its prepare step; a job
// with much left is still dispatched.
#include <gtest/gtest.h>

#include <time.h>

#include <atomic>
#include <chrono>
#include <cstdint>

#include "uniparam/core/parallel.hpp"
#include "support/cpu_burn.hpp"

namespace uniparam {
namespace {

using test_support::burn;
using test_support::thread_cpu_ns;

struct Outcome {
  std::uint64_t dispatches = 0;  // jobs whose pool threads were woken
  int prepares = 0;              // calls of the prepare step
  long elsewhere = 0;            // items run by workers other than 0
  double wall = 0;               // seconds
};

// One parallel_for of n items on 2 workers, item i burning cost(i) ns of
// CPU time, with a prepare step that only counts its calls.
template <class Cost>
Outcome run_job(std::size_t n, Cost cost) {
  Outcome out;
  std::atomic<long> elsewhere{0};
  const std::uint64_t before = parallel_dispatches();
  const auto t0 = std::chrono::steady_clock::now();
  parallel_for(
      n, 2,
      [&](std::size_t w, std::size_t i) {
        if (w != 0) ++elsewhere;
        burn(cost(i));
      },
      [&](std::size_t) { ++out.prepares; });
  out.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.dispatches = parallel_dispatches() - before;
  out.elsewhere = elsewhere.load();
  return out;
}

// Rounds that took more than this wall time are not judged: on a machine
// busy enough to deschedule the caller for that long, a job may be
// dispatched on wall time (0.1 s) instead of CPU time.
constexpr double kJudgedWall = 0.05;

// 20 rounds of run_job(n, cost); check(outcome, round) on each round that
// took at most kJudgedWall, of which there must be 15 at least.
template <class Cost, class Check>
void judged_rounds(std::size_t n, Cost cost, Check check) {
  int judged = 0;
  for (int round = 0; round < 20; ++round) {
    const Outcome o = run_job(n, cost);
    if (o.wall > kJudgedWall) continue;
    ++judged;
    check(o, round);
  }
  EXPECT_GE(judged, 15);
}

// 8 items of 0.1 ms: the caller has spent 0.5 ms after 5 of them, when 3
// are left, the next of which it takes itself: about 0.2 ms for another
// worker, less than waking it costs. The whole job stays on the caller.
TEST(ParallelPolicy, AShortTailIsNotDispatched) {
  judged_rounds(8, [](std::size_t) { return 100000; }, [](const Outcome& o, int round) {
    EXPECT_EQ(o.dispatches, 0u) << "round " << round;
    EXPECT_EQ(o.prepares, 0) << "round " << round;
    EXPECT_EQ(o.elsewhere, 0) << "round " << round;
  });
}

// Two items of 1 ms (an operation's parts, each copied for a woken worker
// by the prepare step): after the first the job is long, but the caller
// takes the second itself; copying for a worker that would find nothing
// left is waste.
TEST(ParallelPolicy, TheLastItemIsNotDispatched) {
  judged_rounds(2, [](std::size_t) { return 1000000; }, [](const Outcome& o, int round) {
    EXPECT_EQ(o.dispatches, 0u) << "round " << round;
    EXPECT_EQ(o.prepares, 0) << "round " << round;
  });
}

// Cheap items first, then an expensive last one: when the caller has
// spent 0.5 ms, only the item it takes next is left.
TEST(ParallelPolicy, AJobFoundLongAtItsLastItemIsNotDispatched) {
  judged_rounds(10, [](std::size_t i) { return i < 9 ? 60000 : 1000000; }, [](const Outcome& o, int round) {
    EXPECT_EQ(o.dispatches, 0u) << "round " << round;
    EXPECT_EQ(o.prepares, 0) << "round " << round;
  });
}

// A job long enough to start the process's first thread (2 ms, then 2 ms
// estimated left): 60 items of 0.1 ms.
void start_threads() {
  if (!parallel_threads_started()) run_job(60, [](std::size_t) { return 100000; });
  ASSERT_TRUE(parallel_threads_started());
}

// 30 items of 0.1 ms, once the process has threads: after 0.5 ms, 2.4 ms
// are left: the job is dispatched once, with its prepare step run once.
TEST(ParallelPolicy, ALongTailIsDispatched) {
  start_threads();
  const Outcome o = run_job(30, [](std::size_t) { return 100000; });
  EXPECT_EQ(o.dispatches, 1u);
  EXPECT_EQ(o.prepares, 1);
}

// Before its first thread a process needs 2 ms of CPU time and 2 ms
// estimated left: 15 items of 0.1 ms (0.5 ms, then 0.9 ms left: dispatched
// in a process that has threads) stay on the caller, and start no thread.
// Each test runs in its own process under ctest; in a process where an
// earlier test started threads this one has nothing to check.
TEST(ParallelPolicy, TheFirstThreadWaitsForALongerJob) {
  if (parallel_threads_started()) GTEST_SKIP() << "an earlier test in this process started threads";
  judged_rounds(15, [](std::size_t) { return 100000; }, [](const Outcome& o, int round) {
    EXPECT_EQ(o.dispatches, 0u) << "round " << round;
    EXPECT_EQ(o.prepares, 0) << "round " << round;
    EXPECT_FALSE(parallel_threads_started()) << "round " << round;
  });
  start_threads();
  const Outcome o = run_job(15, [](std::size_t) { return 100000; });
  EXPECT_EQ(o.dispatches, 1u);
}

// A long item while another is left (two steps side by side) is what the
// dispatcher serves, but one job of two such items of 3 ms (a small job's
// cold first run) starts no thread: the dispatcher waits until long items
// have taken 8 ms in the process. Two more such jobs (9 ms of long items)
// start it.
TEST(ParallelPolicy, OneColdLongItemStartsNoThread) {
  if (parallel_threads_started()) GTEST_SKIP() << "an earlier test in this process started threads";
  const auto step = [](std::size_t, std::size_t) { burn(3000000); };
  const auto t0 = std::chrono::steady_clock::now();
  parallel_for(2, 2, step);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (wall > 0.0075) GTEST_SKIP() << "descheduled for " << wall - 0.006 << " s: the long item may count more than 3 ms";
  EXPECT_FALSE(parallel_threads_started());
  for (int k = 0; k < 3; ++k) parallel_for(2, 2, step);
  EXPECT_TRUE(parallel_threads_started());
}

}  // namespace
}  // namespace uniparam
