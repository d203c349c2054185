// Speeds with narrow features inside (0, 1): peak_split's parts, each in
// its exact balanced chart (Speed::charts), give the integrals of the
// uniformity and of the methods at a cost independent of the features'
// width, and the same certified values as the direct quadratures.
#include <gtest/gtest.h>

#include <arb.h>

#include <optional>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "support/reference.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/reparam/scaling.hpp"

using namespace uniparam;

namespace {

// u -> p(a + (b - a) u) holds p's point at every rational u: the
// components agree at t = a + (b - a) u, evaluated exactly.
Rational component_at(const RatFunc& f, const Rational& t) {
  const Poly n = f.num(), d = f.den();
  auto eval = [&t](const Poly& p) {
    Rational r(0);
    for (long i = p.degree(); i >= 0; --i) r = r * t + Rational(p.coeff(i));
    return r;
  };
  return eval(n) / eval(d);
}

}  // namespace

TEST(PeakSplit, RestrictionIsTheCurveOnTheInterval) {
  const Curve p = Curve::parse("((1 + t^2)/(3 - t), t^3 - 2*t, 5*t^4/(2 + t^2))");
  const std::vector<std::pair<Rational, Rational>> intervals{
      {Rational(0), Rational(1)}, {Rational(1, 3), Rational(5, 7)}, {Rational(9, 10), Rational(1, 8)}};
  for (const auto& [a, b] : intervals) {
    const Curve q = restrict_to(p, a, b);
    for (const Rational& u : {Rational(0), Rational(1, 2), Rational(3, 11), Rational(1)}) {
      const Rational t = a + (b - a) * u;
      for (std::size_t i = 0; i < p.dimension(); ++i)
        EXPECT_EQ(component_at(q.components()[i], u), component_at(p.components()[i], t))
            << "component " << i << " at u = " << u.str() << " on [" << a.str() << ", " << b.str() << "]";
    }
  }
  EXPECT_THROW(restrict_to(p, Rational(1, 2), Rational(1, 2)), InvalidArgument);
}

// Ordinary curves (small coefficients, Bezier power bases) are not split.
TEST(PeakSplit, OrdinaryCurvesAreNotSplit) {
  for (const char* c : {"(t, t^3)", "((1-t^2)/(1+t^2), 2*t/(1+t^2))", "(t^2, t^3 + t)", "(t, t^2, t^3)",
                        "(3*t^5-2*t^3+t, t^4-5*t^2+2*t-1)", "(t, 1000*(t-1/2)^2)"})
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric})
      EXPECT_FALSE(peak_split(Speed(Curve::parse(c), kind)).has_value()) << c;
}

namespace {

// The oracle: quadratures on p's own parameter, without the charts.
// k = 0: sigma (sigma^2 > 0 on [a, b]); 1: sigma^2; 2, 3, 4: piece_integrals'
// A, B, C, sigma^2 (b - a) w(t~) with w = (1 - t~)^2, 2 t~ (1 - t~), t~^2.
Ball direct_integral(const Speed& s, int k, const RealAlgebraic& a, const RealAlgebraic& b) {
  Integrand f = [&s, k, &a, &b](acb_t out, const acb_t z, bool analytic, long prec) {
    s.eval_squared(out, z, prec);
    if (k == 0) {
      acb_sqrt_analytic(out, out, analytic, prec);
      return;
    }
    if (k == 1) return;
    acb_t ta, dt, x;
    acb_init(ta);
    acb_init(dt);
    acb_init(x);
    acb_set_arb(ta, a.to_ball(prec).get());
    acb_set_arb(dt, b.to_ball(prec).get());
    acb_sub(dt, dt, ta, prec);
    acb_sub(x, z, ta, prec);
    acb_div(x, x, dt, prec);  // t~
    acb_mul(out, out, dt, prec);
    acb_sub_ui(ta, x, 1, prec);
    acb_neg(ta, ta);  // 1 - t~
    if (k == 2) acb_mul(x, ta, ta, prec);
    else if (k == 3) acb_mul(x, x, ta, prec), acb_mul_2exp_si(x, x, 1);
    else acb_mul(x, x, x, prec);
    acb_mul(out, out, x, prec);
    acb_clear(ta);
    acb_clear(dt);
    acb_clear(x);
  };
  QuadratureOptions qo;
  qo.rel_goal_bits = 80;
  qo.max_prec = 1 << 14;
  return integrate(f, a, b, qo);
}

}  // namespace

