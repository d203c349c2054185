// The time budget's exception: a TimeLimitExceeded (a BudgetExceeded) that
// names the time limit, from the calling thread and from parallel_for's
// workers alike, so that no caller can mistake it for another budget.
// No test measures how long anything takes: an expired budget is one of
// 10^-9 s, which has passed by the next clock read.
#include <gtest/gtest.h>

#include <atomic>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"

using namespace uniparam;

TEST(TimeLimit, AnExpiredBudgetThrowsTheTimeTypeNamingTime) {
  const TimeBudget b(1e-9);
  bool thrown = false;
  for (long i = 0; i < 100000000 && !thrown; ++i) {
    try {
      check_time_budget();
    } catch (const TimeLimitExceeded& e) {
      thrown = true;
      const std::string m = e.what();
      EXPECT_NE(m.find("time limit exceeded"), std::string::npos) << m;
      EXPECT_NE(m.find("--timeout"), std::string::npos) << m;
    }
  }
  EXPECT_TRUE(thrown);
}

TEST(TimeLimit, IsABudgetExceeded) {
  // Callers that catch BudgetExceeded (exit code 4) still catch it.
  try {
    throw TimeLimitExceeded("time limit exceeded");
  } catch (const BudgetExceeded& e) {
    EXPECT_NE(dynamic_cast<const TimeLimitExceeded*>(&e), nullptr);
  }
}

TEST(TimeLimit, ReachesTheCallerFromWorkerThreadsWithItsType) {
  const TimeBudget b(1e-9);
  std::atomic<long> ran{0};
  try {
    parallel_for(8, 3, [&](std::size_t, std::size_t) {
      ++ran;
      for (;;) check_time_budget();  // every worker inherits the expired deadline
    });
    FAIL() << "parallel_for returned";
  } catch (const TimeLimitExceeded& e) {
    EXPECT_NE(std::string(e.what()).find("time limit exceeded"), std::string::npos);
  }
  EXPECT_GE(ran.load(), 1);
}
