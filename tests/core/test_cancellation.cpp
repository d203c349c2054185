// Cancellation from outside (ScopedCancellation, core/budget.hpp) and the
// per-thread worker count (ScopedWorkerCount, core/parallel.hpp): both are
// in force in the calling thread and in the workers of its parallel loops,
// and both are restored at scope exit. The Python module relies on them for
// Ctrl-C and threads=.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"

using namespace uniparam;

namespace {

// Spends about `ms` of this thread's CPU, so that parallel_for wakes its
// workers (it does after 0.5 ms of the caller's CPU).
void spin(double ms) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double, std::milli>(ms);
  volatile unsigned x = 0;
  while (std::chrono::steady_clock::now() < end) x = x + 1;
}

}  // namespace

TEST(Cancellation, UnsetFlagChangesNothing) {
  std::atomic<bool> flag{false};
  const ScopedCancellation c(flag);
  EXPECT_NO_THROW(check_time_budget());
  EXPECT_FALSE(has_time_budget());
}

TEST(Cancellation, SetFlagThrowsInterruptedALetThroughTimeout) {
  std::atomic<bool> flag{false};
  {
    const ScopedCancellation c(flag);
    flag = true;
    try {
      check_time_budget();
      FAIL() << "no exception";
    } catch (const TimeLimitExceeded& e) {  // let through wherever a timeout is
      EXPECT_NE(dynamic_cast<const Interrupted*>(&e), nullptr);
      EXPECT_NE(std::string(e.what()).find("interrupted"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(check_time_budget());  // the scope is over
}

TEST(Cancellation, NestsWithABudget) {
  std::atomic<bool> flag{false};
  const TimeBudget b(1e6);
  {
    const ScopedCancellation c(flag);
    EXPECT_NO_THROW(check_time_budget());
    {
      const TimeBudget inner(1e5);  // a budget inside keeps the cancellation
      flag = true;
      EXPECT_THROW(check_time_budget(), Interrupted);
    }
    EXPECT_THROW(check_time_budget(), Interrupted);
  }
  EXPECT_NO_THROW(check_time_budget());
  EXPECT_TRUE(has_time_budget());
}

TEST(Cancellation, WorkersInheritTheFlag) {
  std::atomic<bool> flag{false};
  const ScopedCancellation c(flag);
  // How many of 16 work items on 4 workers see the cancellation.
  auto interrupted_items = [] {
    std::atomic<int> seen{0};
    parallel_for(16, 4, [&](std::size_t, std::size_t) {
      spin(2);
      try {
        check_time_budget();
      } catch (const Interrupted&) {
        ++seen;
      }
    });
    return seen.load();
  };
  EXPECT_EQ(interrupted_items(), 0);
  flag = true;
  EXPECT_EQ(interrupted_items(), 16);
}

TEST(WorkerCount, ScopedCountIsInForceAndRestored) {
  const std::size_t before = worker_count();
  {
    const ScopedWorkerCount w(3);
    EXPECT_EQ(worker_count(), 3u);
    {
      const ScopedWorkerCount none(0);  // 0 leaves the setting alone
      EXPECT_EQ(worker_count(), 3u);
      const ScopedWorkerCount one(1);
      EXPECT_EQ(worker_count(), 1u);
    }
    EXPECT_EQ(worker_count(), 3u);
  }
  EXPECT_EQ(worker_count(), before);
  EXPECT_THROW(ScopedWorkerCount(65), InvalidArgument);
}

TEST(WorkerCount, WorkersInheritTheCount) {
  const ScopedWorkerCount w(5);
  std::atomic<int> right{0};
  parallel_for(16, 4, [&](std::size_t, std::size_t) {
    spin(2);
    if (worker_count() == 5) ++right;
  });
  EXPECT_EQ(right.load(), 16);
}