// (t, C (t - c)^2 [+ t^3]) for random centres c in (0, 1) and 30-digit C: a
// peak of width about 1/(2C) at c. The speed has charts, a feature knot on
// the peak's own scale, and its integrals over random intervals (rational
// and algebraic ends, across the peak or beside it) taken in the charts
// overlap the direct quadratures: sigma, sigma^2 and a piece's A, B, C.
TEST(SpeedCharts, IntegralsAgreeWithDirectQuadrature) {
  TimeBudget budget(300);
  std::mt19937 rng(20261204);
  for (int trial = 0; trial < 4; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 30);
    const Rational c = test_support::random_inner_rational(rng);
    const std::string extra = trial % 2 ? " + t^3" : "";
    const Curve p = Curve::parse("(t, " + C + "*(t - " + c.str() + ")^2" + extra + ")");
    SCOPED_TRACE(p.str());
    // ends: [0, 1]; across c from sqrt(q) (algebraic) or a rational; beside c
    const long q = 1 + static_cast<long>(rng() % 97);
    const RealAlgebraic root(Poly(std::vector<Integer>{Integer(-q), Integer(0), Integer(100)}), Rational(0),
                             Rational(1));  // sqrt(q) / 10
    const Rational below = c * Rational(1 + static_cast<long>(rng() % 9), 10);
    const std::vector<std::pair<RealAlgebraic, RealAlgebraic>> intervals{
        {RealAlgebraic(0), RealAlgebraic(1)},
        {root < RealAlgebraic(c) ? root : RealAlgebraic(below), root < RealAlgebraic(c) ? RealAlgebraic(1) : root},
        {RealAlgebraic(below / Rational(2)), RealAlgebraic(below)}};
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(p, kind);
      ASSERT_NE(s.charts(), nullptr);
      const std::optional<PeakSplit> split = peak_split(s);
      ASSERT_TRUE(split.has_value());
      // A feature knot within 2^-70 of the centre (the peak's width is
      // about 2^-100): the part's end is on the peak's own scale.
      bool at_centre = false;
      for (std::size_t i = 0; i < split->knots.size(); ++i) {
        const Rational d = split->knots[i] - c;
        at_centre = at_centre || (split->feature[i] && d <= pow2(-70) && Rational(0) - d <= pow2(-70));
      }
      EXPECT_TRUE(at_centre) << "no feature at the peak";
      for (const auto& [a, b] : intervals) {
        SCOPED_TRACE("[" + a.decimal(10) + ", " + b.decimal(10) + "] " + to_string(kind));
        const Ball mu = integrate_speed(s, a, b, 64, 1 << 14);
        const Ball sq = integrate_speed_squared(s, a, b, 64, 1 << 14);
        const PieceIntegrals pi = piece_integrals(s, Breakpoint{a}, Breakpoint{b}, 64, 1 << 14);
        const Ball* got[] = {&mu, &sq, &pi.A, &pi.B, &pi.C};
        for (int k = 0; k < 5; ++k) {
          const Ball want = direct_integral(s, k, a, b);
          EXPECT_TRUE(arb_overlaps(got[k]->get(), want.get())) << k << ": " << got[k]->str(25) << " vs " << want.str(25);
          EXPECT_TRUE(got[k]->meets_digits(15)) << k << ": " << got[k]->str(25);
        }
      }
    }
  }
}

// The uniformity of such a peak at c: mu is the closed form
// atan(2 C c) + atan(2 C (1 - c)) for the angular speed.
TEST(SpeedCharts, UniformityOfAPeakMatchesTheClosedForm) {
  TimeBudget budget(120);
  std::mt19937 rng(20261203);
  for (int trial = 0; trial < 4; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 40);
    const Rational c = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("(t, " + C + "*(t - " + c.str() + ")^2)");
    SCOPED_TRACE(p.str());
    Options o;
    o.digits = 20;
    const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
    Ball c2, a, b, mu;
    arb_set_str(c2.get(), C.c_str(), 512);
    arb_mul_2exp_si(c2.get(), c2.get(), 1);
    arb_mul(a.get(), c2.get(), Ball(c, 512).get(), 512);
    arb_mul(b.get(), c2.get(), Ball(Rational(1) - c, 512).get(), 512);
    arb_atan(a.get(), a.get(), 512);
    arb_atan(b.get(), b.get(), 512);
    arb_add(mu.get(), a.get(), b.get(), 512);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
    EXPECT_TRUE(r.u.meets_digits(20));
  }
}

