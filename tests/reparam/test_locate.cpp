// locate() and exact_samples(): the parameter at a given arc length or
// turning angle, against independent closed forms evaluated with Arb at 400
// bits (inverted in closed form where one exists, by bisection otherwise).
#include <gtest/gtest.h>

#include <arb.h>

#include <functional>
#include <vector>

#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

constexpr long kRefPrec = 400;

Ball q(long n, long d) { return Ball(Rational(n, d), kRefPrec); }

// The root of an increasing f on [0, 1] with f(0) <= y <= f(1), by 300
// bisection steps on certified signs (an undecided sign keeps both halves:
// the result is then the union, still an enclosure).
Ball bisect(const std::function<Ball(const Ball&)>& f, const Ball& y) {
  Ball lo(0), hi(1);
  for (int i = 0; i < 300; ++i) {
    Ball m;
    arb_add(m.get(), lo.get(), hi.get(), kRefPrec);
    arb_mul_2exp_si(m.get(), m.get(), -1);
    Ball v = f(m), d;
    arb_sub(d.get(), v.get(), y.get(), kRefPrec);
    if (d.certainly_negative()) lo = m;
    else if (d.certainly_positive()) hi = m;
    else break;
  }
  Ball u;
  arb_union(u.get(), lo.get(), hi.get(), kRefPrec);
  return u;
}

// Arc length of (t, t^2) from 0: (asinh(2t) + 2t sqrt(1 + 4t^2)) / 4.
Ball parabola_length(const Ball& t) {
  Ball a, b, r;
  arb_mul_2exp_si(a.get(), t.get(), 1);
  arb_asinh(r.get(), a.get(), kRefPrec);
  arb_mul(b.get(), a.get(), a.get(), kRefPrec);
  arb_add_ui(b.get(), b.get(), 1, kRefPrec);
  arb_sqrt(b.get(), b.get(), kRefPrec);
  arb_mul(b.get(), b.get(), a.get(), kRefPrec);
  arb_add(r.get(), r.get(), b.get(), kRefPrec);
  arb_mul_2exp_si(r.get(), r.get(), -2);
  return r;
}

// Arc length of the cusp (u^2, u^3) from u = 0 to u >= 0:
// int_0^u v sqrt(4 + 9 v^2) dv = ((4 + 9u^2)^(3/2) - 8) / 27.
Ball cusp_length(const Ball& u) {
  Ball r;
  arb_mul(r.get(), u.get(), u.get(), kRefPrec);
  arb_mul_ui(r.get(), r.get(), 9, kRefPrec);
  arb_add_ui(r.get(), r.get(), 4, kRefPrec);
  Ball s;
  arb_sqrt(s.get(), r.get(), kRefPrec);
  arb_mul(r.get(), r.get(), s.get(), kRefPrec);
  arb_sub_ui(r.get(), r.get(), 8, kRefPrec);
  arb_div_ui(r.get(), r.get(), 27, kRefPrec);
  return r;
}

// Its inverse: u = sqrt(((27 L + 8)^(2/3) - 4) / 9).
Ball cusp_inverse(const Ball& L) {
  Ball r, e;
  arb_mul_ui(r.get(), L.get(), 27, kRefPrec);
  arb_add_ui(r.get(), r.get(), 8, kRefPrec);
  arb_set_ui(e.get(), 2);
  arb_div_ui(e.get(), e.get(), 3, kRefPrec);
  arb_pow(r.get(), r.get(), e.get(), kRefPrec);
  arb_sub_ui(r.get(), r.get(), 4, kRefPrec);
  arb_div_ui(r.get(), r.get(), 9, kRefPrec);
  arb_sqrt(r.get(), r.get(), kRefPrec);
  return r;
}

void expect_t(const LocateResult& r, const Ball& ref, long digits, const char* what) {
  EXPECT_TRUE(r.at.t.contains(ref)) << what << ": " << r.at.t.str(40) << " vs " << ref.str(40);
  EXPECT_TRUE(r.at.t.meets_digits(digits)) << what << ": " << r.at.t.str(40);
  for (const Ball& x : r.at.point) EXPECT_TRUE(x.meets_digits(digits)) << what;
}

Options digits(long d) {
  Options o;
  o.digits = d;
  return o;
}

}  // namespace

