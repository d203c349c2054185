// Tests of the exact helpers used to produce short rational output:
// Rational::simplest_between, mid_rational, and exact composition of
// rational functions.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"
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

TEST(PolySignAt, AgreesWithTheExactValue) {
  // Oracle: the sign of the exact rational value. Random polynomials at
  // random rationals, at their rational roots (sign 0: p = (q t - r) f),
  // and where the value is 1 against coefficients of 2^200 and 2^1000 (a
  // ball at 128 or 512 bits cannot decide; the exact value must).
  std::mt19937_64 rng(4242);
  std::uniform_int_distribution<long> c(-1000, 1000), den(1, 1L << 40), deg(0, 40);
  for (long it = 0; it < test_support::iterations(300); ++it) {
    std::vector<long> cs(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : cs) x = c(rng);
    const Poly f(cs);
    const long d = den(rng);
    const Rational x(c(rng) * (d / 1000 + 1) + c(rng), d);
    EXPECT_EQ(f.sign_at(x), f(x).sign()) << f.str() << " at " << x.str();
    const long q = std::uniform_int_distribution<long>(1, 50)(rng), r = c(rng);
    const Poly g = Poly(std::vector<long>{-r, q}) * f;
    EXPECT_EQ(g.sign_at(Rational(r, q)), 0) << g.str();
  }
  for (long e : {200L, 1000L}) {
    Integer big;
    fmpz_one(big.get());
    fmpz_mul_2exp(big.get(), big.get(), static_cast<ulong>(e));
    // p = 3 2^e t - (2^e - 1) - s: p(1/3) = 1 - s, for s = 0, 1, 2
    for (long s : {0L, 1L, 2L}) {
      const Poly p(std::vector<Integer>{Integer(1) - big - Integer(s), Integer(3) * big});
      EXPECT_EQ(p.sign_at(Rational(1, 3)), s == 0 ? 1 : s == 1 ? 0 : -1) << "e = " << e << ", s = " << s;
    }
  }
}

// centred_at_half(p)(2x - 1) = 2^n p(x) exactly, at random rationals, for
// random p of degree 0..40 (and the zero polynomial); fails with a wrong
// scale on any coefficient or a shift by other than 1.
TEST(CentredAtHalf, IsTheScaledPolynomialInTheVariable2xMinus1) {
  std::mt19937_64 rng(2424);
  std::uniform_int_distribution<long> c(-1000, 1000), den(1, 1L << 20), deg(0, 40);
  EXPECT_TRUE(centred_at_half(Poly()).is_zero());
  for (long it = 0; it < test_support::iterations(200); ++it) {
    std::vector<long> cs(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : cs) x = c(rng);
    if (cs.back() == 0) cs.back() = 1;
    const Poly p(cs);
    const Poly q = centred_at_half(p);
    ASSERT_EQ(q.degree(), p.degree());
    const Rational x(c(rng), den(rng));
    Rational scale(1);
    for (long k = 0; k < p.degree(); ++k) scale = scale * Rational(2);
    EXPECT_EQ(q(Rational(2) * x - Rational(1)), scale * p(x)) << p.str() << " at " << x.str();
  }
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