// The methods on (t, C (t - 1/2)^2) with a 2000-digit C (a peak of width
// 10^-2000 at 1/2), within a TimeBudget the integrals across the peak
// cannot meet (and pieces away from the peak, where the charts would need
// 6600 bits to tell their ends apart, on p's own parameter): radical's mu is 2 atan(C), its pieces symmetric about 1/2
// (A and C swapped), and u(p) the parabola's closed form (as in the test
// below) for radical and the optimised three-piece C0 method, whose u(p o r)
// is no lower than u(p).
TEST(SpeedCharts, MethodsOnAHugeInteriorPeakFinish) {
  TimeBudget budget(30);
  const std::string c_text(2000, '3');
  const Curve p = Curve::parse("(t, " + c_text + "*(t - 1/2)^2)");
  const long prec = 16000;
  Ball half_c;
  arb_set_str(half_c.get(), c_text.c_str(), prec);
  arb_mul_2exp_si(half_c.get(), half_c.get(), -1);
  const test_support::ParabolaAngular half = test_support::parabola_angular(half_c, prec);
  Ball mu;
  arb_mul_2exp_si(mu.get(), half.mu.get(), 1);
  Options o;
  o.digits = 20;
  const RadicalResult r = radical(p, SpeedKind::Angular, o);
  EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
  EXPECT_TRUE(arb_overlaps(r.u_before.get(), half.u.get())) << r.u_before.str(25) << " vs " << half.u.str(25);
  // sigma(t) = sigma(1 - t): pieces symmetric about 1/2, A and C swapped
  const std::size_t n = r.integrals.size();
  for (std::size_t i = 0; i < n; ++i) {
    Ball sum;
    arb_add(sum.get(), r.T[i].t.to_ball(128).get(), r.T[n - i].t.to_ball(128).get(), 128);
    EXPECT_TRUE(arb_contains_si(sum.get(), 1)) << r.T[i].t.str();
    EXPECT_TRUE(arb_overlaps(r.integrals[i].A.get(), r.integrals[n - 1 - i].C.get())) << i;
    EXPECT_TRUE(arb_overlaps(r.integrals[i].B.get(), r.integrals[n - 1 - i].B.get())) << i;
  }
  const MoebiusResult m = reparam_c0(p, SpeedKind::Angular, 3, o);
  EXPECT_TRUE(arb_overlaps(m.u_before.get(), half.u.get())) << m.u_before.str(25) << " vs " << half.u.str(25);
  EXPECT_FALSE(arb_lt(m.u_after.get(), m.u_before.get())) << m.u_after.str(25) << " < " << m.u_before.str(25);
}

// Must show: (t, C (t - 1/2)^2) with a 2000-digit C, whose angular speed is
// a peak of width 1/(2C) at 1/2, is certified within a TimeBudget the
// direct integrals cannot meet (they bisect ~6600 times at ~6600 bits),
// and matches the parabola's closed forms: by symmetry twice the arc of
// (t, (C/2) t^2) over [0, 1], mu = 2 atan(C), int omega^2 = 4 I(C/2).
TEST(PeakSplit, InteriorPeakOfAHugeParabolaMatchesClosedForms) {
  TimeBudget budget(30);
  const std::string c_text(2000, '7');
  const Curve p = Curve::parse("(t, " + c_text + "*(t - 1/2)^2)");
  Options o;
  o.digits = 30;
  const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
  const long prec = 16000;
  Ball half_c;
  arb_set_str(half_c.get(), c_text.c_str(), prec);
  arb_mul_2exp_si(half_c.get(), half_c.get(), -1);
  const test_support::ParabolaAngular half = test_support::parabola_angular(half_c, prec);
  Ball mu, u;
  arb_mul_2exp_si(mu.get(), half.mu.get(), 1);
  // u = mu^2 / int omega^2 = (2 mu')^2 / (4 I') = mu'^2 / I' = u'.
  u = half.u;
  EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(35) << " vs " << mu.str(35);
  EXPECT_TRUE(arb_overlaps(r.u.get(), u.get())) << r.u.str(35) << " vs " << u.str(35);
  EXPECT_TRUE(r.mu.meets_digits(30));
}

// A cubic peak (D = 1 + 9 C^2 (t - c)^4: four roots within C^(-1/2) of c)
// next to which the balanced part's g vanishes, with a 300-digit C: both
// speeds certified within the budget.
TEST(PeakSplit, CubicPeakWithAHugeCoefficientFinishes) {
  TimeBudget budget(30);
  const Curve p = Curve::parse("(t, " + std::string(300, '7') + "*(t - 2/7)^3)");
  for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
    const UniformityResult r = uniformity(p, kind, Options{});
    EXPECT_TRUE(r.u.meets_digits(15));
    EXPECT_GT(arf_sgn(arb_midref(r.u.get())), 0);
  }
}

// (t, C (t - a)^2 + t^3) with a 300-digit C and a random centre a: the
// angular peak sits where y' = 2 C (t - a) + 3 t^2 vanishes, an irrational
// point, and is 1 / (2 C) wide. Its feature knot lies on the peak itself
// (|y'| < 1/16 there, exactly), not merely within a few hundred bits of it,
// which left the peak 2^680 of its widths inside a part and every quadrature
// bisecting down to it; mu is the turning angle atan(y'(1)) - atan(y'(0))
// (y'' > 0).
TEST(PeakSplit, FeatureKnotsSitOnPeaksAtIrrationalPoints) {
  TimeBudget budget(60);
  std::mt19937 rng(20261206);
  for (int trial = 0; trial < 3; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 300);
    const Rational a = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("(t, " + C + "*(t - " + a.str() + ")^2 + t^3)");
    SCOPED_TRACE(p.str());
    const Rational c_big{Integer(C)};
    const auto slope = [&](const Rational& t) { return Rational(2) * c_big * (t - a) + Rational(3) * t * t; };
    const Speed s(p, SpeedKind::Angular);
    const std::optional<PeakSplit> split = peak_split(s);
    ASSERT_TRUE(split.has_value());
    int features = 0;
    for (std::size_t i = 0; i < split->knots.size(); ++i) {
      if (!split->feature[i]) continue;
      ++features;
      Rational y1 = slope(split->knots[i]);
      if (y1.sign() < 0) y1 = -y1;
      EXPECT_LT(y1, Rational(1, 16)) << "knot " << split->knots[i].str();
    }
    EXPECT_EQ(features, 1);
    Options o;
    o.digits = 20;
    const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
    const long prec = 2400;
    Ball y0(-slope(Rational(0)), prec), y1(slope(Rational(1)), prec), mu;
    arb_atan(y0.get(), y0.get(), prec);
    arb_atan(y1.get(), y1.get(), prec);
    arb_add(mu.get(), y0.get(), y1.get(), prec);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
    EXPECT_TRUE(r.u.meets_digits(20));
  }
}

