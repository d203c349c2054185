// Tests of the exact helpers used to produce short rational output:
// Rational::simplest_between, mid_rational, and exact composition of
// rational functions.
#include <gtest/gtest.h>

#include <random>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/ratfunc.hpp"

namespace uniparam {
namespace {

TEST(SimplestBetween, HasTheSmallestDenominatorInTheInterval) {
  // Oracle: brute force over denominators 1, 2, ... for random small intervals.
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<long> num(-400, 400), den(1, 60), width(0, 40);
  for (long it = 0; it < test_support::iterations(300); ++it) {
    Rational lo(num(rng), den(rng));
    Rational hi = lo + Rational(width(rng), 97);
    Rational r = Rational::simplest_between(lo, hi);
    ASSERT_TRUE(lo <= r && r <= hi) << lo.str() << " " << r.str() << " " << hi.str();
    // no rational with a smaller denominator lies in [lo, hi]
    const long q = std::stol(r.den().str());
    for (long d = 1; d < q; ++d) {
      // c = ceil(lo * d): the smallest multiple of 1/d at or above lo
      fmpz_t c, n;
      fmpz_init(c);
      fmpz_init(n);
      fmpz_mul_si(n, lo.num().get(), d);
      fmpz_cdiv_q(c, n, lo.den().get());
      const Rational cand{Integer(c), Integer(d)};
      fmpz_clear(c);
      fmpz_clear(n);
      ASSERT_GT(cand, hi) << "denominator " << d << " fits in [" << lo.str() << ", " << hi.str() << "] but got "
                          << r.str();
    }
  }
}

TEST(SimplestBetween, PointIntervalAndErrors) {
  EXPECT_EQ(Rational::simplest_between(Rational(3, 7), Rational(3, 7)), Rational(3, 7));
  EXPECT_EQ(Rational::simplest_between(Rational(-1, 3), Rational(1, 3)), Rational(0));
  EXPECT_THROW(Rational::simplest_between(Rational(1), Rational(0)), InvalidArgument);
}

TEST(MidRational, IsTheExactMidpoint) {
  Ball b(Rational(5, 8), 64);
  EXPECT_EQ(mid_rational(b), Rational(5, 8));
  Ball third(Rational(1, 3), 64);
  Rational m = mid_rational(third);
  // the midpoint of a 64-bit enclosure of 1/3 is a dyadic number within 2^-60
  EXPECT_NE(m, Rational(1, 3));
  Rational err = m - Rational(1, 3);
  if (err.sign() < 0) err = -err;
  EXPECT_LT(err, Rational(Integer(1), Integer("1152921504606846976")));
}

TEST(Compose, AgreesWithHornerCompositionOnRandomRationalFunctions) {
  std::mt19937_64 rng(5);
  for (long it = 0; it < test_support::iterations(60); ++it) {
    RatFunc f(test_support::random_poly(rng, 1 + it % 5, 9), test_support::random_poly(rng, it % 3, 9) + Poly(50));
    RatFunc g(test_support::random_poly(rng, 1 + it % 2, 9), test_support::random_poly(rng, it % 2, 9) + Poly(30));
    RatFunc h;
    try {
      h = compose(f, g);
    } catch (const DomainError&) {
      continue;
    }
    EXPECT_EQ(h, test_support::compose(f, g));
  }
}

}  // namespace
}  // namespace uniparam
