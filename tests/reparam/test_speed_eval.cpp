// Speed evaluation on wide complex balls (the quadrature's ellipses): the
// enclosure of sigma^2 (and sigma, and sigma^2 over a zero) on a ball must
// contain the value at every point of the ball. Curves: Bezier curves of
// moderate degree converted to the power basis (large alternating
// coefficients, where the centred form replaces Horner), plane and space,
// polynomial and rational.
#include <acb_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

// sum_k P_k C(d,k) t^k (1-t)^(d-k), exactly.
Poly bernstein(const std::vector<long>& P) {
  const long d = static_cast<long>(P.size()) - 1;
  Poly acc(0), omt = Poly(1) - Poly::t();
  Integer binom(1);
  for (long k = 0; k <= d; ++k) {
    if (k > 0) {
      fmpz_mul_ui(binom.get(), binom.get(), static_cast<ulong>(d - k + 1));
      fmpz_divexact_ui(binom.get(), binom.get(), static_cast<ulong>(k));
    }
    Integer c;
    fmpz_mul_si(c.get(), binom.get(), P[static_cast<std::size_t>(k)]);
    acc = acc + Poly(std::vector<Integer>{c}) * Poly::t().pow(static_cast<ulong>(k)) * omt.pow(static_cast<ulong>(d - k));
  }
  return acc;
}

Curve random_bezier(std::mt19937_64& rng, long d, std::size_t dim, bool rational) {
  std::uniform_int_distribution<long> coord(-50, 50), weight(1, 4);
  std::vector<long> w;
  for (long k = 0; k <= d; ++k) w.push_back(rational ? weight(rng) : 1);
  const Poly W = bernstein(w);
  std::vector<RatFunc> comps;
  for (std::size_t i = 0; i < dim; ++i) {
    std::vector<long> P;
    for (long k = 0; k <= d; ++k) P.push_back(w[static_cast<std::size_t>(k)] * (i == 0 ? 20 * k : coord(rng)));
    comps.emplace_back(bernstein(P), W);
  }
  return Curve(comps);
}

// A random complex ball with midpoint near [0, 1] and radii up to `maxrad`.
void random_ball(acb_t z, std::mt19937_64& rng, double maxrad) {
  std::uniform_int_distribution<long> m(0, 1 << 20), r(1, 1 << 10);
  arb_set_si(acb_realref(z), m(rng));
  arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
  arb_set_si(acb_imagref(z), m(rng) - (1 << 19));
  arb_mul_2exp_si(acb_imagref(z), acb_imagref(z), -24);
  mag_set_d(arb_radref(acb_realref(z)), maxrad * static_cast<double>(r(rng)) / 1024.0);
  mag_set_d(arb_radref(acb_imagref(z)), maxrad * static_cast<double>(r(rng)) / 1024.0);
}

// True when out overlaps v or -v: sigma evaluated with default piece signs
// is the analytic continuation from a piece where sign g (or the plane's
// sign of E) is +-1, so only |sigma| is compared.
bool overlaps_up_to_sign(const acb_t out, const acb_t v) {
  acb_t nv;
  acb_init(nv);
  acb_neg(nv, v);
  const bool ok = acb_overlaps(out, v) || acb_overlaps(out, nv);
  acb_clear(nv);
  return ok;
}

// An exact point of the ball z: mid + (a, b) * rad with a, b in [-1, 1].
void random_point(acb_t w, const acb_t z, std::mt19937_64& rng) {
  std::uniform_int_distribution<long> f(-1024, 1024);
  arb_t s;
  arb_init(s);
  for (int part = 0; part < 2; ++part) {
    arb_srcptr src = part ? acb_imagref(z) : acb_realref(z);
    arb_ptr dst = part ? acb_imagref(w) : acb_realref(w);
    arf_set_mag(arb_midref(s), arb_radref(src));
    mag_zero(arb_radref(s));
    arb_mul_si(s, s, f(rng), ARF_PREC_EXACT);
    arb_mul_2exp_si(s, s, -10);
    arb_set_arf(dst, arb_midref(src));
    arb_add(dst, dst, s, ARF_PREC_EXACT);
  }
  arb_clear(s);
}

}  // namespace