namespace {

// The turning angle of (t, C t^2 (1 - t)^2) over [0, 1]: 4 atan(C sqrt(3)
// / 9) (y' = 0 at 0, 1/2, 1; |y'| = C sqrt(3) / 9 at the zeros
// (3 -+ sqrt(3)) / 6 of y'').
Ball quartic_turning_angle(const std::string& C) {
  const long prec = 2400;
  Ball x, mu;
  arb_set_str(x.get(), C.c_str(), prec);
  arb_sqrt_ui(mu.get(), 3, prec);
  arb_mul(x.get(), x.get(), mu.get(), prec);
  arb_div_ui(x.get(), x.get(), 9, prec);
  arb_atan(mu.get(), x.get(), prec);
  arb_mul_2exp_si(mu.get(), mu.get(), 2);
  return mu;
}

}  // namespace

// (t, C t^2 (1 - t)^2) with a random 300-digit C: angular peaks 1 / (2 C)
// wide at 0, 1/2 and 1, each part's feature at its chart's u = 0, where
// the speed's factors are evaluated next to their roots: mu matches the
// closed form.
TEST(PeakSplit, PeaksAtBothEndsAndInsideMatchTheClosedForm) {
  TimeBudget budget(60);
  std::mt19937 rng(20261207);
  for (int trial = 0; trial < 3; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 300);
    const Curve p = Curve::parse("(t, " + C + "*t^2*(1 - t)^2)");
    Options o;
    o.digits = 20;
    const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
    const Ball mu = quartic_turning_angle(C);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
    EXPECT_TRUE(r.u.meets_digits(20));
  }
}

// radical on (t, C t^2 (1 - t)^2), 300-digit C: every piece ends at a zero
// of omega (the zeros (3 -+ sqrt(3)) / 6 of y'') and holds a peak 10^-300
// wide at its other end, so its A, B, C and its integral of omega^2 run
// through the charts with the zero deflated in its chart (on t they
// bisected down to the peak at 800 bits: over 30 s). mu is the closed form,
// u(p) from the pieces' integrals of omega^2 agrees with uniformity()'s
// (speed_integrals: other spans, no deflation), the pieces are symmetric
// about 1/2, and the Moebius step does not lower u.
TEST(SpeedCharts, RadicalPiecesEndingAtZerosNextToPeaks) {
  TimeBudget budget(20);
  std::mt19937 rng(20261208);
  const std::string C = test_support::random_positive_digits(rng, 300);
  const Curve p = Curve::parse("(t, " + C + "*t^2*(1 - t)^2)");
  Options o;
  o.digits = 20;
  const RadicalResult r = radical(p, SpeedKind::Angular, o);
  const Ball mu = quartic_turning_angle(C);
  EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
  const UniformityResult u = uniformity(p, SpeedKind::Angular, o);
  EXPECT_TRUE(arb_overlaps(r.u_before.get(), u.u.get())) << r.u_before.str(25) << " vs " << u.u.str(25);
  EXPECT_TRUE(r.u_before.meets_digits(20));
  const std::size_t n = r.integrals.size();
  ASSERT_EQ(n, 4u);
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_TRUE(arb_overlaps(r.integrals[i].A.get(), r.integrals[n - 1 - i].C.get())) << i;
    EXPECT_TRUE(arb_overlaps(r.integrals[i].B.get(), r.integrals[n - 1 - i].B.get())) << i;
  }
  EXPECT_FALSE(arb_lt(r.u_after.get(), r.u_before.get())) << r.u_after.str(25) << " < " << r.u_before.str(25);
}

