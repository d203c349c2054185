// Tests of Integer and Rational (core/number.hpp): exact parsing, canonical
// form, arithmetic against independent constructions, and every error kind.
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/ratfunc.hpp"

#include <type_traits>

namespace uniparam {
namespace {

using test_support::iterations;
using test_support::random_digits;

Integer pow10(long k) {
  Integer p;
  fmpz_set_ui(p.get(), 10);
  fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(k));
  return p;
}

// ---- Integer ------------------------------------------------------------------

TEST(Integer, ParsesDecimalStrings) {
  EXPECT_EQ(Integer("0"), Integer(0));
  EXPECT_EQ(Integer("123"), Integer(123));
  EXPECT_EQ(Integer("-45"), Integer(-45));
  EXPECT_EQ(Integer("007"), Integer(7));
  EXPECT_EQ(Integer("-123456789012345678901234567890").str(), "-123456789012345678901234567890");
}

TEST(Integer, RejectsNonIntegers) {
  for (const char* bad : {"", "-", "+5", " 5", "5 ", "12a", "1.0", "1e3", "--1", "0x10"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(Integer{std::string(bad)}, InvalidArgument);
  }
}

TEST(Integer, ArithmeticMatchesDecimalStrings) {
  // (10^30 + 1) * (10^30 - 1) = 10^60 - 1, written out independently.
  const Integer a = pow10(30) + Integer(1), b = pow10(30) - Integer(1);
  EXPECT_EQ((a * b).str(), std::string(60, '9'));
  EXPECT_EQ((a - b).str(), "2");
  EXPECT_EQ((a + b).str(), "2" + std::string(30, '0'));
  EXPECT_EQ(pow10(30).bits(), 100);  // 2^99 < 10^30 < 2^100
  EXPECT_EQ(Integer(0).bits(), 0);
  EXPECT_EQ(Integer(-8).sign(), -1);
  EXPECT_TRUE(Integer(-8) < Integer(3));
}

TEST(Integer, StringRoundTripProperty) {
  std::mt19937_64 rng(20240601);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    std::string s = random_digits(rng, 60);
    s.erase(0, std::min(s.find_first_not_of('0'), s.size() - 1));  // canonical: no leading zeros
    if (rng() & 1 && s != "0") s = "-" + s;
    SCOPED_TRACE("iteration " + std::to_string(it) + ": " + s);
    EXPECT_EQ(Integer(s).str(), s);
  }
}

// ---- Rational -----------------------------------------------------------------

TEST(Rational, ParsesDecimalsExactly) {
  EXPECT_EQ(Rational::parse("0.1"), Rational(1, 10));
  EXPECT_NE(Rational::parse("0.1"), Rational(0));
  EXPECT_EQ(Rational::parse("1e-3"), Rational(1, 1000));
  EXPECT_EQ(Rational::parse("2.5e+2"), Rational(250));
  EXPECT_EQ(Rational::parse("1E3"), Rational(1000));
  EXPECT_EQ(Rational::parse("-1.25"), Rational(-5, 4));
  EXPECT_EQ(Rational::parse(".5"), Rational(1, 2));
  EXPECT_EQ(Rational::parse("-.5"), Rational(-1, 2));
  EXPECT_EQ(Rational::parse("0.000"), Rational(0));
  EXPECT_EQ(Rational::parse("12.5e-1"), Rational(5, 4));
  // 0.1 + 0.2 == 0.3 exactly, unlike binary floating point.
  EXPECT_EQ(Rational::parse("0.1") + Rational::parse("0.2"), Rational::parse("0.3"));
}

TEST(Rational, ParsesFractionsToCanonicalForm) {
  EXPECT_EQ(Rational::parse("-2/4"), Rational(-1, 2));
  EXPECT_EQ(Rational::parse("-2/4").str(), "-1/2");
  EXPECT_EQ(Rational::parse("6/3").str(), "2");
  EXPECT_EQ(Rational::parse("0/5"), Rational(0));
  EXPECT_EQ(Rational::parse("17"), Rational(17));
  const Rational q = Rational::parse("-14/21");
  EXPECT_EQ(q.num(), Integer(-2));
  EXPECT_EQ(q.den(), Integer(3));
  EXPECT_TRUE(Rational(Integer(3), Integer(-6)).den().sign() > 0);
}

TEST(Rational, ParseErrorsGiveColumns) {
  struct Case { const char* text; std::size_t column; };
  const Case cases[] = {
      {"", 1}, {"abc", 1}, {"-", 2}, {".", 2}, {"1/", 3}, {"/2", 1}, {"1.2.3", 4},
      {"1e", 3}, {"1e+", 4}, {"--1", 2}, {"1.5/2", 4}, {"1/2/3", 4}, {"1.2x", 4}, {"1 ", 2},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(std::string("input '") + c.text + "'");
    try {
      Rational::parse(c.text);
      ADD_FAILURE() << "no exception";
    } catch (const ParseError& e) {
      EXPECT_EQ(e.column(), c.column) << e.what();
      EXPECT_FALSE(e.expected().empty());
      EXPECT_NE(std::string(e.what()).find("column " + std::to_string(c.column)), std::string::npos);
    }
  }
}

TEST(Rational, DivisionByZeroIsADomainError) {
  EXPECT_THROW(Rational::parse("1/0"), DomainError);
  EXPECT_THROW(Rational(1, 0), DomainError);
  EXPECT_THROW(Rational(1) / Rational(0), DomainError);
  EXPECT_THROW(Rational::parse("1e1234567"), InvalidArgument);  // exponent out of range
}

TEST(Rational, StringRoundTripAndDecimalProperty) {
  std::mt19937_64 rng(77);
  const long iters = iterations(200);
  std::uniform_int_distribution<int> small(0, 12);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it));
    // p/q with random big p, q: str() then parse() is the identity.
    Integer p(random_digits(rng, 40)), q(random_digits(rng, 40));
    if (q.sign() == 0) q = Integer(1);
    if (rng() & 1) p = Integer(0) - p;
    const Rational r(p, q);
    EXPECT_EQ(Rational::parse(r.str()), r) << r.str();
    // A decimal "I.F e E" equals (I*10^|F| + F) / 10^|F| * 10^E, built here without parsing.
    const std::string ip = random_digits(rng, 15), fp = random_digits(rng, 15);
    const long e = small(rng) - 6;
    const std::string text = ip + "." + fp + "e" + std::to_string(e);
    Rational expect(Integer(ip + fp), pow10(static_cast<long>(fp.size())));
    expect = e >= 0 ? expect * Rational(pow10(e)) : expect / Rational(pow10(-e));
    EXPECT_EQ(Rational::parse(text), expect) << text;
    EXPECT_EQ(Rational::parse("-" + text), -expect) << text;
  }
}