namespace {

// For `iters` random Bezier curves (make(it): degree, dimension, rational)
// and both speed kinds, 10 random balls each (ball(z, b) makes ball b):
// where wide(s, out, z) gives a finite enclosure, the values point(s, v, w)
// at 8 exact points w of the ball must overlap it (up to sign: see
// overlaps_up_to_sign). Returns {finite enclosures, balls}.
struct WideCase {
  long d;
  std::size_t dim;
  bool rational;
};
template <class Make, class Ball, class Wide, class Point>
std::pair<long, long> check_wide_balls(std::mt19937_64& rng, long iters, Make make, Ball ball, Wide wide,
                                       Point point, bool up_to_sign) {
  long finite = 0, total = 0;
  for (long it = 0; it < iters; ++it) {
    const WideCase k = make(it);
    const Curve c = random_bezier(rng, k.d, k.dim, k.rational);
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(c, kind);
      acb_t z, w, out, v;
      for (acb_ptr x : {z, w, out, v}) acb_init(x);
      for (int b = 0; b < 10; ++b) {
        ball(z, b);
        ++total;
        wide(s, out, z);
        if (!acb_is_finite(out)) continue;
        ++finite;
        for (int p = 0; p < 8; ++p) {
          random_point(w, z, rng);
          point(s, v, w);
          const bool ok = up_to_sign ? overlaps_up_to_sign(out, v) : acb_overlaps(out, v);
          if (!ok) {  // (ASSERT_* needs a void function)
            ADD_FAILURE() << c.str() << " degree " << k.d << " kind " << static_cast<int>(kind);
            for (acb_ptr x : {z, w, out, v}) acb_clear(x);
            return {finite, total};
          }
        }
      }
      for (acb_ptr x : {z, w, out, v}) acb_clear(x);
    }
  }
  return {finite, total};
}

}  // namespace

TEST(SpeedEval, SquaredSpeedOnWideBallsContainsEveryPointValue) {
  std::mt19937_64 rng(7);
  const auto [finite, balls] = check_wide_balls(
      rng, test_support::iterations(6),
      [&](long it) { return WideCase{8 + static_cast<long>(rng() % 24), 2 + rng() % 2, it % 2 == 1}; },
      [&](acb_t z, int b) { random_ball(z, rng, b % 2 ? 0.05 : 0.002); },
      [](const Speed& s, acb_t out, const acb_t z) { s.eval_squared(out, z, 128); },
      [](const Speed& s, acb_t v, const acb_t w) { s.eval_squared(v, w, 256); }, false);
  (void)balls;
  EXPECT_GT(finite, 0);  // the check above ran
}

TEST(SpeedEval, AnalyticSpeedOnEllipsesInDiscsContainsEveryPointValue) {
  // Low degrees, where every factor has its centred form in double and the
  // ellipses are bounded in complex discs (Speed::eval_disk, the factored
  // form's discs for space curves): plane and space, polynomial and
  // rational, angular and parametric; boxes as the quadrature's (real and
  // complex midpoints). The enclosure must contain sigma at every point.
  std::mt19937_64 rng(31);
  const auto [finite, total] = check_wide_balls(
      rng, test_support::iterations(12),
      [&](long it) { return WideCase{3 + static_cast<long>(rng() % 8), 2 + static_cast<std::size_t>(it % 2), (it / 2) % 2 == 1}; },
      [&](acb_t z, int b) {
        random_ball(z, rng, b % 2 ? 0.1 : 0.01);
        if (b % 3 == 0) arb_zero(acb_imagref(z));  // the ellipses' bounding boxes: real midpoints
      },
      [](const Speed& s, acb_t out, const acb_t z) { s.eval(out, z, Speed::PieceSigns{}, true, 64); },
      [](const Speed& s, acb_t v, const acb_t w) { s.eval(v, w, Speed::PieceSigns{}, false, 256); }, true);
  EXPECT_GE(2 * finite, total);  // most boxes near [0, 1] are bounded
}