namespace {

// Locates each fraction of mu and K exact samples on p, and hands every
// point with its fraction to expect.
template <class Expect>
void check_located(const Curve& p, const Speed& s, const std::vector<Rational>& fractions, long K, Expect expect) {
  for (const Rational& f : fractions) {
    SCOPED_TRACE(f.str());
    expect(locate(p, s, f, LocateTarget::Fraction).at, f);
  }
  const ExactSamples ex = exact_samples(p, s, K);
  for (long k = 0; k < K; ++k) {
    SCOPED_TRACE(k);
    expect(ex.points[static_cast<std::size_t>(k)], Rational(k, K - 1));
  }
}

// The angular peak (t, C (t - c)^2): G(t) = atan(2 C (t - c)) + atan(2 C c),
// so the point at the fraction f of mu is t = c + tan(f mu - atan(2 C c)) /
// (2 C), and p(t) = (t, C (t - c)^2). Checks that `at` overlaps it.
void expect_peak_point(const LocatedPoint& at, const std::string& C, const Rational& c, const Rational& f) {
  const long prec = 20000;
  Ball c2, a, b, mu, x, t, y;
  arb_set_str(c2.get(), C.c_str(), prec);
  arb_mul_2exp_si(c2.get(), c2.get(), 1);  // 2 C
  arb_mul(a.get(), c2.get(), Ball(c, prec).get(), prec);
  arb_atan(a.get(), a.get(), prec);  // atan(2 C c)
  arb_mul(b.get(), c2.get(), Ball(Rational(1) - c, prec).get(), prec);
  arb_atan(b.get(), b.get(), prec);
  arb_add(mu.get(), a.get(), b.get(), prec);
  arb_mul(x.get(), mu.get(), Ball(f, prec).get(), prec);
  arb_sub(x.get(), x.get(), a.get(), prec);
  arb_tan(x.get(), x.get(), prec);
  arb_div(x.get(), x.get(), c2.get(), prec);  // t - c
  arb_add(t.get(), x.get(), Ball(c, prec).get(), prec);
  arb_sqr(y.get(), x.get(), prec);
  arb_mul(y.get(), y.get(), c2.get(), prec);
  arb_mul_2exp_si(y.get(), y.get(), -1);
  EXPECT_TRUE(arb_overlaps(at.t.get(), t.get())) << at.t.str(30) << " vs " << t.str(30);
  ASSERT_EQ(at.point.size(), 2u);
  EXPECT_TRUE(arb_overlaps(at.point[0].get(), t.get())) << at.point[0].str(30) << " vs " << t.str(30);
  EXPECT_TRUE(arb_overlaps(at.point[1].get(), y.get())) << at.point[1].str(30) << " vs " << y.str(30);
  EXPECT_TRUE(at.t.meets_digits(15)) << at.t.str(30);
  for (const Ball& v : at.point) EXPECT_TRUE(v.meets_digits(15)) << v.str(30);
}

}  // namespace

// locate() and the exact samples on angular peaks at random centres with
// 40- and 300-digit C run on the charts' track, and give the closed-form
// points; the parametric speed's located t brackets its target (G from
// integrate_speed at t's rational ends). Within a TimeBudget the track
// on p's own parameter cannot meet at 300 digits.
TEST(SpeedCharts, LocatedPointsOfAPeakMatchTheClosedForm) {
  TimeBudget budget(60);
  std::mt19937 rng(4121226);
  for (int trial = 0; trial < 4; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, trial < 2 ? 40 : 300);
    const Rational c = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("(t, " + C + "*(t - " + c.str() + ")^2)");
    SCOPED_TRACE(p.str());
    const Speed s(p, SpeedKind::Angular);
    ASSERT_NE(s.charts(), nullptr);
    check_located(p, s, {Rational(1, 3), Rational(1 + static_cast<long>(rng() % 999), 1000), Rational(1, 1000000)}, 7,
                  [&](const LocatedPoint& at, const Rational& f) { expect_peak_point(at, C, c, f); });
    const Speed sp(p, SpeedKind::Parametric);
    const Rational f(1 + static_cast<long>(rng() % 9), 10);
    const LocateResult r = locate(p, sp, f, LocateTarget::Fraction);
    EXPECT_TRUE(r.at.t.meets_digits(15));
    // G(lo) <= f mu <= G(hi) at the rational ends of t's ball
    Rational lo, hi;
    {
      arf_t l, h;
      arf_init(l);
      arf_init(h);
      arb_get_lbound_arf(l, r.at.t.get(), 256);
      arb_get_ubound_arf(h, r.at.t.get(), 256);
      arf_get_fmpq(lo.get(), l);
      arf_get_fmpq(hi.get(), h);
      arf_clear(l);
      arf_clear(h);
    }
    const Ball mu = mean_speed(sp, 80);
    Ball target, g_lo = integrate_speed(sp, RealAlgebraic(0), RealAlgebraic(lo), 80, 1 << 14),
                 g_hi = integrate_speed(sp, RealAlgebraic(0), RealAlgebraic(hi), 80, 1 << 14);
    arb_mul(target.get(), mu.get(), Ball(f, 256).get(), 256);
    EXPECT_FALSE(arb_gt(g_lo.get(), target.get())) << g_lo.str(25) << " > " << target.str(25);
    EXPECT_FALSE(arb_lt(g_hi.get(), target.get())) << g_hi.str(25) << " < " << target.str(25);
  }
}