// Unit circle: angle and arc length are both 2 atan(t), so t = tan(theta / 2).
TEST(Locate, CircleBothSpeedsContainTanHalfAngle) {
  const Curve c = Curve::parse("((1-t^2)/(1+t^2), 2t/(1+t^2))");
  for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
    const Speed s(c, kind);
    for (long d : {15L, 40L}) {
      for (const Rational& theta : {Rational(1, 10), Rational(1, 2), Rational(1), Rational(3, 2)}) {
        const LocateResult r = locate(c, s, theta, LocateTarget::Integral, digits(d));
        Ball half(theta, kRefPrec), ref, cs, sn;
        arb_mul_2exp_si(half.get(), half.get(), -1);
        arb_tan(ref.get(), half.get(), kRefPrec);
        expect_t(r, ref, d, "circle");
        Ball th(theta, kRefPrec);
        arb_sin_cos(sn.get(), cs.get(), th.get(), kRefPrec);
        EXPECT_TRUE(r.at.point[0].contains(cs));
        EXPECT_TRUE(r.at.point[1].contains(sn));
      }
      // fraction 1/3 of mu = pi/2: t = tan(pi/12)
      const LocateResult r = locate(c, s, Rational(1, 3), LocateTarget::Fraction, digits(d));
      Ball ref;
      arb_const_pi(ref.get(), kRefPrec);
      arb_div_ui(ref.get(), ref.get(), 12, kRefPrec);
      arb_tan(ref.get(), ref.get(), kRefPrec);
      expect_t(r, ref, d, "circle fraction");
    }
  }
}

TEST(Locate, ParabolaArcLengthMatchesClosedFormInverse) {
  const Curve c = Curve::parse("(t, t^2)");
  const Speed s(c, SpeedKind::Parametric);
  for (long d : {15L, 30L}) {
    for (const Rational& len : {Rational(1, 1000), Rational(1, 3), Rational(1), Rational(14, 10)}) {
      const LocateResult r = locate(c, s, len, LocateTarget::Integral, digits(d));
      expect_t(r, bisect(parabola_length, Ball(len, kRefPrec)), d, "parabola");
    }
    const LocateResult r = locate(c, s, Rational(1, 2), LocateTarget::Fraction, digits(d));
    Ball half = parabola_length(Ball(1));
    arb_mul_2exp_si(half.get(), half.get(), -1);
    expect_t(r, bisect(parabola_length, half), d, "parabola fraction");
  }
}

TEST(Locate, ParabolaLengthAboveMuIsRefused) {
  const Curve c = Curve::parse("(t, t^2)");
  const Speed s(c, SpeedKind::Parametric);
  EXPECT_THROW(locate(c, s, Rational(3, 2), LocateTarget::Integral), InvalidArgument);  // mu = 1.4789...
  EXPECT_THROW(locate(c, s, Rational(-1, 2), LocateTarget::Integral), InvalidArgument);
  EXPECT_THROW(locate(c, s, Rational(11, 10), LocateTarget::Fraction), InvalidArgument);
  const LocateResult r0 = locate(c, s, Rational(0), LocateTarget::Integral);
  EXPECT_TRUE(r0.at.t.certainly_zero());
  const LocateResult r1 = locate(c, s, Rational(1), LocateTarget::Fraction);
  EXPECT_TRUE(r1.at.t.contains(Rational(1)) && r1.at.t.is_exact());
}

// Cusp (t^2, t^3): sigma = t sqrt(4 + 9 t^2) vanishes at t = 0.
TEST(Locate, CuspAtTheStartMatchesClosedForm) {
  const Curve c = Curve::parse("(t^2, t^3)");
  const Speed s(c, SpeedKind::Parametric);
  for (const Rational& len : {Rational(1, 1000000), Rational(1, 5), Rational(1)}) {
    const LocateResult r = locate(c, s, len, LocateTarget::Integral, digits(20));
    expect_t(r, cusp_inverse(Ball(len, kRefPrec)), 20, "cusp");
  }
}

// The cusp in the middle: ((2t-1)^2, (2t-1)^3), sigma(1/2) = 0. Half the
// length is reached exactly at the zero of sigma, where Newton's derivative
// vanishes; a quarter at u = 2t - 1 < 0 with g(|u|) = g(1) / 2.
TEST(Locate, CuspInTheMiddleIncludingTheZeroItself) {
  const Curve c = Curve::parse("((2t-1)^2, (2t-1)^3)");
  const Speed s(c, SpeedKind::Parametric);
  for (long d : {15L, 30L}) {
    const LocateResult half = locate(c, s, Rational(1, 2), LocateTarget::Fraction, digits(d));
    expect_t(half, q(1, 2), d, "cusp half");
    const LocateResult quarter = locate(c, s, Rational(1, 4), LocateTarget::Fraction, digits(d));
    Ball g1 = cusp_length(Ball(1)), u, t;
    arb_mul_2exp_si(g1.get(), g1.get(), -1);
    u = cusp_inverse(g1);  // |u|, u < 0
    arb_sub_ui(t.get(), u.get(), 1, kRefPrec);
    arb_neg(t.get(), t.get());
    arb_mul_2exp_si(t.get(), t.get(), -1);  // t = (1 - |u|) / 2
    expect_t(quarter, t, d, "cusp quarter");
  }
}

