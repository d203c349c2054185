// Speed evaluation against exact oracles: components with mixed
// denominators against the exact squared speed, the critical numerator from
// factors, the angular denominator, the double-word path at node balls, and
// the singularity hints of high-degree curves.
#include <acb_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "reparam/speed_eval_support.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

using uniparam::speed_eval_test::random_bezier;

namespace {

/// A polynomial of degree d with coefficients in [-9, 9], or in [1, 9]
/// (positive: no zeros on [0, 1]) -- the components and weights below.
Poly small_poly(std::mt19937_64& rng, long d, bool positive) {
  std::uniform_int_distribution<long> coef(-9, 9), pos(1, 9);
  std::vector<long> c;
  for (long k = 0; k <= d; ++k) c.push_back(positive ? pos(rng) : coef(rng));
  return Poly(c);
}

/// The speed of a random curve, or null when the curve is not regular on
/// [0, 1] (Speed's DomainError): such curves are skipped.
std::unique_ptr<Speed> regular_speed(const Curve& c, SpeedKind kind) {
  try {
    return std::make_unique<Speed>(c, kind);
  } catch (const DomainError&) {
    return nullptr;
  }
}

}  // namespace

TEST(SpeedEval, ComponentsWithMixedDenominatorsAgreeWithTheExactSquaredSpeed) {
  // Components sharing a denominator evaluate it once per ball; others their
  // own. A curve whose components alternate between two weights (and one
  // with a common weight, and a polynomial component) must give sigma^2 at
  // rational points whose enclosure holds the exact value of squared().
  std::mt19937_64 rng(11);
  std::uniform_int_distribution<long> den(1, 64);
  long checked = 0;
  for (long it = 0; it < test_support::iterations(8); ++it) {
    auto random_poly = [&](long d, bool positive) { return small_poly(rng, d, positive); };
    const long d = 2 + static_cast<long>(rng() % 5);
    const Poly W1 = random_poly(d, true), W2 = random_poly(d, true);  // no zeros on [0, 1]
    std::vector<RatFunc> comps;
    const int pattern = static_cast<int>(it % 3);  // 0: W1 W2 W1; 1: W1 W1 W1; 2: W1 1 W2
    comps.emplace_back(random_poly(d, false), W1);
    comps.emplace_back(random_poly(d, false), pattern == 0 ? W2 : pattern == 1 ? W1 : Poly(1));
    comps.emplace_back(random_poly(d, false), pattern == 1 ? W1 : pattern == 0 ? W1 : W2);
    Curve c(comps);
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const std::unique_ptr<Speed> s = regular_speed(c, kind);
      if (!s || s->squared().num().is_zero()) continue;
      acb_t z, out;
      acb_init(z);
      acb_init(out);
      for (int p = 0; p < 6; ++p) {
        const long q = den(rng);
        const Rational t(static_cast<long>(rng() % static_cast<unsigned long>(q + 1)), q);
        acb_zero(z);
        arb_set_fmpq(acb_realref(z), t.get(), 256);
        s->eval_squared(out, z, 128);
        ASSERT_TRUE(acb_is_finite(out));
        ASSERT_TRUE(arb_contains_zero(acb_imagref(out)));
        const Ball re(acb_realref(out));
        ASSERT_TRUE(re.contains(s->squared()(t)))
            << c.str() << " " << to_string(kind) << " at t = " << t.str() << ": " << re.str(20);
        ++checked;
      }
      acb_clear(z);
      acb_clear(out);
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(SpeedEval, CriticalNumeratorFromFactorsContainsTheExactOne) {
  // eval_critical gives P = 2 g' Q D + g Q' D - 2 g Q D' (Q = sum K^2) and P'
  // from the factors' local expansions; the root isolation of the critical
  // points trusts both (P' decides monotonicity). Oracle: P formed exactly
  // from the public factors g, K, D, evaluated at rational points, inside
  // point balls and wide balls around them.
  std::mt19937_64 rng(2026);
  std::uniform_int_distribution<long> den(1, 64);
  long checked = 0;
  for (long it = 0; it < test_support::iterations(8); ++it) {
    auto random_poly = [&](long d, bool positive) { return small_poly(rng, d, positive); };
    const long d = 2 + static_cast<long>(rng() % 6);
    const Poly W = random_poly(d, true);  // no zeros on [0, 1]
    const bool rational = it % 2 == 1;
    const std::size_t dim = it % 4 < 2 ? 2 : 3;
    std::vector<RatFunc> comps;
    for (std::size_t i = 0; i < dim; ++i) comps.emplace_back(random_poly(d, false), rational ? W : Poly(1));
    Curve c(comps);
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const std::unique_ptr<Speed> s = regular_speed(c, kind);
      if (!s || s->identically_zero()) continue;
      Poly Q(0);
      for (const Poly& k : s->cofactors()) Q = Q + k * k;
      const Poly& g = s->g();
      const Poly& D = s->denominator();
      const Poly P = Poly(2) * g.derivative() * Q * D + g * Q.derivative() * D - Poly(2) * g * Q * D.derivative();
      const Poly dP = P.derivative();
      acb_t z, v, dv;
      acb_init(z);
      acb_init(v);
      acb_init(dv);
      for (int p = 0; p < 6; ++p) {
        const long q = den(rng);
        const Rational t(static_cast<long>(rng() % static_cast<unsigned long>(q + 1)), q);
        for (bool wide : {false, true}) {
          acb_zero(z);
          arb_set_fmpq(acb_realref(z), t.get(), 256);
          if (wide) {
            mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -10);
            mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), 1, -11);
          }
          s->eval_critical(v, dv, z, 128);
          ASSERT_TRUE(acb_is_finite(v) && acb_is_finite(dv));
          const Ball re(acb_realref(v)), dre(acb_realref(dv));
          ASSERT_TRUE(re.contains(P(t)) && arb_contains_zero(acb_imagref(v)))
              << c.str() << " " << to_string(kind) << " at t = " << t.str() << (wide ? " (wide)" : "");
          ASSERT_TRUE(dre.contains(dP(t)) && arb_contains_zero(acb_imagref(dv)))
              << c.str() << " " << to_string(kind) << " P' at t = " << t.str() << (wide ? " (wide)" : "");
          ++checked;
        }
      }
      acb_clear(z);
      acb_clear(v);
      acb_clear(dv);
    }
  }
  EXPECT_GT(checked, 40);
}