namespace {

// The turning angle G(t) of the bump (t, 1/(1 + C (t - c)^2)) from 0 to the
// rational t, theta = atan y', A = atan m (m = 3 sqrt(3C) / 8, the largest |y'|):
// theta(t) - theta(0) before the inflection i1 = c - 1/sqrt(3C),
// 2A - theta(0) - theta(t) between i1 and i2 = c + 1/sqrt(3C), and
// 4A - theta(0) + theta(t) after i2.
Ball bump_angle_to(const std::string& C, const Rational& c, const Rational& t) {
  const long prec = 2400;
  Ball Cb, A, r3;
  arb_set_str(Cb.get(), C.c_str(), prec);
  arb_sqrt_ui(r3.get(), 3, prec);
  arb_sqrt(A.get(), Cb.get(), prec);
  arb_mul(A.get(), A.get(), r3.get(), prec);
  arb_mul_ui(A.get(), A.get(), 3, prec);
  arb_mul_2exp_si(A.get(), A.get(), -3);
  arb_atan(A.get(), A.get(), prec);
  auto theta = [&](const Rational& x) {
    Ball xb(x, prec), den, num;
    arb_sqr(den.get(), xb.get(), prec);
    arb_mul(den.get(), den.get(), Cb.get(), prec);
    arb_add_ui(den.get(), den.get(), 1, prec);
    arb_sqr(den.get(), den.get(), prec);
    arb_mul(num.get(), Cb.get(), xb.get(), prec);
    arb_mul_si(num.get(), num.get(), -2, prec);
    arb_div(num.get(), num.get(), den.get(), prec);
    arb_atan(num.get(), num.get(), prec);
    return num;
  };
  // the side of t against the inflections: (t - c)^2 3C against 1
  const Rational x = t - c;
  Ball q(x * x * Rational(3), prec);
  arb_mul(q.get(), q.get(), Cb.get(), prec);
  const bool outside = arb_gt(q.get(), Ball(1).get());
  const Ball th = theta(x), th0 = theta(Rational(0) - c);
  Ball g;
  if (!outside) {  // 2A - theta(0) - theta(t)
    arb_mul_2exp_si(g.get(), A.get(), 1);
    arb_sub(g.get(), g.get(), th.get(), prec);
  } else if (x.sign() < 0) {
    g = th;
  } else {  // 4A + theta(t)
    arb_mul_2exp_si(g.get(), A.get(), 2);
    arb_add(g.get(), g.get(), th.get(), prec);
  }
  arb_sub(g.get(), g.get(), th0.get(), prec);
  return g;
}

// The turning angle of the bump (t, 1/(1 + C (t - c)^2)) over [0, 1]: y' rises
// from y'(0) > 0 to m = 3 sqrt(3) sqrt(C) / 8 at the inflection c - 1/sqrt(3C),
// falls to -m at c + 1/sqrt(3C) and rises to y'(1) < 0, so
// mu = 4 atan(m) - atan(y'(0)) + atan(y'(1)).
Ball bump_turning_angle(const std::string& C, const Rational& c) { return bump_angle_to(C, c, Rational(1)); }

}  // namespace

// The bump (t, 1/(1 + C (t - c)^2)), C of 50 to 300 digits: the angular
// speed has structure at three scales about c (a peak 1/C wide, the
// inflections at 1/sqrt(3C), the slope's return to 1 at C^(-1/3)). In a
// balanced chart the outer two were squeezed next to u = 1 (from C ~ 10^48
// on, no quadrature converged: over 60 s); the affine charts' power basis is
// the Taylor expansion about c, accurate at every distance. mu matches the
// closed form, and the arc length lies between the polygon through
// p(0), p(c), p(1) and the total variation of the coordinates (which it
// meets to about C^(-1/3)).
TEST(SpeedCharts, BumpsWithThreeScalesMatchTheClosedForm) {
  TimeBudget budget(60);
  std::mt19937 rng(20261204);
  for (int trial = 0; trial < 3; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, trial == 0 ? 50 : trial == 1 ? 120 : 300);
    const Rational c = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("(t, 1/(1 + " + C + "*(t - " + c.str() + ")^2))");
    SCOPED_TRACE(p.str());
    Options o;
    o.digits = 20;
    const UniformityResult r = uniformity(p, SpeedKind::Angular, o);
    const Ball mu = bump_turning_angle(C, c);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(25) << " vs " << mu.str(25);
    EXPECT_TRUE(r.u.meets_digits(20));
    EXPECT_FALSE(arb_gt(r.u.get(), Ball(1).get()));
    const UniformityResult a = uniformity(p, SpeedKind::Parametric, o);
    const long prec = 256;
    const Rational y0 = p.components()[1](Rational(0)), y1 = p.components()[1](Rational(1));
    Ball lower, leg, upper(Rational(3) - y0 - y1, prec);
    arb_sqrt(lower.get(), Ball(c * c + (Rational(1) - y0) * (Rational(1) - y0), prec).get(), prec);
    arb_sqrt(leg.get(), Ball((Rational(1) - c) * (Rational(1) - c) + (Rational(1) - y1) * (Rational(1) - y1), prec).get(), prec);
    arb_add(lower.get(), lower.get(), leg.get(), prec);
    EXPECT_TRUE(arb_gt(a.mu.get(), lower.get())) << a.mu.str(25) << " vs polygon " << lower.str(25);
    EXPECT_FALSE(arb_gt(a.mu.get(), upper.get())) << a.mu.str(25) << " vs " << upper.str(25);
    EXPECT_TRUE(a.u.meets_digits(20));
  }
}

