// Tests of the small exact helpers of number.hpp and ball.hpp (pow2,
// grid_floor, mid_rational, rad_rational, interval_ball), each clause of
// their contracts against exact arithmetic on random inputs.
#include <gtest/gtest.h>

#include <arb.h>

#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {
namespace {

using test_support::iterations;
using test_support::random_integer;
using test_support::test_seed;

Rational random_rational(std::mt19937_64& rng) {
  Integer d = random_integer(rng, 12);
  if (d.sign() == 0) d = Integer(3);
  return Rational(random_integer(rng, 15), d);
}

// p(x) exactly, by Horner's rule in Q.
Rational eval_exact(const Poly& p, const Rational& x) {
  Rational r(0);
  for (long i = p.degree(); i >= 0; --i) r = r * x + Rational(p.coeff(i));
  return r;
}

// mapped_to_unit_interval(f, a, b) is f(a + (b - a) x) times one nonzero
// constant: the ratio G(x) / f(a + (b - a) x) is the same at every x, for
// random f, a and b (b < a too), and G is primitive.
TEST(ExactHelpers, MappedToUnitIntervalIsFOnTheInterval) {
  std::mt19937_64 rng(test_seed(4242));
  for (long it = 0; it < iterations(200); ++it) {
    std::vector<Integer> c;
    for (long k = 0, n = 1 + static_cast<long>(rng() % 7); k <= n; ++k) c.push_back(random_integer(rng, 40));
    if (c.back().sign() == 0) c.back() = Integer(5);
    const Poly f(c);
    const Rational a = random_rational(rng);
    Rational b = random_rational(rng);
    if (b == a) b = a + Rational(1, 7);
    const Poly G = mapped_to_unit_interval(f, a, b);
    ASSERT_EQ(G.degree(), f.degree());
    EXPECT_EQ(G, G.primitive());
    bool have = false;
    Rational ratio;
    for (const Rational& x : {Rational(0), Rational(1), Rational(1, 3), Rational(-5, 2), Rational(7, 11)}) {
      const Rational fx = eval_exact(f, a + (b - a) * x), gx = eval_exact(G, x);
      if (fx.sign() == 0) {
        EXPECT_EQ(gx.sign(), 0);
        continue;
      }
      if (!have) {
        ratio = gx / fx;
        have = true;
        EXPECT_NE(ratio.sign(), 0);
      } else {
        EXPECT_EQ(gx / fx, ratio) << "at x = " << x.str();
      }
    }
  }
}

TEST(ExactHelpers, Pow2IsThePowerOfTwo) {
  Integer p(1);
  for (long e = 0; e <= 200; ++e) {
    EXPECT_EQ(pow2(e), Rational(p)) << e;
    EXPECT_EQ(pow2(-e), Rational(1) / Rational(p)) << e;
    p = p * Integer(2);
  }
}

TEST(ExactHelpers, GridFloorIsTheLargestGridPointBelow) {
  std::mt19937_64 rng(31);
  for (long it = 0; it < iterations(2000); ++it) {
    const Rational x = random_rational(rng);
    const long s = std::uniform_int_distribution<long>(-80, 40)(rng);
    const Rational g = grid_floor(x, s), step = pow2(s);
    SCOPED_TRACE(x.str() + ", s = " + std::to_string(s));
    EXPECT_TRUE((g / step).is_integer());  // a point of the grid
    EXPECT_LE(g, x);
    EXPECT_LT(x, g + step);  // the largest one
    EXPECT_EQ(-grid_floor(-x, s) == x, (x / step).is_integer());  // the ceiling is x exactly on the grid
  }
}

TEST(ExactHelpers, MidAndRadAreTheBallsOwnNumbers) {
  std::mt19937_64 rng(32);
  for (long it = 0; it < iterations(500); ++it) {
    const Rational m = random_rational(rng), r = random_rational(rng);
    const long prec = std::uniform_int_distribution<long>(20, 200)(rng);
    Ball b(m, prec);
    Ball w(r < Rational(0) ? -r : r, 30);
    arb_add_error(b.get(), w.get());
    // [mid - rad, mid + rad] is the ball: its ends are in it, a bit beyond is not
    const Rational mid = mid_rational(b), rad = rad_rational(b);
    EXPECT_TRUE(b.contains(mid - rad) && b.contains(mid + rad));
    const Rational beyond = rad + pow2(-400);
    EXPECT_FALSE(b.contains(mid + beyond));
    EXPECT_FALSE(b.contains(mid - beyond));
    EXPECT_TRUE(b.contains(m));
  }
  EXPECT_EQ(rad_rational(Ball(Rational(1, 3), 64)) > Rational(0), true);
  EXPECT_EQ(rad_rational(Ball(5)), Rational(0));
}

TEST(ExactHelpers, NonFiniteBallsAreRefused) {
  Ball inf;
  arb_zero_pm_inf(inf.get());
  EXPECT_THROW(rad_rational(inf), DomainError);
  Ball nan;
  arb_indeterminate(nan.get());
  EXPECT_THROW(mid_rational(nan), DomainError);
}

TEST(ExactHelpers, IntervalBallHoldsTheClosedInterval) {
  std::mt19937_64 rng(33);
  for (long it = 0; it < iterations(500); ++it) {
    const Rational a = random_rational(rng), b = random_rational(rng);
    const long prec = std::uniform_int_distribution<long>(8, 128)(rng);
    const Ball iv = interval_ball(a, b, prec);  // either order
    SCOPED_TRACE(a.str() + ", " + b.str() + " at " + std::to_string(prec));
    EXPECT_TRUE(iv.contains(a) && iv.contains(b));
    for (int k = 1; k < 8; ++k) EXPECT_TRUE(iv.contains(a + (b - a) * Rational(k, 8)));
  }
}

}  // namespace
}  // namespace uniparam