// The angular speed's denominator D = sum Y_i^2 (Y = X / gcd(X)) is never
// checked for roots in [0, 1]: the Y_i are coprime, so D > 0 on the whole
// real line. Checked exactly here on the curves where that could fail:
// singular points, p'(a) = 0, at random rational and irrational a in [0, 1]
// (a common factor m(t) of every X_i, which D would keep if the Y_i were not
// reduced), plane and space, and random rational Bezier curves.
TEST(SpeedEval, AngularDenominatorHasNoRealRootEvenWhereTheDerivativeVanishes) {
  std::mt19937_64 rng(20261123);
  std::uniform_int_distribution<long> num(1, 99), small(-5, 5);
  long checked = 0;
  for (long it = 0; it < test_support::iterations(12); ++it) {
    const std::string a = std::to_string(num(rng)) + "/100";
    // m vanishes in [0, 1]: at a, or at sqrt(a) (irrational unless a square).
    const std::string m = it % 2 ? "(t - " + a + ")" : "(t^2 - " + a + ")";
    const std::string x = m + "^2", y = m + "^3 + (" + std::to_string(small(rng)) + "*t + 1)*" + m + "^2";
    const std::string z = std::to_string(small(rng)) + "*" + m + "^3 + t*" + m + "^2";
    std::vector<Curve> curves = {parse_curve("(" + x + ", " + y + ")"), parse_curve("(" + x + ", " + y + ", " + z + ")"),
                                 random_bezier(rng, 3 + it % 5, 2 + it % 2, true)};
    for (const Curve& c : curves) {
      const Speed s(c, SpeedKind::Angular);
      if (s.identically_zero()) continue;
      const Poly& D = s.denominator();
      ASSERT_GT(D.degree(), -1) << c.str();
      EXPECT_TRUE(isolate_real_roots(D, Rational(-4), Rational(4)).empty()) << c.str() << ": D = " << D.str();
      ++checked;
    }
  }
  EXPECT_GE(checked, 30);
}