namespace {

// Checks G(lo) <= f mu <= G(hi) at the rational ends of the located t's ball.
void expect_bump_point(const LocatedPoint& at, const std::string& C, const Rational& c, const Rational& f) {
  const long prec = 2400;
  Rational lo, hi;
  arf_t l, h;
  arf_init(l);
  arf_init(h);
  arb_get_lbound_arf(l, at.t.get(), prec);
  arb_get_ubound_arf(h, at.t.get(), prec);
  arf_get_fmpq(lo.get(), l);
  arf_get_fmpq(hi.get(), h);
  arf_clear(l);
  arf_clear(h);
  Ball target;
  arb_mul(target.get(), bump_turning_angle(C, c).get(), Ball(f, prec).get(), prec);
  EXPECT_FALSE(arb_gt(bump_angle_to(C, c, lo).get(), target.get())) << at.t.str(30);
  EXPECT_FALSE(arb_lt(bump_angle_to(C, c, hi).get(), target.get())) << at.t.str(30);
  EXPECT_TRUE(at.t.meets_digits(15)) << at.t.str(30);
}

}  // namespace

// Locating on bumps (t, 1/(1 + C (t - c)^2)), C of 50 to 60 digits: the
// feature's scales (1/C, 1/sqrt(3C), C^(-1/3)) each need their own zoom, so
// the balanced charts are a ladder of parts zooming by 2^16 at most (one
// balanced chart spread 1/sqrt(C) and squeezed the rest next to u = 1: no
// point within 60 s). Each located t brackets its target turning angle in
// the closed form, by locate and by the exact samples.
TEST(SpeedCharts, PointsLocatedOnBumpsBracketTheirTargets) {
  TimeBudget budget(60);
  std::mt19937 rng(20261205);
  for (int trial = 0; trial < 2; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 50 + 10 * trial);
    const Rational c = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("(t, 1/(1 + " + C + "*(t - " + c.str() + ")^2))");
    SCOPED_TRACE(p.str());
    const Speed s(p, SpeedKind::Angular);
    check_located(p, s, {Rational(1, 10), Rational(1 + static_cast<long>(rng() % 999), 1000)}, 5,
                  [&](const LocatedPoint& at, const Rational& f) { expect_bump_point(at, C, c, f); });
  }
}

// radical on features whose pieces end next to them: the bump
// (t, 1/(1 + C (t - c)^2)) with a 250-digit C, cut at its inflections
// c -+ 1/sqrt(3C), 10^-125 from the peak, and (t, C t^2 + t^3) with a
// 100-digit C, whose piece [0, t1] ends 10^-300 from the peak at t = 0. A
// piece's length and its ends' offsets t - a, t - b came from balls of a
// and b with absolute radii 2^-prec (near c, or across the part's end from
// the neighbouring chart): the digits of a 10^-125 length cost 415 bits
// more than asked, by failed doublings, and the pieces took over 40 s.
// They now come from the ends' chart coordinates, enclosed relatively.
// Within a TimeBudget: mu is the closed form (the bump's from its
// inflections; atan(y'(1)) = atan(2C + 3) for y'' > 0), u(p) from the
// pieces' integrals of omega^2 agrees with uniformity()'s, and the Moebius
// step does not lower u.
TEST(SpeedCharts, RadicalPiecesNextToFeaturesKeepTheirDigits) {
  TimeBudget budget(30);
  std::mt19937 rng(20261209);
  const std::string Cb = test_support::random_positive_digits(rng, 250);
  const Rational c = test_support::random_inner_rational(rng);
  const std::string Cc = test_support::random_positive_digits(rng, 100);
  const long prec = 2400;
  Ball cubic_mu;
  arb_set_str(cubic_mu.get(), Cc.c_str(), prec);
  arb_mul_2exp_si(cubic_mu.get(), cubic_mu.get(), 1);
  arb_add_ui(cubic_mu.get(), cubic_mu.get(), 3, prec);
  arb_atan(cubic_mu.get(), cubic_mu.get(), prec);
  const struct {
    Curve p;
    Ball mu;
  } cases[] = {{Curve::parse("(t, 1/(1 + " + Cb + "*(t - " + c.str() + ")^2))"), bump_turning_angle(Cb, c)},
               {Curve::parse("(t, " + Cc + "*t^2 + t^3)"), cubic_mu}};
  for (const auto& k : cases) {
    SCOPED_TRACE(k.p.str().substr(0, 60));
    Options o;
    o.digits = 20;
    const RadicalResult r = radical(k.p, SpeedKind::Angular, o);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), k.mu.get())) << r.mu.str(25) << " vs " << k.mu.str(25);
    const UniformityResult u = uniformity(k.p, SpeedKind::Angular, o);
    EXPECT_TRUE(arb_overlaps(r.u_before.get(), u.u.get())) << r.u_before.str(25) << " vs " << u.u.str(25);
    EXPECT_TRUE(r.u_before.meets_digits(20));
    EXPECT_TRUE(r.u_after.meets_digits(20));
    EXPECT_FALSE(arb_lt(r.u_after.get(), r.u_before.get())) << r.u_after.str(25) << " < " << r.u_before.str(25);
  }
}

