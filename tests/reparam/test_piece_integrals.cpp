// piece_integrals A, B, C on pieces without zeros, against exact rationals:
// a polynomial curve's parametric speed has a polynomial sigma^2, so
//     A = Delta t^2 int_0^1 sigma^2(a + Delta t s) (1 - s)^2 ds
// (B with 2 s (1 - s), C with s^2) is rational. At 15 and 20 digits the
// quadrature's nodes take the double-word path (QuadratureOptions::
// node_fast), at 40 the Arb one: both must hold the exact values.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/uniparam.hpp"

using namespace uniparam;

namespace {

using QPoly = std::vector<Rational>;  // coefficients over Q, low to high

QPoly mul(const QPoly& x, const QPoly& y) {
  QPoly r(x.size() + y.size() - 1, Rational(0));
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = 0; j < y.size(); ++j) r[i + j] = r[i + j] + x[i] * y[j];
  return r;
}

// int_0^1 q(s) w(s) ds
Rational integral01(const QPoly& q, const QPoly& w) {
  const QPoly p = mul(q, w);
  Rational s(0);
  for (std::size_t k = 0; k < p.size(); ++k) s = s + p[k] / Rational(static_cast<long>(k) + 1);
  return s;
}

// p(a + h s) as a polynomial in s (Horner over Q)
QPoly shifted(const Poly& p, const Rational& a, const Rational& h) {
  QPoly r = {Rational(0)};
  for (long k = p.degree(); k >= 0; --k) {
    Integer c;
    fmpz_set(c.get(), p.get()->coeffs + k);
    r = mul(r, {a, h});
    r[0] = r[0] + Rational(c);
  }
  return r;
}

}  // namespace

TEST(PieceIntegrals, ContainTheExactMomentsOfAPolynomialSquaredSpeed) {
  std::mt19937_64 rng(20261123u);
  std::uniform_int_distribution<long> coef(-9, 9), deg(2, 6), num(0, 19);
  const long n = uniparam::test_support::iterations(8);
  for (long it = 0; it < n; ++it) {
    // (t, y(t)) or (t, y(t), z(t)): x' = 1, so sigma has no zero
    std::vector<RatFunc> comps = {RatFunc(Poly::t())};
    for (int i = 0; i < 1 + static_cast<int>(it % 2); ++i) {
      std::vector<long> c(static_cast<std::size_t>(deg(rng)) + 1);
      for (long& x : c) x = coef(rng);
      comps.emplace_back(Poly(c));
    }
    const Curve c(comps);
    const Speed s(c, SpeedKind::Parametric);
    Rational a(num(rng), 20), b(num(rng), 20);
    if (b < a) std::swap(a, b);
    if (a == b) b = b + Rational(1, 20);
    const Poly sigma2 = s.squared().num();  // denominator 1 for a polynomial curve
    ASSERT_EQ(s.squared().den(), Poly(1));
    const Rational h = b - a;
    const QPoly q = shifted(sigma2, a, h);
    const Rational A = h * h * integral01(q, {Rational(1), Rational(-2), Rational(1)});
    const Rational B = h * h * integral01(q, {Rational(0), Rational(2), Rational(-2)});
    const Rational C = h * h * integral01(q, {Rational(0), Rational(0), Rational(1)});
    for (long bits : {50L, 66L, 133L}) {
      SCOPED_TRACE(c.str() + " on [" + a.str() + ", " + b.str() + "] at " + std::to_string(bits) + " bits");
      const PieceIntegrals pi = piece_integrals(s, Breakpoint{RealAlgebraic(a)}, Breakpoint{RealAlgebraic(b)}, bits, 4096);
      EXPECT_TRUE(pi.A.contains(A)) << pi.A.str(30) << " exact " << A.str();
      EXPECT_TRUE(pi.B.contains(B)) << pi.B.str(30) << " exact " << B.str();
      EXPECT_TRUE(pi.C.contains(C)) << pi.C.str(30) << " exact " << C.str();
      EXPECT_TRUE(pi.A.meets_digits(bits * 3 / 10)) << pi.A.str(30);
    }
  }
}
