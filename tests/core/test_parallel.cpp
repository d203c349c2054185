// Tests of uniparam/core/parallel.hpp: every item runs exactly once on a
// worker in range, per-worker state needs no lock, the first exception is
// rethrown, and worker threads inherit the caller's time budget.
#include <gtest/gtest.h>

#include <atomic>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"

namespace uniparam {
namespace {

TEST(Parallel, EveryItemRunsOnceOnAWorkerInRange) {
  for (std::size_t workers : {1u, 2u, 3u, 7u})
    for (std::size_t n : {0u, 1u, 2u, 5u, 100u}) {
      std::vector<std::atomic<int>> runs(n);
      const std::size_t used = std::min(workers, n);
      std::vector<long> per_worker(std::max<std::size_t>(used, 1), 0);  // unlocked per-worker state
      std::atomic<bool> out_of_range{false};
      parallel_for(n, workers, [&](std::size_t w, std::size_t i) {
        if (w >= used) { out_of_range = true; return; }
        ++runs[i];
        per_worker[w] += static_cast<long>(i);
      });
      EXPECT_FALSE(out_of_range) << workers << " workers, " << n << " items";
      long sum = 0;
      for (long v : per_worker) sum += v;
      EXPECT_EQ(sum, static_cast<long>(n * (n == 0 ? 0 : n - 1) / 2));
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(runs[i].load(), 1) << "item " << i;
    }
}

TEST(Parallel, WorkerZeroIsTheCallingThread) {
  const auto caller = std::this_thread::get_id();
  std::atomic<bool> ok{true};
  parallel_for(20, 2, [&](std::size_t w, std::size_t) {
    if ((w == 0) != (std::this_thread::get_id() == caller)) ok = false;
  });
  EXPECT_TRUE(ok);
}

TEST(Parallel, RethrowsTheFirstException) {
  EXPECT_THROW(parallel_for(50, 3,
                            [](std::size_t, std::size_t i) {
                              if (i == 17) throw DomainError("item 17");
                            }),
               DomainError);
}

TEST(Parallel, WorkersInheritTheTimeBudget) {
  std::atomic<int> with_budget{0};
  {
    TimeBudget budget(100.0);
    parallel_for(8, 4, [&](std::size_t, std::size_t) {
      if (has_time_budget()) ++with_budget;
    });
  }
  EXPECT_EQ(with_budget.load(), 8);
  std::atomic<int> without{0};
  parallel_for(8, 4, [&](std::size_t, std::size_t) {
    if (has_time_budget()) ++without;
  });
  EXPECT_EQ(without.load(), 0);
}

TEST(Parallel, AnExpiredBudgetStopsWorkers) {
  TimeBudget budget(1e-6);
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_THROW(parallel_for(8, 4, [](std::size_t, std::size_t) { check_time_budget(); }), BudgetExceeded);
}

TEST(Parallel, WorkerCountHonoursTheEnvironment) {
  setenv("UNIPARAM_THREADS", "3", 1);
  EXPECT_EQ(worker_count(), 3u);
  setenv("UNIPARAM_THREADS", "0", 1);  // invalid: falls back to the hardware
  EXPECT_GE(worker_count(), 1u);
  unsetenv("UNIPARAM_THREADS");
  EXPECT_GE(worker_count(), 1u);
}

}  // namespace
}  // namespace uniparam
