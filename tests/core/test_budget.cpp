// The time budget (core/budget.hpp): deadlines nest (earliest wins), are
// restored at scope exit, and expire into BudgetExceeded naming --timeout.
// No test measures how long anything takes: an expired budget is one of
// 10^-9 s, which has passed by the next clock read.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

using namespace uniparam;

namespace {

// Calls check_time_budget() until it throws (an expired budget throws at the
// first call whose clock read is past the deadline); false if it never does
// within many calls.
bool expires(std::string* message = nullptr) {
  for (long i = 0; i < 100000000; ++i) {
    try {
      check_time_budget();
    } catch (const BudgetExceeded& e) {
      if (message) *message = e.what();
      return true;
    }
  }
  return false;
}

}  // namespace

TEST(TimeBudget, NoBudgetMeansNoDeadline) {
  EXPECT_FALSE(has_time_budget());
  EXPECT_NO_THROW(check_time_budget());
}

TEST(TimeBudget, ExpiredBudgetThrowsNamingTheOption) {
  const TimeBudget b(1e-9);
  EXPECT_TRUE(has_time_budget());
  std::string msg;
  ASSERT_TRUE(expires(&msg));
  EXPECT_NE(msg.find("time limit"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--timeout"), std::string::npos) << msg;
  EXPECT_NE(msg.find("1e-09 s"), std::string::npos) << msg;
}

TEST(TimeBudget, InnerBudgetShortensButNeverExtends) {
  const TimeBudget outer(1e6);
  EXPECT_NO_THROW(check_time_budget());
  {
    const TimeBudget inner(1e-9);
    EXPECT_TRUE(expires());
  }
  EXPECT_NO_THROW(check_time_budget());  // the outer deadline is back
  EXPECT_TRUE(has_time_budget());
  {
    const TimeBudget short_outer(1e-9);
    const TimeBudget long_inner(1e6);  // cannot extend the expired one
    EXPECT_TRUE(expires());
  }
}

TEST(TimeBudget, ScopeExitRemovesTheDeadline) {
  { const TimeBudget b(1e-9); }
  EXPECT_FALSE(has_time_budget());
  EXPECT_NO_THROW(check_time_budget());
}

TEST(TimeBudget, InvalidLengthsAreRefused) {
  for (double s : {0.0, -1.0, std::nan(""), HUGE_VAL, 2e9}) EXPECT_THROW(TimeBudget b(s), InvalidArgument) << s;
  EXPECT_FALSE(has_time_budget());
}
