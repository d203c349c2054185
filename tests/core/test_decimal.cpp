// Tests of decimal.hpp: rounding of decimal_string and decimal_upper
// checked exactly against rationals, and the enclosure property of
// decimal_enclosure on random balls (the printed [mid - rad, mid + rad],
// read back exactly, must contain the ball's exact interval).
#include <gtest/gtest.h>

#include <arf.h>
#include <mag.h>

#include <cstdlib>
#include <random>
#include <string>

#include "support/iterations.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {
namespace {

using test_support::iterations;
using test_support::random_integer;

Rational pow10(long k) {
  Integer p;
  fmpz_set_ui(p.get(), 10);
  fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(k < 0 ? -k : k));
  return k >= 0 ? Rational(p) : Rational(Integer(1), p);
}

Rational abs(const Rational& x) { return x.sign() < 0 ? -x : x; }

// floor(log10(a)) for a > 0, by exact comparison.
long floor_log10(const Rational& a) {
  long e = 0;
  while (pow10(e) > a) --e;
  while (pow10(e + 1) <= a) ++e;
  return e;
}

// Number of significant digits of a decimal string "-0.00120e5" -> 2.
long significant_digits(const std::string& s) {
  std::string d;
  for (char c : s) {
    if (c == 'e' || c == 'E') break;
    if (c >= '0' && c <= '9') d += c;
  }
  const std::size_t first = d.find_first_not_of('0');
  if (first == std::string::npos) return 0;
  d = d.substr(first);
  // Trailing zeros are not counted: decimal_string never prints them after
  // the point, and "1000" (rounded to 1 digit) has one significant digit.
  const std::size_t last = d.find_last_not_of('0');
  return static_cast<long>(last + 1);
}

Rational random_rational(std::mt19937_64& rng) {
  Integer d = random_integer(rng, 25);
  if (d.sign() == 0) d = Integer(7);
  Rational q(random_integer(rng, 25), d);
  const long shift = std::uniform_int_distribution<long>(-40, 40)(rng);
  return q * pow10(shift);
}

// A random finite ball: mid = m * 2^e1, rad = r * 2^e2 (r may be 0).
Ball random_ball(std::mt19937_64& rng) {
  Ball b;
  const Integer m = random_integer(rng, 30);
  const long e1 = std::uniform_int_distribution<long>(-250, 200)(rng);
  arf_set_fmpz_2exp(arb_midref(b.get()), m.get(), Integer(e1).get());
  const ulong r = rng() % 4 == 0 ? 0 : rng() % 1000000;
  const long e2 = e1 + std::uniform_int_distribution<long>(-120, 10)(rng);
  mag_set_ui_2exp_si(arb_radref(b.get()), r, e2);
  return b;
}

TEST(Decimal, StringRoundsToNearestProperty) {
  std::mt19937_64 rng(12345);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Rational q = random_rational(rng);
    const long sig = std::uniform_int_distribution<long>(1, 30)(rng);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": q = " + q.str() + ", sig = " + std::to_string(sig));
    const std::string s = decimal_string(q, sig);
    const Rational p = Rational::parse(s);
    if (q.is_zero()) {
      EXPECT_EQ(s, "0");
      continue;
    }
    // |p - q| <= 1/2 unit in the last requested place of q.
    const long e = floor_log10(abs(q));
    EXPECT_LE(abs(p - q), Rational(1, 2) * pow10(e - sig + 1)) << s;
    EXPECT_LE(significant_digits(s), sig) << s;
    EXPECT_EQ(p.sign(), q.sign()) << s;
  }
}

TEST(Decimal, UpperRoundsUpWithTwoDigitsProperty) {
  std::mt19937_64 rng(999);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Rational q = abs(random_rational(rng));
    SCOPED_TRACE("iteration " + std::to_string(it) + ": q = " + q.str());
    const std::string s = decimal_upper(q);
    const Rational p = Rational::parse(s);
    EXPECT_GE(p, q) << s;
    if (q.is_zero()) continue;
    EXPECT_LE(significant_digits(s), 2) << s;
    EXPECT_LT(p - q, pow10(floor_log10(q) - 1)) << s;  // less than one unit in the 2nd digit
  }
  EXPECT_EQ(decimal_upper(Rational(0)), "0");
  EXPECT_THROW(decimal_upper(Rational(-1)), InvalidArgument);
}

TEST(Decimal, RoundingCarriesIntoANewDigit) {
  EXPECT_EQ(Rational::parse(decimal_string(Rational::parse("9.999"), 3)), Rational(10));
  EXPECT_EQ(Rational::parse(decimal_string(Rational::parse("-9.999"), 3)), Rational(-10));
  EXPECT_EQ(Rational::parse(decimal_string(Rational::parse("0.99995"), 4)), Rational(1));
  EXPECT_EQ(decimal_string(Rational::parse("9.999"), 4), "9.999");
  EXPECT_EQ(Rational::parse(decimal_string(Rational::parse("9.999"), 2)), Rational(10));
  // Rounding 9.9999e20 to 3 digits gives 1e21, whose exponent is outside the plain range.
  EXPECT_EQ(Rational::parse(decimal_string(Rational::parse("9.9999e20"), 3)), Rational::parse("1e21"));
  EXPECT_NE(decimal_string(Rational::parse("9.9999e20"), 3).find('e'), std::string::npos);
  EXPECT_EQ(Rational::parse(decimal_upper(Rational::parse("0.991"))), Rational(1));
  EXPECT_EQ(decimal_upper(Rational::parse("0.0015")), "0.0015");
}