// The angular speed of (t, t^3) vanishes at t = 0 (an inflection); the
// tangent's angle is atan(3 t^2), so t = sqrt(tan(A) / 3).
TEST(Locate, AngularSpeedZeroOfCubic) {
  const Curve c = Curve::parse("(t, t^3)");
  const Speed s(c, SpeedKind::Angular);
  for (const Rational& a : {Rational(1, 100000), Rational(1, 2), Rational(6, 5)}) {  // mu = atan 3 = 1.249...
    const LocateResult r = locate(c, s, a, LocateTarget::Integral, digits(20));
    Ball ref(a, kRefPrec);
    arb_tan(ref.get(), ref.get(), kRefPrec);
    arb_div_ui(ref.get(), ref.get(), 3, kRefPrec);
    arb_sqrt(ref.get(), ref.get(), kRefPrec);
    expect_t(r, ref, 20, "cubic angle");
  }
  // Inflection in the middle: (2t-1, (2t-1)^3), half the turning at t = 1/2.
  const Curve m = Curve::parse("(2t-1, (2t-1)^3)");
  const LocateResult r = locate(m, Speed(m, SpeedKind::Angular), Rational(1, 2), LocateTarget::Fraction, digits(25));
  expect_t(r, q(1, 2), 25, "inflection half");
}

TEST(Locate, StraightLineAngularIsAnError) {
  const Curve c = Curve::parse("(t, 2t)");
  const Speed s(c, SpeedKind::Angular);
  EXPECT_THROW(locate(c, s, Rational(1, 2), LocateTarget::Fraction), DomainError);
  EXPECT_THROW(exact_samples(c, s, 5), DomainError);
  // The parametric speed of a line is fine: (3t, 4t) has length 5t.
  const Curve l = Curve::parse("(3t, 4t)");
  const LocateResult r = locate(l, Speed(l, SpeedKind::Parametric), Rational(2), LocateTarget::Integral);
  expect_t(r, q(2, 5), 15, "line");
}

// Consecutive exact samples: the arc between the balls of t_k and t_{k+1}
// brackets mu / (K - 1): int_{hi(t_k)}^{lo(t_k+1)} sigma <= mu / (K - 1) <=
// int_{lo(t_k)}^{hi(t_k+1)} sigma, each integral certified on its own.
TEST(ExactSamples, ConsecutiveArcsEqualMuOverKMinusOne) {
  struct Case {
    const char* curve;
    SpeedKind kind;
    long K, digits;
  };
  const Case cases[] = {{"(t, t^2)", SpeedKind::Parametric, 9, 20},
                        {"(t^2, t^3)", SpeedKind::Parametric, 6, 15},
                        {"(2t-1, (2t-1)^3)", SpeedKind::Angular, 7, 15},
                        {"((1-t^2)/(1+t^2), 2t/(1+t^2))", SpeedKind::Angular, 5, 30}};
  for (const Case& cs : cases) {
    const Curve c = Curve::parse(cs.curve);
    const Speed s(c, cs.kind);
    const ExactSamples e = exact_samples(c, s, cs.K, digits(cs.digits));
    ASSERT_EQ(static_cast<long>(e.points.size()), cs.K);
    const long bits = digits_to_bits(cs.digits) + 40;
    const Ball mu = integrate_speed(s, RealAlgebraic(0), RealAlgebraic(1), bits, 16384);
    Ball step;
    arb_div_si(step.get(), mu.get(), cs.K - 1, 2 * bits);
    auto end = [](const Ball& t, bool upper) {
      arf_t x;
      arf_init(x);
      if (upper) arb_get_ubound_arf(x, t.get(), 512);
      else arb_get_lbound_arf(x, t.get(), 512);
      fmpq_t f;
      fmpq_init(f);
      arf_get_fmpq(f, x);
      Rational r(f);
      fmpq_clear(f);
      arf_clear(x);
      if (r.sign() < 0) r = Rational(0);
      if (Rational(1) < r) r = Rational(1);
      return r;
    };
    for (long k = 0; k + 1 < cs.K; ++k) {
      const LocatedPoint& a = e.points[static_cast<std::size_t>(k)];
      const LocatedPoint& b = e.points[static_cast<std::size_t>(k + 1)];
      EXPECT_TRUE(a.t.meets_digits(cs.digits) && b.t.meets_digits(cs.digits)) << cs.curve;
      const Ball inner = integrate_speed(s, RealAlgebraic(end(a.t, true)), RealAlgebraic(end(b.t, false)), bits, 16384);
      const Ball outer = integrate_speed(s, RealAlgebraic(end(a.t, false)), RealAlgebraic(end(b.t, true)), bits, 16384);
      Ball d1, d2;
      arb_sub(d1.get(), step.get(), inner.get(), 2 * bits);
      arb_sub(d2.get(), outer.get(), step.get(), 2 * bits);
      EXPECT_FALSE(d1.certainly_negative()) << cs.curve << " k=" << k;
      EXPECT_FALSE(d2.certainly_negative()) << cs.curve << " k=" << k;
      // and the bracket is as narrow as the digits say: outer - inner small
      Ball w;
      arb_sub(w.get(), outer.get(), inner.get(), 2 * bits);
      Ball tol(Rational(1, 1), 64);
      arb_mul_2exp_si(tol.get(), tol.get(), -static_cast<long>(3.32 * cs.digits) + 4);
      arb_sub(w.get(), w.get(), tol.get(), 2 * bits);
      EXPECT_TRUE(w.certainly_negative()) << cs.curve << " k=" << k;
    }
  }
}

