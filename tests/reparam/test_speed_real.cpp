// Tests of Speed::eval_real: sigma on real balls, against the exact sigma^2
// (Speed::squared) at rational points, for both speeds.
#include <gtest/gtest.h>

#include <arb.h>

#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

// A rational in (0, 1] with denominator up to 1000.
Rational random_unit(std::mt19937_64& rng) {
  const long d = std::uniform_int_distribution<long>(1, 1000)(rng);
  return Rational(std::uniform_int_distribution<long>(1, d)(rng), d);
}

const std::vector<std::string> kCurves = {"(t, t^2)", "((1-t^2)/(1+t^2), 2*t/(1+t^2))", "(t^3, t^2)",
                                          "(t, t^3 - t/2)", "((1-t^2)/(1+t^2), 2*t/(1+t^2), t)"};

TEST(SpeedReal, ContainsSigmaAtExactPoints) {
  std::mt19937_64 rng(41);
  for (const auto& text : kCurves)
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const Curve c = Curve::parse(text);
      const Speed s(c, kind);
      for (long it = 0; it < iterations(40); ++it) {
        const Rational t = random_unit(rng);
        const long prec = std::uniform_int_distribution<long>(30, 300)(rng);
        const Ball v = s.eval_real(Ball(t, prec), prec);
        SCOPED_TRACE(text + " at " + t.str() + ", " + std::to_string(prec) + " bits");
        ASSERT_TRUE(v.is_finite());
        EXPECT_FALSE(v.certainly_negative());
        Ball v2;
        arb_sqr(v2.get(), v.get(), prec);
        EXPECT_TRUE(v2.contains(s.squared()(t))) << v.str();  // sigma(t)^2, exactly
      }
    }
}

TEST(SpeedReal, WideBallContainsSigmaEverywhereInside) {
  std::mt19937_64 rng(42);
  for (const auto& text : kCurves)
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const Curve c = Curve::parse(text);
      const Speed s(c, kind);
      long finite = 0;
      for (long it = 0; it < iterations(20); ++it) {
        Rational a = random_unit(rng), b = random_unit(rng);
        if (b < a) std::swap(a, b);
        const Ball wide = interval_ball(a, b, 64);
        const Ball v = s.eval_real(wide, 64);
        SCOPED_TRACE(text + " on [" + a.str() + ", " + b.str() + "]");
        if (!v.is_finite()) continue;  // allowed: "nothing is known"
        ++finite;
        for (int k = 0; k <= 4; ++k) {
          const Rational t = a + (b - a) * Rational(k, 4);
          Ball v2;
          arb_sqr(v2.get(), v.get(), 64);
          EXPECT_TRUE(v2.contains(s.squared()(t))) << v.str() << " at " << t.str();
        }
      }
      EXPECT_GT(finite, 0) << text;  // the check is not vacuous
    }
}

}  // namespace
}  // namespace uniparam