TEST(Rational, OrderingAndArithmetic) {
  const Rational a(1, 3), b(1, 2);
  EXPECT_TRUE(a < b);
  EXPECT_TRUE(b >= a);
  EXPECT_EQ(a + b, Rational(5, 6));
  EXPECT_EQ(a - b, Rational(-1, 6));
  EXPECT_EQ(a * b, Rational(1, 6));
  EXPECT_EQ(a / b, Rational(2, 3));
  EXPECT_EQ(-a, Rational(-1, 3));
  EXPECT_TRUE(Rational(4, 2).is_integer());
  EXPECT_FALSE(a.is_integer());
}

// primitive() against FLINT's primitive part on random polynomials times a
// random integer (content 1 or not, either sign of the leading coefficient,
// zero coefficients, the zero polynomial): the same polynomial, primitive
// with a positive leading coefficient.
TEST(Poly, PrimitiveMatchesFlintsPrimitivePart) {
  std::mt19937_64 rng(4401);
  std::uniform_int_distribution<long> coef(-50, 50), deg(-1, 12), scale(-6, 6);
  for (long it = 0; it < iterations(400); ++it) {
    const long n = deg(rng);
    std::vector<long> c(static_cast<std::size_t>(n + 1));
    for (auto& x : c) x = coef(rng) * (rng() % 3 == 0 ? 0 : 1);
    long k = scale(rng);
    if (k == 0) k = 1;
    const Poly p = Poly(c) * Poly(k);
    Poly want;
    fmpz_poly_primitive_part(want.get(), p.get());
    const Poly got = p.primitive();
    EXPECT_EQ(got, want) << p.str();
    if (!got.is_zero()) {
      EXPECT_GT(got.leading().sign(), 0) << p.str();
      Integer content;
      fmpz_poly_content(content.get(), got.get());
      EXPECT_TRUE(content == Integer(1)) << p.str();
    }
  }
}

}  // namespace
}  // namespace uniparam

// No implicit (or explicit) conversion from double into an exact or ball type.
static_assert(!std::is_convertible_v<double, uniparam::Rational>, "double must not convert to Rational");
static_assert(!std::is_constructible_v<uniparam::Rational, double>, "no Rational from double");
static_assert(!std::is_constructible_v<uniparam::Integer, double>, "no Integer from double");
static_assert(!std::is_constructible_v<uniparam::Poly, double>, "no Poly from double");
static_assert(!std::is_constructible_v<uniparam::RatFunc, double>, "no RatFunc from double");
static_assert(!std::is_constructible_v<uniparam::Ball, double>, "no Ball from double");