TEST(SpeedEval, SpeedAndSquaredOverIrrationalZeroOnWideBalls) {
  // (t, t^4 - 3 t^2): angular speed zero of multiplicity 1 at 1/sqrt(2).
  const Curve c = parse_curve("(t, t^4 - 3*t^2)");
  const Speed s(c, SpeedKind::Angular);
  ASSERT_EQ(s.zeros().size(), 1u);
  const SpeedZero& zero = s.zeros()[0];
  const Speed::PieceSigns right = s.piece_signs(zero.t, RealAlgebraic(1));
  std::mt19937_64 rng(11);
  acb_t z, w, out, v;
  acb_init(z);
  acb_init(w);
  acb_init(out);
  acb_init(v);
  long checked = 0;
  for (int b = 0; b < 40; ++b) {
    // balls around 1/sqrt(2) ~ 0.70710678 and to its right
    arb_set_d(acb_realref(z), 0.7071 + 0.002 * b);
    arb_zero(acb_imagref(z));
    mag_set_d(arb_radref(acb_realref(z)), 0.01);
    mag_set_d(arb_radref(acb_imagref(z)), 0.01);
    for (int power = 0; power <= 2; ++power) {
      s.eval_squared_over_zero(out, z, zero, 1, power, 128);
      if (!acb_is_finite(out)) continue;
      for (int p = 0; p < 6; ++p) {
        random_point(w, z, rng);
        s.eval_squared_over_zero(v, w, zero, 1, power, 256);
        ASSERT_TRUE(acb_overlaps(out, v)) << "power " << power << " ball " << b;
        ++checked;
      }
    }
    s.eval(out, z, right, false, 128);
    if (!acb_is_finite(out)) continue;
    for (int p = 0; p < 6; ++p) {
      random_point(w, z, rng);
      s.eval(v, w, right, false, 256);
      ASSERT_TRUE(acb_overlaps(out, v)) << "sigma, ball " << b;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  acb_clear(z);
  acb_clear(w);
  acb_clear(out);
  acb_clear(v);
}

TEST(SpeedEval, SpaceSpeedOnWideBallsAtLowPrecision) {
  // Rational space Bezier curves of degree 40: the cofactors K of the
  // factored form have degree ~ 110 and power-basis coefficients some 200
  // bits above their values near t = 1. At a working precision of 64 bits the
  // enclosure of sigma on balls of radius ~1e-3 must still be finite (the
  // Taylor shift is redone above the bits lost to cancellation, and the
  // factored form is used instead of the components' |p' x p''|) and contain
  // sigma at every point of the ball.
  std::mt19937_64 rng(23);
  long finite = 0, total = 0;
  for (long it = 0; it < test_support::iterations(2); ++it) {
    const Curve c = random_bezier(rng, 40, 3, true);
    const Speed s(c, SpeedKind::Angular);
    const Speed::PieceSigns sign{};
    acb_t z, w, out, v;
    acb_init(z);
    acb_init(w);
    acb_init(out);
    acb_init(v);
    for (int b = 0; b < 12; ++b) {
      arb_set_d(acb_realref(z), 0.8 + 0.015 * b);
      arb_zero(acb_imagref(z));
      mag_set_d(arb_radref(acb_realref(z)), 1e-3);
      mag_set_d(arb_radref(acb_imagref(z)), 8e-4);
      ++total;
      s.eval(out, z, sign, true, 64);
      if (!acb_is_finite(out)) continue;
      ++finite;
      for (int p = 0; p < 6; ++p) {
        random_point(w, z, rng);
        s.eval(v, w, sign, false, 512);
        ASSERT_TRUE(overlaps_up_to_sign(out, v)) << c.str() << " ball " << b;
      }
    }
    acb_clear(z);
    acb_clear(w);
    acb_clear(out);
    acb_clear(v);
  }
  EXPECT_GE(2 * finite, total);
}

namespace uniparam {
namespace {

TEST(SpeedEval, SpeedOnRealSegmentsWithoutHolomorphyIsFiniteAndContainsPointValues) {
  // Arb's direct bound on a subinterval evaluates sigma on the real segment
  // itself with holomorphy not asked. sigma is real there, and |p' x p''|^2
  // and |p'|^2 are >= 0 at every real point: the enclosure must be real
  // (square roots of [max(0, lo), hi], no detour through the complex branch
  // cut), contain sigma at every point of the segment, and be finite on most
  // segments (a segment of radius 2^-6 near an end of a degree-30 curve may
  // still have |p'|^2's enclosure reach 0: at least half, as above).
  // Rational space Bezier curves of degree 30 and plane ones, segments of
  // radius 2^-6..2^-10.
  std::mt19937_64 rng(31);
  long finite = 0, total = 0;
  for (long it = 0; it < test_support::iterations(3); ++it) {
    const Curve c = random_bezier(rng, 30, it % 2 == 0 ? 3 : 2, true);
    const Speed s(c, SpeedKind::Angular);
    acb_t z, w, out, v;
    for (acb_ptr x : {z, w, out, v}) acb_init(x);
    for (int b = 0; b < 16; ++b) {
      acb_zero(z);
      arb_set_d(acb_realref(z), (b + 0.5) / 16);
      mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -6 - b % 5);
      const Speed::PieceSigns sign{};
      ++total;
      s.eval(out, z, sign, false, 64);
      ASSERT_TRUE(acb_is_real(out)) << c.str() << " segment " << b;
      if (!acb_is_finite(out)) continue;
      ++finite;
      for (int p = 0; p < 8; ++p) {
        random_point(w, z, rng);
        arb_zero(acb_imagref(w));
        s.eval(v, w, sign, false, 256);
        ASSERT_TRUE(overlaps_up_to_sign(out, v)) << c.str() << " segment " << b;
      }
    }
    for (acb_ptr x : {z, w, out, v}) acb_clear(x);
  }
  EXPECT_GE(2 * finite, total);
}

}  // namespace
}  // namespace uniparam

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