TEST(ExactSamples, CircleAngleStepsContainTanOfEqualAngles) {
  const Curve c = Curve::parse("((1-t^2)/(1+t^2), 2t/(1+t^2))");
  const long K = 7;
  const ExactSamples e = exact_samples(c, Speed(c, SpeedKind::Parametric), K, digits(25));
  for (long k = 0; k < K; ++k) {
    Ball ref;  // t_k = tan(k (pi/2) / (K - 1) / 2)
    arb_const_pi(ref.get(), kRefPrec);
    arb_mul_si(ref.get(), ref.get(), k, kRefPrec);
    arb_div_si(ref.get(), ref.get(), 4 * (K - 1), kRefPrec);
    arb_tan(ref.get(), ref.get(), kRefPrec);
    const Ball& t = e.points[static_cast<std::size_t>(k)].t;
    if (k == 0 || k == K - 1) EXPECT_TRUE(t.is_exact() && arb_overlaps(t.get(), ref.get())) << k;
    else EXPECT_TRUE(t.contains(ref)) << k;
  }
}

// The identity map of the circle: its points t = k/(K-1) sit at fraction
// (4/pi) atan(k/(K-1)) of the length.
TEST(FractionDeviation, IdentityOfCircleMatchesAtan) {
  const Curve c = Curve::parse("((1-t^2)/(1+t^2), 2t/(1+t^2))");
  const Speed s(c, SpeedKind::Parametric);
  const long K = 11;
  const UniformityResult u = uniformity(s);
  const Ball dev = fraction_deviation(s, Reparameterization::identity(u.mu, u.u), K);
  Ball worst(0), pi;
  arb_const_pi(pi.get(), kRefPrec);
  for (long k = 0; k < K; ++k) {
    Ball x = q(k, K - 1), a;
    arb_atan(a.get(), x.get(), kRefPrec);
    arb_mul_ui(a.get(), a.get(), 4, kRefPrec);
    arb_div(a.get(), a.get(), pi.get(), kRefPrec);
    arb_sub(a.get(), a.get(), x.get(), kRefPrec);
    arb_abs(a.get(), a.get());
    arb_max(worst.get(), worst.get(), a.get(), kRefPrec);
  }
  EXPECT_TRUE(dev.contains(worst)) << dev.str(30) << " vs " << worst.str(30);
  EXPECT_TRUE(dev.meets_digits(12)) << dev.str(30);
}

TEST(FractionDeviation, RadicalMapOfParabolaIsSmallButNotZero) {
  const Curve c = Curve::parse("(t, t^2)");
  const Speed s(c, SpeedKind::Parametric);
  const Reparameterization r(radical(c, SpeedKind::Parametric));
  const Ball dev = fraction_deviation(s, r, 21);
  EXPECT_TRUE(dev.certainly_positive()) << dev.str(20);
  // identity's deviation is larger than the radical map's
  const UniformityResult u = uniformity(s);
  const Ball id = fraction_deviation(s, Reparameterization::identity(u.mu, u.u), 21);
  Ball diff;
  arb_sub(diff.get(), id.get(), dev.get(), 128);
  EXPECT_TRUE(diff.certainly_positive()) << id.str(20) << " " << dev.str(20);
}
