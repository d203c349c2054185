// balance(p, speed) (reparam/scaling.hpp) on curves whose speed is
// concentrated next to one end because of a huge coefficient: which curves
// it balances (and to which side), that q = p o m exactly, and that the
// uniformity computed through q is the closed form.
#include <gtest/gtest.h>

#include <acb.h>
#include <arb.h>
#include <arb_fmpz_poly.h>
#include <flint/fmpz_poly.h>

#include <random>
#include <string>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "support/reference.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/reparam/scaling.hpp"

using namespace uniparam;

namespace {

constexpr double kBudgetSeconds = 300;

// 2^e as the decimal integer a curve's text takes.
std::string pow2_text(long e) { return pow2(e).str(); }

std::optional<BalancedCurve> balanced(const std::string& text, SpeedKind kind) {
  const Curve c = Curve::parse(text);
  return balance(c, Speed(c, kind));
}

// log2 (b / a) of a balanced curve (b / a is a power of 2 either way).
long log2_lambda(const BalancedCurve& bal) {
  return static_cast<long>(fmpz_bits(bal.b.get())) - static_cast<long>(fmpz_bits(bal.a.get()));
}

}  // namespace

// Must show: the angular speed 2C / (1 + 4 C^2 t^2) of (t, C t^2) with
// C = 2^60 is a peak of width 2^-61 at t = 0, balanced with lambda = b / a
// near 2C (m(1/2) = 1 / (1 + lambda) ~ 2^-61); mirrored at t = 1 the
// other way; and left alone: the parametric speed of the same curve
// (spread over [0, 1]), ordinary curves, and a space curve whose balanced
// curve would bring its singularities at |t| ~ C next to s = 1.
TEST(HugeCoeff, BalanceFollowsTheSpeedsMass) {
  const std::string C = pow2_text(60);
  const auto b0 = balanced("(t, " + C + "*t^2)", SpeedKind::Angular);
  ASSERT_TRUE(b0.has_value());
  EXPECT_GE(log2_lambda(*b0), 59);
  EXPECT_LE(log2_lambda(*b0), 63);
  const auto b1 = balanced("(t, " + C + "*(1-t)^2)", SpeedKind::Angular);
  ASSERT_TRUE(b1.has_value());
  EXPECT_LE(log2_lambda(*b1), -59);
  EXPECT_GE(log2_lambda(*b1), -63);
  EXPECT_FALSE(balanced("(t, " + C + "*t^2)", SpeedKind::Parametric).has_value());
  for (const char* ordinary : {"(t, t^2)", "(t, t^3)", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "(t, 1000*t^2)",
                               "(t^2, t^3 + t)", "(t, t^2, t^3)"})
    for (SpeedKind k : {SpeedKind::Angular, SpeedKind::Parametric})
      EXPECT_FALSE(balanced(ordinary, k).has_value()) << ordinary << " " << to_string(k);
  EXPECT_FALSE(balanced("(t, " + C + "*t^2, t^3)", SpeedKind::Angular).has_value());
}

// Must show: q = p o m exactly at rational s (p(m(s)) == q(s) in Q), and
// balance_map_ball encloses m(s) at s = 1/3 and over a ball.
TEST(HugeCoeff, BalancedPolynomialCurveIsExactComposition) {
  const Curve p = Curve::parse("(t, " + pow2_text(80) + "*t^2 + t)");
  const auto bal = balance(p, Speed(p, SpeedKind::Angular));
  ASSERT_TRUE(bal.has_value());
  const Rational a(bal->a), b(bal->b);
  for (const Rational s : {Rational(1, 3), Rational(5, 7), Rational(0), Rational(1)}) {
    const Rational t = a * s / (a * s + b * (Rational(1) - s));
    for (std::size_t i = 0; i < p.dimension(); ++i) {
      const RatFunc& pc = p.components()[i];
      const RatFunc& qc = bal->q.components()[i];
      EXPECT_EQ(pc.num()(t) / pc.den()(t), qc.num()(s) / qc.den()(s)) << i;
    }
    const Ball m = balance_map_ball(*bal, Ball(s, 256), 256);
    EXPECT_TRUE(arb_contains(m.get(), Ball(t, 512).get())) << m.str(20);
  }
  Ball s(Rational(1, 3), 256);
  arb_add_error_2exp_si(s.get(), -30);
  const Ball m = balance_map_ball(*bal, s, 256);
  for (const Rational x : {Rational(1, 3) - Rational(1, 1L << 31), Rational(1, 3) + Rational(1, 1L << 31)}) {
    const Rational t = a * x / (a * x + b * (Rational(1) - x));
    EXPECT_TRUE(arb_contains(m.get(), Ball(t, 512).get())) << m.str(20);
  }
}

