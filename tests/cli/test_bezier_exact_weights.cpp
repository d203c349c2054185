// `bezier --exact-weights`: the exact new weights of an integral Bezier curve
// grow like the degree squared each, so above a size the command prints their
// exact formula in alpha (which is exact) and certified balls, never megabytes
// of surds; the balls do not depend on the form chosen.
#include <gtest/gtest.h>

#include <random>
#include <regex>
#include <string>
#include <vector>

#include "support/run.hpp"

using uniparam::test_support::run_uniparam;

namespace {

// A plane control polygon of degree n with small random integer points.
std::string random_control(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_int_distribution<int> d(-9, 9);
  std::string s = "[";
  for (int i = 0; i <= n; ++i) s += (i ? ",[" : "[") + std::to_string(3 * i + d(gen)) + "," + std::to_string(d(gen)) + "]";
  return s + "]";
}

// The text lines "w_i = ... = BALL" or "w_i = BALL": the certified ball of each.
std::vector<std::string> weight_balls(const std::string& out) {
  std::vector<std::string> balls;
  std::regex re("w_[0-9]+ = (?:[^\n]* = )?([-0-9.e]+ \\+/- [-0-9.e]+)\n");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), re); it != std::sregex_iterator(); ++it)
    balls.push_back((*it)[1]);
  return balls;
}

}  // namespace

TEST(CliBezierExactWeights, HighDegreePrintsTheFormulaNotMegabytes) {
  const int n = 150;
  auto r = run_uniparam({"bezier", "--control", random_control(n, 7), "--timeout", "300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("w_i = (1-alpha)^i * alpha^(150-i)"), std::string::npos);
  EXPECT_EQ(weight_balls(r.out).size(), static_cast<std::size_t>(n + 1));
  // n + 1 balls and a few exact values of degree-independent size.
  EXPECT_LT(r.out.size(), 40000u) << "output of " << r.out.size() << " bytes";

  auto j = run_uniparam({"bezier", "--control", random_control(n, 7), "--json", "--timeout", "300"});
  ASSERT_EQ(j.exit_code, 0) << j.err;
  EXPECT_NE(j.out.find("\"weights_formula\""), std::string::npos);
  EXPECT_LT(j.out.size(), 80000u) << "output of " << j.out.size() << " bytes";
}

TEST(CliBezierExactWeights, BallsDoNotDependOnTheForm) {
  for (int n : {3, 9, 30}) {
    const std::string control = random_control(n, 100 + n);
    auto e = run_uniparam({"bezier", "--control", control, "--exact-weights", "expanded"});
    auto f = run_uniparam({"bezier", "--control", control, "--exact-weights", "formula"});
    ASSERT_EQ(e.exit_code, 0) << e.err;
    ASSERT_EQ(f.exit_code, 0) << f.err;
    EXPECT_NE(e.out.find("sqrt("), std::string::npos) << e.out;  // the surds themselves
    const auto be = weight_balls(e.out), bf = weight_balls(f.out);
    ASSERT_EQ(be.size(), static_cast<std::size_t>(n + 1)) << e.out;
    EXPECT_EQ(be, bf);
  }
}

TEST(CliBezierExactWeights, LowDegreeAutoExpandsAndBadFormIsRefused) {
  auto r = run_uniparam({"bezier", "--control", "[[0,0],[1,2],[3,1],[4,4]]"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("w_3 = (16885607 - 233774*sqrt(5191))/250047"), std::string::npos) << r.out;
  auto bad = run_uniparam({"bezier", "--control", "[[0,0],[1,2],[3,1]]", "--exact-weights", "short"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--exact-weights expects expanded, formula or auto"), std::string::npos) << bad.err;
}