// The radical map evaluated next to a peak at a piece's end: on
// (t, C t^2 (1 - t)^2) with a 100-digit C the piece [i1, 1/2] (a zero of
// omega at the inflection i1, the peak at 1/2) has alpha ~ 10^-100, and r(z)
// for z inside it lies about 10^-100 from 1/2, where omega varies on that
// scale. t and the new speed come from the nearer end, 1 - x and 1 - y as
// complements, so the map's data at the digits asked suffice; from t_i,
// t - 1/2 kept the data's absolute error, and the data had to be refined
// past 100 digits (with a 300-digit C, to 600 digits: 20 s for `radical
// --at`). Oracle: the same map with data refined to 250 digits, evaluated
// here by the plain formulas at 2000 bits:
// t = t_i + dt sqrt(x), speed = sigma(t) dt x'(zt) / (2 sqrt(x) dz) with
// x = (1 - a) zt / ((1 - a) zt + a (1 - zt)), x' = a (1 - a) / den^2.
TEST(SpeedCharts, RadicalMapNextToAPeakEndFromTheNearerEnd) {
  TimeBudget budget(60);
  std::mt19937 rng(20261210);
  const std::string C = test_support::random_positive_digits(rng, 100);
  const Curve p = Curve::parse("(t, " + C + "*t^2*(1 - t)^2)");
  const Speed s(p, SpeedKind::Angular);
  Options o;
  o.digits = 20;
  const RadicalResult r = radical(p, SpeedKind::Angular, o);
  ASSERT_EQ(r.pieces(), 4u);
  ASSERT_EQ(r.side(1), ZeroSide::Left);
  ASSERT_EQ(r.root_index(1), 2);
  const RadicalResult fine = refine_radical_data(s, r, 250, 1L << 14);
  const long hp = 2000;
  for (int trial = 0; trial < 3; ++trial) {
    // z in (0.26, 0.49), inside [Z_1, Z_2] = [1/4, 1/2] (by symmetry)
    const Rational z(26000 + static_cast<long>(rng() % 23000), 100000);
    SCOPED_TRACE(z.str());
    Ball zt, dz, x, dx, y, t, dt, speed;
    arb_sub(dz.get(), fine.Z[2].get(), fine.Z[1].get(), hp);
    arb_sub(zt.get(), Ball(z, hp).get(), fine.Z[1].get(), hp);
    arb_div(zt.get(), zt.get(), dz.get(), hp);
    test_support::local_moebius(x, dx, zt, fine.integrals[1].alpha, hp);
    arb_sqrt(y.get(), x.get(), hp);
    const Ball ta = fine.T[1].t.to_ball(hp), tb = fine.T[2].t.to_ball(hp);
    arb_sub(dt.get(), tb.get(), ta.get(), hp);
    arb_mul(t.get(), y.get(), dt.get(), hp);
    arb_add(t.get(), t.get(), ta.get(), hp);
    speed = s.eval_real(t, hp);
    arb_mul(speed.get(), speed.get(), dt.get(), hp);
    arb_mul(speed.get(), speed.get(), dx.get(), hp);
    arb_div(speed.get(), speed.get(), y.get(), hp);
    arb_mul_2exp_si(speed.get(), speed.get(), -1);
    arb_div(speed.get(), speed.get(), dz.get(), hp);
    ASSERT_TRUE(speed.meets_digits(20)) << speed.str(30);
    Ball t_minus_half;
    arb_sub(t_minus_half.get(), t.get(), Ball(Rational(1, 2), hp).get(), hp);
    ASSERT_TRUE(arb_is_negative(t_minus_half.get()));
    // the map with its 20-digit data, at a working precision that resolves
    // t - 1/2 (about 10^-100)
    const long prec = 500;
    const Ball zb(z, prec);
    const Ball tf = eval_r(r, zb, prec), sf = eval_speed(r, s, zb, prec);
    EXPECT_TRUE(arb_overlaps(tf.get(), t.get())) << tf.str(30) << " vs " << t.str(30);
    EXPECT_TRUE(arb_overlaps(sf.get(), speed.get())) << sf.str(30) << " vs " << speed.str(30);
    EXPECT_TRUE(sf.meets_digits(15)) << sf.str(30);
    Ball df;
    arb_sub(df.get(), tf.get(), Ball(Rational(1, 2), prec).get(), prec);
    EXPECT_TRUE(df.meets_digits(15)) << "t - 1/2 = " << df.str(30);
  }
}