// Must show: the uniformity of (t, C t^2), C = 7^300 (balanced), contains the
// closed form: mu = atan K, int sigma^2 = (K / 2)(atan K + K / (1 + K^2)),
// K = 2C.
TEST(HugeCoeff, BalancedUniformityMatchesClosedForm) {
  TimeBudget budget(kBudgetSeconds);
  Integer C(1);
  for (int i = 0; i < 300; ++i) C = C * Integer(7);
  const Curve p = Curve::parse("(t, " + C.str() + "*t^2)");
  ASSERT_TRUE(balance(p, Speed(p, SpeedKind::Angular)).has_value());
  Options o;
  o.digits = 30;
  const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
  Ball c;
  arb_set_fmpz(c.get(), C.get());
  const test_support::ParabolaAngular ref = test_support::parabola_angular(c, 4096);
  const Ball &at = ref.mu, &u = ref.u;
  EXPECT_TRUE(arb_overlaps(r.mu.get(), at.get())) << r.mu.str(35);
  EXPECT_TRUE(arb_overlaps(r.u.get(), u.get())) << r.u.str(35) << " vs " << u.str(35);
  EXPECT_TRUE(r.u.meets_digits(o.digits)) << r.u.str(35);
}

namespace {

// Whether every nonzero complex root of p lies at distance >= 2^-d from 0
// and (roots of p(1 + t)) from 1, by Arb's certified roots.
::testing::AssertionResult roots_at_least(const Poly& p, long d) {
  if (p.degree() < 1) return ::testing::AssertionSuccess();
  for (int end = 0; end < 2; ++end) {
    Poly q = p;
    if (end == 1) {
      fmpz_t one;
      fmpz_init_set_ui(one, 1);
      fmpz_poly_taylor_shift(q.get(), p.get(), one);
      fmpz_clear(one);
    }
    long v = 0;
    while (v <= q.degree() && q.coeff(v).sign() == 0) ++v;
    std::vector<Integer> c;
    for (long k = v; k <= q.degree(); ++k) c.push_back(q.coeff(k));
    const Poly r(c);
    if (r.degree() < 1) continue;
    acb_ptr roots = _acb_vec_init(r.degree());
    arb_fmpz_poly_complex_roots(roots, r.get(), 0, 512);
    Ball m, bound(1);
    arb_mul_2exp_si(bound.get(), bound.get(), -d);
    bool ok = true;
    for (long i = 0; i < r.degree() && ok; ++i) {
      acb_abs(m.get(), roots + i, 512);
      ok = arb_ge(m.get(), bound.get()) != 0;
    }
    _acb_vec_clear(roots, r.degree());
    if (!ok) return ::testing::AssertionFailure() << "a root of " << p.str() << " within 2^-" << d << " of " << end;
  }
  return ::testing::AssertionSuccess();
}

}  // namespace

// Must show: the scale on which the speed varies next to the ends
// (speed_scale_bits) follows its roots and poles, not the size of its
// coefficients: (t, 2^k t^2) has its peak of width 2^-k at t = 0 (scale
// about k bits) while its balanced curve, whose coefficients have ~2k
// bits, has its features at distances of order 1 (a few bits whatever k:
// the quadrature's samples and budgets no longer grow with the numbers);
// and on random curves the scale is certified: no zero, pole or branch
// point of sigma (roots of g, D, sum K^2) lies within 2^-scale of 0 or 1.
TEST(HugeCoeff, ScaleBitsFollowTheRootsNotTheCoefficients) {
  for (long k : {60L, 600L, 6000L}) {
    SCOPED_TRACE(k);
    const Curve p = Curve::parse("(t, " + pow2_text(k) + "*t^2)");
    const Speed s(p, SpeedKind::Angular);
    EXPECT_GE(speed_scale_bits(s), k);
    EXPECT_LE(speed_scale_bits(s), k + 8);
    const auto bal = balance(p, s);
    ASSERT_TRUE(bal.has_value());
    const Speed sq(bal->q, SpeedKind::Angular);
    EXPECT_LE(speed_scale_bits(sq), 8);
    EXPECT_GE(speed_coefficient_bits(sq), k);  // the sizes stay: only the scale is small
  }
  std::mt19937_64 rng(test_support::test_seed(8104));
  for (long it = 0; it < test_support::iterations(40); ++it) {
    std::vector<RatFunc> comps;
    for (int i = 0; i < 2 + static_cast<int>(it % 2); ++i)
      comps.emplace_back(test_support::random_poly(rng, 1 + static_cast<long>(rng() % 4), 1000));
    Curve c = Curve::parse("(t, t^2)");
    try {
      c = Curve(comps);
    } catch (const std::exception&) {
      continue;  // constant: not a curve
    }
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(c, kind);
      if (s.identically_zero()) continue;
      const long d = speed_scale_bits(s);
      Poly K2(0);
      for (const Poly& q : s.cofactors()) K2 = K2 + q * q;
      EXPECT_TRUE(roots_at_least(s.g(), d)) << c.str();
      EXPECT_TRUE(roots_at_least(s.denominator(), d)) << c.str();
      EXPECT_TRUE(roots_at_least(K2, d)) << c.str();
    }
  }
}