TEST(Decimal, ScientificNotationOutsideTheExponentRange) {
  // Plain notation exactly for decimal exponents in [-7, 21).
  for (long k = -12; k <= 25; ++k) {
    SCOPED_TRACE("10^" + std::to_string(k));
    for (const Rational& x : {pow10(k), Rational::parse("1.25") * pow10(k), -Rational::parse("3.5") * pow10(k)}) {
      const std::string s = decimal_string(x, 5);
      EXPECT_EQ(Rational::parse(s), x) << s;
      const bool scientific = s.find('e') != std::string::npos;
      EXPECT_EQ(scientific, k < -7 || k >= 21) << s;
    }
  }
  EXPECT_EQ(decimal_string(Rational(0), 5), "0");
  EXPECT_EQ(decimal_string(Rational::parse("0.000123"), 3), "0.000123");
  EXPECT_EQ(decimal_string(Rational::parse("1249.05"), 6), "1249.05");
  EXPECT_EQ(decimal_string(Rational::parse("1.25e-30"), 3), "1.25e-30");
  EXPECT_THROW(decimal_string(Rational(1), 0), InvalidArgument);
}

TEST(Decimal, EnclosureContainsTheBallProperty) {
  std::mt19937_64 rng(4242);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Ball b = random_ball(rng);
    const long sig = std::uniform_int_distribution<long>(1, 25)(rng);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": ball " + b.str(30) + ", sig = " + std::to_string(sig));
    const DecimalEnclosure e = decimal_enclosure(b, sig);
    const Rational mid = Rational::parse(e.mid), rad = Rational::parse(e.rad);
    ASSERT_GE(rad.sign(), 0) << e.rad;
    const Rational m = mid_rational(b), r = rad_rational(b);
    EXPECT_LE(mid - rad, m - r) << e.mid << " +/- " << e.rad;
    EXPECT_GE(mid + rad, m + r) << e.mid << " +/- " << e.rad;
    EXPECT_LE(significant_digits(e.mid), sig) << e.mid;
    EXPECT_LE(significant_digits(e.rad), 2) << e.rad;
    // Not absurdly wide: the radius is at most the ball's plus one unit in the
    // last printed place of mid (the rounding error is half of one), rounded up.
    if (!m.is_zero()) {
      const Rational ulp = pow10(floor_log10(abs(m)) - sig + 1);
      EXPECT_LE(rad, (r + ulp) * Rational(11, 10)) << e.rad;
    }
  }
}

TEST(Decimal, EnclosureOfRationalBallsContainsTheRational) {
  std::mt19937_64 rng(31337);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Rational q = random_rational(rng);
    const long prec = std::uniform_int_distribution<long>(10, 300)(rng);
    const Ball b(q, prec);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": q = " + q.str());
    ASSERT_TRUE(b.contains(q));
    const DecimalEnclosure e = decimal_enclosure(b, 15);
    const Rational mid = Rational::parse(e.mid), rad = Rational::parse(e.rad);
    EXPECT_LE(abs(q - mid), rad) << e.mid << " +/- " << e.rad;
  }
}

TEST(Decimal, ExactBallsHaveZeroRadiusOnlyWhenPrintedExactly) {
  const DecimalEnclosure three = decimal_enclosure(Ball(3), 10);
  EXPECT_EQ(three.mid, "3");
  EXPECT_EQ(three.rad, "0");
  const DecimalEnclosure quarter = decimal_enclosure(Ball(Rational(1, 4), 64), 10);
  EXPECT_EQ(quarter.mid, "0.25");
  EXPECT_EQ(quarter.rad, "0");
  // 1/1024 is exact as a ball but needs 7 digits: at 3 digits the rounding
  // error must show up in the radius.
  const Ball tiny(Rational(1, 1024), 64);
  ASSERT_TRUE(tiny.is_exact());
  const DecimalEnclosure e = decimal_enclosure(tiny, 3);
  EXPECT_NE(e.rad, "0");
  EXPECT_LE(abs(Rational::parse(e.mid) - Rational(1, 1024)), Rational::parse(e.rad));
}

TEST(Decimal, NonFiniteBallIsADomainError) {
  Ball b;
  arb_indeterminate(b.get());
  EXPECT_THROW(decimal_enclosure(b, 5), DomainError);
  Ball inf(1);
  mag_inf(arb_radref(inf.get()));
  EXPECT_THROW(decimal_enclosure(inf, 5), DomainError);
}

}  // namespace
}  // namespace uniparam
