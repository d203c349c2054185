// RealAlgebraic::short_interval, the interval printed with an algebraic
// number: an isolating interval with short decimal ends (checked against an
// exact root count), a function of the number and its construction interval
// alone, and found without any root isolation (a work counter).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

// A random squarefree product of quadratics and cubics with integer
// coefficients in [-bound, bound] (a product of factors of nonzero
// discriminant is retried until it is squarefree).
Poly random_squarefree(std::mt19937_64& rng, int factors, long bound) {
  std::uniform_int_distribution<long> c(-bound, bound);
  for (;;) {
    Poly p(std::vector<Integer>{Integer(1)});
    for (int f = 0; f < factors; ++f) {
      std::vector<Integer> co;
      const int deg = 2 + f % 2;
      for (int i = 0; i <= deg; ++i) co.push_back(Integer(c(rng)));
      if (co.back().sign() == 0) co.back() = Integer(1);
      p = p * Poly(co);
    }
    if (p.degree() >= 2 && gcd(p, p.derivative()).degree() == 0) return p;
  }
}

// 10^-d for the d with w = 10^-d, or a flag that w is no power of ten.
bool is_power_of_ten(const Rational& w, long& d) {
  Rational t = w;
  d = 0;
  while (t < Rational(1)) { t = t * Rational(10); ++d; }
  while (Rational(1) < t) {
    if (!(t.den() == Integer(1))) return false;
    t = t / Rational(10);
    --d;
  }
  return t == Rational(1);
}

// Oracle: (L, H) holds exactly one root of x's polynomial (an exact root
// count), x is inside, neither end is a root, H - L = 10^-d and L is a
// multiple of 10^-d.
void expect_short_isolating(const RealAlgebraic& x, const std::pair<Rational, Rational>& iv) {
  const auto& [L, H] = iv;
  ASSERT_TRUE(L < H) << x.str();
  EXPECT_EQ(compare(RealAlgebraic(L), x), -1) << x.str();
  EXPECT_EQ(compare(x, RealAlgebraic(H)), -1) << x.str();
  EXPECT_NE(x.poly().sign_at(L), 0);
  EXPECT_NE(x.poly().sign_at(H), 0);
  EXPECT_EQ(count_real_roots(x.poly(), L, H), 1) << x.str() << " in (" << L.str() << ", " << H.str() << ")";
  long d = 0;
  ASSERT_TRUE(is_power_of_ten(H - L, d)) << L.str() << ", " << H.str();
  const Rational k = L / (H - L);
  EXPECT_EQ(k.den(), Integer(1)) << L.str() << " is no multiple of 10^" << -d;
}

TEST(AlgebraicPrint, ShortIntervalIsADecimalIsolatingCell) {
  std::mt19937_64 rng(2718);
  long checked = 0;
  for (long it = 0; it < iterations(8); ++it) {
    const Poly p = random_squarefree(rng, 2 + static_cast<int>(it % 3), 9 + 1000 * (it % 2));
    for (const IsolatedRoot& r : isolate_real_roots(p, Rational(-100), Rational(100))) {
      if (r.is_exact()) continue;
      const RealAlgebraic x(r);
      expect_short_isolating(x, x.short_interval());
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
}

// Close roots: the cell must be narrow enough to exclude the neighbour.
TEST(AlgebraicPrint, SeparatesCloseRoots) {
  // (t^2 - 2) (t^2 - 2 - 10^-12 t): two roots within about 10^-13 of sqrt(2)
  Integer big;
  fmpz_set_ui(big.get(), 10);
  fmpz_pow_ui(big.get(), big.get(), 12);
  const Poly a(std::vector<Integer>{Integer(-2), Integer(0), Integer(1)});
  const Poly b(std::vector<Integer>{Integer(-2) * big, Integer(-1), big});
  const Poly p = a * b;
  long seen = 0;
  for (const IsolatedRoot& r : isolate_real_roots(p, Rational(1), Rational(2))) {
    const RealAlgebraic x(r);
    expect_short_isolating(x, x.short_interval());
    ++seen;
  }
  EXPECT_EQ(seen, 2);
}

// Canonical: the same interval whatever the number was refined to before,
// so printed output does not depend on the order of evaluations (threads).
TEST(AlgebraicPrint, ShortIntervalDoesNotDependOnRefinement) {
  std::mt19937_64 rng(31415);
  for (long it = 0; it < iterations(6); ++it) {
    const Poly p = random_squarefree(rng, 3, 50);
    for (const IsolatedRoot& r : isolate_real_roots(p, Rational(-100), Rational(100))) {
      if (r.is_exact()) continue;
      const RealAlgebraic fresh(r), refined(r);
      refined.refine(20 + 37 * (it % 5));
      refined.to_ball(300);
      const auto a = fresh.short_interval(), b = refined.short_interval();
      EXPECT_EQ(a.first, b.first) << fresh.str();
      EXPECT_EQ(a.second, b.second) << fresh.str();
    }
  }
}

// Work: printing does not isolate roots again (the construction's isolating
// interval and refinement with exact signs at rationals suffice).
TEST(AlgebraicPrint, ShortIntervalIsolatesNothing) {
  std::mt19937_64 rng(161803);
  for (long it = 0; it < iterations(4); ++it) {
    const Poly p = random_squarefree(rng, 4, 99);
    for (const IsolatedRoot& r : isolate_real_roots(p, Rational(-100), Rational(100))) {
      if (r.is_exact()) continue;
      const RealAlgebraic x(r);
      x.to_ball(80);  // as the printers do first
      const long before = exact_isolations();
      const auto iv = x.short_interval();
      EXPECT_EQ(exact_isolations() - before, 0) << x.str();
      EXPECT_TRUE(iv.first < iv.second);
    }
  }
}

}  // namespace
}  // namespace uniparam
