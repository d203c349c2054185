// cumulative_normalised (uniparam/core/ball.hpp) for balls, exact rationals
// and doubles: exact ends, and every inner value the prefix sum over the
// total, checked against an exact rational oracle.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

double mid_d(const Ball& b) { return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR); }

// Random positive rationals w_0 .. w_{n-1}, n in [1, 12].
std::vector<Rational> random_weights(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> len(1, 12), num(1, 1000000), den(1, 997);
  std::vector<Rational> w(static_cast<std::size_t>(len(rng)));
  for (auto& x : w) x = Rational(num(rng), den(rng));
  return w;
}

Rational prefix_over_total(const std::vector<Rational>& w, std::size_t i) {
  Rational acc(0), total(0);
  for (std::size_t k = 0; k < w.size(); ++k) {
    if (k < i) acc = acc + w[k];
    total = total + w[k];
  }
  return acc / total;
}

TEST(CumulativeSums, RationalsAreTheExactPrefixSumsOverTheTotal) {
  std::mt19937_64 rng(1);
  for (long it = 0; it < iterations(200); ++it) {
    const std::vector<Rational> w = random_weights(rng);
    Rational total(0);
    for (const auto& x : w) total = total + x;
    const std::vector<Rational> s = cumulative_normalised(w, total);
    ASSERT_EQ(s.size(), w.size() + 1);
    for (std::size_t i = 0; i <= w.size(); ++i) EXPECT_EQ(s[i], prefix_over_total(w, i)) << i;
  }
}

TEST(CumulativeSums, BallsContainThePrefixSumsAndDoublesAreNearThemWithExactEnds) {
  std::mt19937_64 rng(2);
  for (long it = 0; it < iterations(200); ++it) {
    const std::vector<Rational> w = random_weights(rng);
    std::vector<Ball> wb;
    std::vector<double> wd;
    Ball total(0);
    double total_d = 0;
    for (const auto& x : w) {
      wb.emplace_back(x, 53);
      arb_add(total.get(), total.get(), wb.back().get(), 53);
      wd.push_back(mid_d(wb.back()));
      total_d += wd.back();
    }
    const std::vector<Ball> sb = cumulative_normalised(wb, total, 53);
    const std::vector<double> sd = cumulative_normalised(wd, total_d);
    ASSERT_EQ(sb.size(), w.size() + 1);
    ASSERT_EQ(sd.size(), w.size() + 1);
    EXPECT_TRUE(sb.front().is_exact() && sb.front().certainly_zero());
    EXPECT_TRUE(sb.back().is_exact() && sb.back().contains(Rational(1)));
    EXPECT_EQ(sd.front(), 0.0);
    EXPECT_EQ(sd.back(), 1.0);
    for (std::size_t i = 0; i <= w.size(); ++i) {
      const Rational exact = prefix_over_total(w, i);
      EXPECT_TRUE(sb[i].contains(exact)) << i << " " << sb[i].str(20);
      EXPECT_NEAR(sd[i], mid_d(Ball(exact, 64)), 1e-13) << i;
    }
  }
}

}  // namespace
}  // namespace uniparam