TEST(SpeedEval, DoubleWordPathContainsTheExactSpeedAtNodeBalls) {
  // The quadrature's nodes are real balls of tiny radius at ~70-100 bits:
  // there eval and eval_squared first try Horner's rule in double-word balls
  // (eval_double_word). Whenever it answers, sigma^2 must hold the exact
  // squared() at rational points of the ball, sigma (from a piece's signs)
  // the square root of it with the piece's sign, and both must agree with
  // the Arb path at 256 bits. Plane, space, polynomial and rational curves
  // (with a common weight and with one denominator per component), angular
  // and parametric.
  std::mt19937_64 rng(21);
  std::uniform_int_distribution<long> num(0, 1 << 20), prec(64, 110);
  long answered = 0, checked = 0;
  for (long it = 0; it < test_support::iterations(24); ++it) {
    const long d = 2 + static_cast<long>(rng() % 9);
    const std::size_t dim = 2 + static_cast<std::size_t>(it % 2);
    Curve c = random_bezier(rng, d, dim, it % 4 == 2);
    if (it % 4 == 3) {  // a different denominator per component
      std::vector<RatFunc> comps;
      for (std::size_t i = 0; i < dim; ++i) comps.emplace_back(small_poly(rng, d, false), small_poly(rng, d, true));
      c = Curve(comps);
    }
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const std::unique_ptr<Speed> s = regular_speed(c, kind);
      if (!s || s->squared().num().is_zero()) continue;
      acb_t z, dw, ref;
      acb_init(z);
      acb_init(dw);
      acb_init(ref);
      for (int p = 0; p < 8; ++p) {
        const Rational t(num(rng), 1 << 20);
        const long wp = prec(rng);
        acb_zero(z);
        arb_set_fmpq(acb_realref(z), t.get(), wp);  // a node: radius ~2^-wp
        if (!s->eval_double_word(dw, z, Speed::PieceSigns{}, true, wp)) continue;
        ++answered;
        ASSERT_TRUE(arb_is_zero(acb_imagref(dw)));
        ASSERT_LE(mag_cmp_2exp_si(arb_radref(acb_realref(dw)), 0), 0);
        {  // the promised accuracy: relative radius <= 2^-(wp - kNodeFastSlackBits)
          mag_t m;
          mag_init(m);
          arf_get_mag(m, arb_midref(acb_realref(dw)));
          mag_mul_2exp_si(m, m, -(wp - kNodeFastSlackBits));
          EXPECT_LE(mag_cmp(arb_radref(acb_realref(dw)), m), 0) << c.str() << " at " << t.str() << ", wp " << wp;
          mag_clear(m);
        }
        // every point of z: its ends and t
        arb_t e;
        arb_init(e);
        for (int side = -1; side <= 1; ++side) {
          arf_set_mag(arb_midref(e), arb_radref(acb_realref(z)));
          arf_mul_si(arb_midref(e), arb_midref(e), side, ARF_PREC_EXACT, ARF_RND_DOWN);
          arf_add(arb_midref(e), arb_midref(e), arb_midref(acb_realref(z)), ARF_PREC_EXACT, ARF_RND_DOWN);
          mag_zero(arb_radref(e));
          Rational pt;
          arf_get_fmpq(pt.get(), arb_midref(e));
          const Ball re(acb_realref(dw));
          ASSERT_TRUE(re.contains(s->squared()(pt)))
              << c.str() << " " << to_string(kind) << " at t = " << pt.str() << ": " << re.str(20);
        }
        arb_clear(e);
        // sigma itself, against the Arb path at 256 bits (the ball's midpoint)
        const Speed::PieceSigns sg{};
        if (s->eval_double_word(dw, z, sg, false, wp)) {
          acb_zero(ref);
          arb_set_fmpq(acb_realref(ref), t.get(), 256);
          acb_t v;
          acb_init(v);
          s->eval(v, ref, sg, false, 256);
          ASSERT_TRUE(acb_overlaps(dw, v) || (acb_neg(v, v), acb_overlaps(dw, v)))
              << c.str() << " " << to_string(kind) << " at t = " << t.str();
          acb_clear(v);
        }
        ++checked;
      }
      acb_clear(z);
      acb_clear(dw);
      acb_clear(ref);
    }
  }
  EXPECT_GT(answered, 100);  // the path is taken on these low-degree curves
  EXPECT_EQ(answered, checked);
}

TEST(SpeedEval, DoubleWordPathDeclinesWideComplexAndHighPrecisionBalls) {
  const Curve c = Curve({RatFunc(Poly::t()), RatFunc(Poly::t().pow(3))});  // (t, t^3)
  const Speed s(c, SpeedKind::Angular);
  acb_t z, out;
  acb_init(z);
  acb_init(out);
  acb_set_d(z, 0.375);
  EXPECT_TRUE(s.eval_double_word(out, z, Speed::PieceSigns{}, true, 90));
  EXPECT_FALSE(s.eval_double_word(out, z, Speed::PieceSigns{}, true, 200));  // more bits than double words
  arb_set_d(acb_imagref(z), 0.125);
  EXPECT_FALSE(s.eval_double_word(out, z, Speed::PieceSigns{}, true, 90));   // complex
  acb_set_d(z, 0.375);
  mag_set_d(arb_radref(acb_realref(z)), 1e-3);
  EXPECT_FALSE(s.eval_double_word(out, z, Speed::PieceSigns{}, true, 90));   // wide
  acb_clear(z);
  acb_clear(out);
}

