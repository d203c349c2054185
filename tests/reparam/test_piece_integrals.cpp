// piece_integrals A, B, C against exact rationals, on pieces without zeros
// and (second test) next to a zero of the speed:
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
#include "uniparam/reparam/all.hpp"

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

namespace {

// x(s)^k as a polynomial in s, for x = {x0, x1} (linear)
QPoly power(const QPoly& x, int k) {
  QPoly r = {Rational(1)};
  for (int i = 0; i < k; ++i) r = mul(r, x);
  return r;
}

// q(s) / s^m, exactly (the m lowest coefficients must be 0)
QPoly divide_by_power(const QPoly& q, int m) {
  for (int k = 0; k < m && k < static_cast<int>(q.size()); ++k) EXPECT_TRUE(q[static_cast<std::size_t>(k)].is_zero());
  return QPoly(q.begin() + std::min<std::ptrdiff_t>(m, static_cast<std::ptrdiff_t>(q.size())), q.end());
}

}  // namespace

TEST(PieceIntegrals, ContainTheExactMomentsNextToAZeroOfTheSpeed) {
  // A polynomial plane curve with p' = (t - g)^m (c, v(t)), g = k / d: its
  // parametric speed vanishes at g with multiplicity m, and sigma^2 =
  // (t - g)^(2m) (c^2 + v^2) is a polynomial. With g an end of the piece
  // (side = +1 at the left end, -1 at the right; r the distance to g over
  // Delta t), the piece integrals are
  //     Delta t^2 / (m + 1) int_0^1 sigma^2(g + side Delta t r) / r^m W(r) dr,
  // W = (1 - r^(m+1))^2, 2 r^(m+1) (1 - r^(m+1)), r^(2(m+1)) for A, B, C at
  // the left end (reversed at the right), and int sigma^2 = Delta t
  // int_0^1 sigma^2 ds: rationals. At 50 and 66 bits the nodes take the
  // double-word path (divided by (t - g)^m), at 133 the Arb one.
  std::mt19937_64 rng(20261124u);
  std::uniform_int_distribution<long> coef(-9, 9), cst(1, 9), deg(0, 3), den(3, 11), mult(1, 2);
  const long n = uniparam::test_support::iterations(8);
  for (long it = 0; it < n; ++it) {
    const long d = den(rng);
    const long k = std::uniform_int_distribution<long>(1, d - 1)(rng);
    const Rational g(k, d);
    const int m = static_cast<int>(mult(rng));
    // p' = (d t - k)^m (c, v): integrate over Q, then clear denominators
    std::vector<long> v(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : v) x = coef(rng);
    const Poly lin(std::vector<long>{-k, d});
    Poly lm(1);
    for (int i = 0; i < m; ++i) lm = lm * lin;
    const Poly dx = lm * Poly(cst(rng)), dy = lm * Poly(v);
    auto antiderivative = [](const Poly& p, long scale) {  // scale * int_0^t p, exact when scale clears 1/(j+1)
      std::vector<long> c(static_cast<std::size_t>(p.degree()) + 2, 0);
      for (long j = 0; j <= p.degree(); ++j) {
        Integer cj;
        fmpz_set(cj.get(), p.get()->coeffs + j);
        c[static_cast<std::size_t>(j) + 1] = fmpz_get_si(cj.get()) * (scale / (j + 1));
      }
      return Poly(c);
    };
    const long L = 420;  // lcm(1..7) covers degrees <= 6
    const Curve c({RatFunc(antiderivative(dx, L)), RatFunc(antiderivative(dy, L))});
    const Speed s(c, SpeedKind::Parametric);
    ASSERT_EQ(s.squared().den(), Poly(1));
    const Poly sigma2 = s.squared().num();
    std::vector<Breakpoint> bp = mark_zeros(s, {RealAlgebraic(0), RealAlgebraic(g), RealAlgebraic(1)});
    ASSERT_EQ(bp[1].multiplicity, m) << c.str();
    // the other end: a non-dyadic rational on either side of g
    const bool left = it % 2 == 0;  // g is the piece's left end
    const Rational other = left ? g + (Rational(1) - g) * Rational(5, 7) : g * Rational(2, 7);
    const Rational a = left ? g : other, b = left ? other : g;
    const Rational h = b - a;
    // sigma^2(g + side h r) in r, divided by r^m, times h^2 / (m + 1)
    const QPoly q = divide_by_power(shifted(sigma2, g, left ? h : -h), m);
    const QPoly rp = power({Rational(0), Rational(1)}, m + 1);  // r^(m+1)
    QPoly om = rp;
    for (auto& x : om) x = -x;
    om[0] = om[0] + Rational(1);  // 1 - r^(m+1)
    const QPoly WA = mul(om, om), WB = mul(mul({Rational(2)}, rp), om), WC = mul(rp, rp);
    const Rational f = h * h / Rational(m + 1);
    const Rational A = f * integral01(q, left ? WA : WC), B = f * integral01(q, WB), C = f * integral01(q, left ? WC : WA);
    const Rational S = h * integral01(shifted(sigma2, a, h), {Rational(1)});
    const Breakpoint ba = left ? bp[1] : Breakpoint{RealAlgebraic(a)};
    const Breakpoint bb = left ? Breakpoint{RealAlgebraic(b)} : bp[1];
    for (long bits : {50L, 66L, 133L}) {
      SCOPED_TRACE(c.str() + " on [" + a.str() + ", " + b.str() + "], zero at " + g.str() + " of multiplicity " +
                   std::to_string(m) + ", " + std::to_string(bits) + " bits");
      const PieceIntegrals pi = piece_integrals(s, ba, bb, bits, 4096);
      EXPECT_TRUE(pi.A.contains(A)) << pi.A.str(30) << " exact " << A.str();
      EXPECT_TRUE(pi.B.contains(B)) << pi.B.str(30) << " exact " << B.str();
      EXPECT_TRUE(pi.C.contains(C)) << pi.C.str(30) << " exact " << C.str();
      EXPECT_TRUE(pi.square.contains(S)) << pi.square.str(30) << " exact " << S.str();
      EXPECT_TRUE(pi.A.meets_digits(bits * 3 / 10)) << pi.A.str(30);
    }
  }
}
