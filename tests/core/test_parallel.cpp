// Tests of uniparam/core/parallel.hpp: every item runs exactly once on a
// worker in range, per-worker state needs no lock, the first exception is
// rethrown, and worker threads inherit the caller's time budget.
#include <gtest/gtest.h>
#include <time.h>

#include <atomic>
#include <algorithm>
#include <mutex>
#include <chrono>
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

// The workers are persistent pool threads: a call nested inside a task, and
// calls made at the same time from several threads (the pool serves one),
// must still run every item exactly once on a worker in range, with the
// per-worker state unshared.
TEST(Parallel, NestedCallsRunEveryItemOnce) {
  const std::size_t outer = 6, inner = 9;
  std::vector<std::atomic<int>> runs(outer * inner);
  std::atomic<bool> out_of_range{false};
  parallel_for(outer, 3, [&](std::size_t w, std::size_t i) {
    if (w >= 3) out_of_range = true;
    std::vector<long> per_worker(2, 0);
    parallel_for(inner, 2, [&](std::size_t v, std::size_t j) {
      if (v >= 2) { out_of_range = true; return; }
      ++per_worker[v];
      ++runs[i * inner + j];
    });
    if (per_worker[0] + per_worker[1] != static_cast<long>(inner)) out_of_range = true;
  });
  EXPECT_FALSE(out_of_range);
  for (std::size_t k = 0; k < runs.size(); ++k) EXPECT_EQ(runs[k].load(), 1) << "item " << k;
}

// A loop nested in a task (an operation's steps side by side, each with
// its own loop) runs on persistent threads too: the inner worker 1 is the
// same thread from one outer call to the next (a thread-local counter there
// keeps counting), so its FLINT/Arb caches stay warm. With threads started
// for each call the counter would restart at every round.
thread_local long t_items = 0;

// Busy work for about `ns` of this thread's CPU time (parallel_for wakes its
// pool threads for a job once the caller has spent CPU time on it; a
// sleeping task would not be dispatched).
void burn_cpu(long ns) {
  auto cpu = [] {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<long>(ts.tv_sec) * 1000000000L + ts.tv_nsec;
  };
  const long until = cpu() + ns;
  volatile unsigned long x = 1;
  while (cpu() < until)
    for (int i = 0; i < 1000; ++i) x = x * 6364136223846793005UL + 1;
}

TEST(Parallel, NestedCallsRunOnPersistentThreads) {
  long most = 0;
  std::mutex m;
  const int rounds = 10;
  for (int round = 0; round < rounds; ++round)
    parallel_for(2, 2, [&](std::size_t w, std::size_t) {
      if (w != 0) {  // the calling thread's task nests a loop (this one keeps the other item)
        burn_cpu(12000000);
        return;
      }
      parallel_for(2, 2, [&](std::size_t v, std::size_t) {
        burn_cpu(5000000);  // both workers get an item
        if (v != 1) return;
        const long seen = ++t_items;
        std::lock_guard<std::mutex> lock(m);
        most = std::max(most, seen);
      });
    });
  EXPECT_GE(most, rounds / 2);  // threads of each call's own: at most 2
}

TEST(Parallel, ConcurrentCallsRunEveryItemOnce) {
  const std::size_t callers = 4, n = 200;
  std::vector<std::vector<std::atomic<int>>> runs(callers);
  for (auto& r : runs) r = std::vector<std::atomic<int>>(n);
  std::atomic<bool> bad{false};
  std::vector<std::thread> threads;
  for (std::size_t c = 0; c < callers; ++c)
    threads.emplace_back([&, c] {
      for (int round = 0; round < 20; ++round) {
        const std::size_t workers = 2 + (c + static_cast<std::size_t>(round)) % 3;
        std::vector<long> per_worker(workers, 0);  // unlocked: each worker its own slot
        parallel_for(n, workers, [&](std::size_t w, std::size_t i) {
          if (w >= workers) { bad = true; return; }
          per_worker[w] += static_cast<long>(i);
          ++runs[c][i];
        });
        long sum = 0;
        for (long v : per_worker) sum += v;
        if (sum != static_cast<long>(n * (n - 1) / 2)) bad = true;
      }
    });
  for (auto& t : threads) t.join();
  EXPECT_FALSE(bad);
  for (std::size_t c = 0; c < callers; ++c)
    for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(runs[c][i].load(), 20) << "caller " << c << " item " << i;
}

TEST(Parallel, AFailedCallLeavesThePoolUsable) {
  for (int round = 0; round < 5; ++round) {
    EXPECT_THROW(parallel_for(30, 3,
                              [](std::size_t, std::size_t i) {
                                if (i % 7 == 3) throw DomainError("item");
                              }),
                 DomainError);
    std::vector<std::atomic<int>> runs(40);
    parallel_for(40, 3, [&](std::size_t, std::size_t i) { ++runs[i]; });
    for (std::size_t i = 0; i < runs.size(); ++i) EXPECT_EQ(runs[i].load(), 1) << "item " << i;
  }
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