namespace {

// |p(h)| / sum |c_k| |h|^k: 0 at a root, up to 1 elsewhere (the relative
// size of p at h against Horner's rounding scale).
double relative_value(const Poly& p, std::complex<double> h) {
  std::complex<double> v = 0;
  double scale = 0;
  for (long k = p.degree(); k >= 0; --k) {
    const double c = fmpz_get_d(p.get()->coeffs + k);
    v = v * h + c;
    scale = scale * std::abs(h) + std::fabs(c);
  }
  return std::abs(v) / scale;
}

}  // namespace

// The exact Newton step |p(h) / p'(h)| at h (Arb at 512 bits on p's
// integer coefficients): small when h is close to a simple root of p.
double newton_step(const Poly& p, std::complex<double> h) {
  acb_poly_t a;
  acb_t z, v, d;
  acb_poly_init(a);
  acb_init(z);
  acb_init(v);
  acb_init(d);
  acb_poly_set_fmpz_poly(a, p.get(), 512);
  acb_set_d_d(z, h.real(), h.imag());
  acb_poly_evaluate2(v, d, a, z, 512);
  acb_div(v, v, d, 512);
  const double r = std::hypot(arf_get_d(arb_midref(acb_realref(v)), ARF_RND_NEAR),
                              arf_get_d(arb_midref(acb_imagref(v)), ARF_RND_NEAR));
  acb_poly_clear(a);
  acb_clear(z);
  acb_clear(v);
  acb_clear(d);
  return r;
}

TEST(SpeedEval, SingularityHintsOfHighDegreeBezierCurvesComeFromTheCentredBasis) {
  // At degree 12 a Bezier curve's D and sum K^2 lose more than 30 bits on
  // [0, 1] in their own power basis (no hints from it); centred at 1/2 they
  // still give every root, and those within 1/2 of [0, 1] (the ones the
  // quadrature's boxes meet) are each within 1e-6 of a root by the exact
  // Newton step (the roots of random curves are simple).
  std::mt19937_64 rng(20261202u);
  const long n = uniparam::test_support::iterations(4);
  for (long it = 0; it < n; ++it) {
    const Curve c = random_bezier(rng, 12, 3, true);
    const Speed s(c, SpeedKind::Angular);
    SCOPED_TRACE(c.str());
    Poly sumK2(0);
    for (const Poly& k : s.cofactors()) sumK2 = sumK2 + k * k;
    const Poly& D = s.denominator();
    ASSERT_GT(power_basis_loss(D), 30);
    const auto& sg = s.singularity_hints(false);
    ASSERT_EQ(static_cast<long>(sg.size()), D.degree() + sumK2.degree());
    long near = 0;
    for (const auto& h : sg) {
      if (std::fabs(h.imag()) > 0.5 || h.real() < -0.5 || h.real() > 1.5) continue;
      ++near;
      EXPECT_LT(std::min(newton_step(D, h), newton_step(sumK2, h)), 1e-6) << h;
    }
    EXPECT_GT(near, 0);
  }
}

TEST(SpeedEval, SingularityHintsApproximateThePolesAndBranchPoints) {
  // sigma^2's hints: the roots of D; sigma's: those and, where sigma has a
  // square root (space curves, the parametric speed), the roots of sum K^2.
  // Each hint must nearly be a root of its polynomial (an exact oracle:
  // D and the K_k are exact), and there are as many as the degrees say.
  std::mt19937_64 rng(20261123u);
  const long n = uniparam::test_support::iterations(6);
  for (long it = 0; it < n; ++it)
    for (std::size_t dim : {2u, 3u})
      for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
        const Curve c = random_bezier(rng, 3 + it % 4, dim, it % 2 == 1);
        const Speed s(c, kind);
        const bool root = !(kind == SpeedKind::Angular && dim == 2);
        Poly sumK2(0);
        for (const Poly& k : s.cofactors()) sumK2 = sumK2 + k * k;
        const Poly& D = s.denominator();
        SCOPED_TRACE(c.str() + (kind == SpeedKind::Angular ? " angular" : " parametric"));
        const auto& sq = s.singularity_hints(true);
        const auto& sg = s.singularity_hints(false);
        ASSERT_EQ(static_cast<long>(sq.size()), D.degree());
        ASSERT_EQ(static_cast<long>(sg.size()), D.degree() + (root ? sumK2.degree() : 0));
        for (const auto& h : sq) EXPECT_LT(relative_value(D, h), 1e-8) << h;
        for (const auto& h : sg) EXPECT_LT(std::min(relative_value(D, h), root ? relative_value(sumK2, h) : 1.0), 1e-8) << h;
      }
}
