// Exact samples from Taylor models of the arc length (reparam/src/arc_model.hpp):
// every ball must contain the exact parameter, checked against closed forms
// (a straight segment traced non-uniformly, the parabola (t, c t^2), the
// rational circle) and against the chain of certified integrals at 40
// digits (random Bezier and rational curves, both speeds, zeros of sigma at
// rational and irrational parameters, composite curves); and the models
// must replace the certified integrals (counted through the internal Track
// interface of reparam/src/track.hpp).
#include <gtest/gtest.h>

#include <arb.h>

#include <random>
#include <string>
#include <vector>

#include "../../reparam/src/track.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

constexpr long kPrec = 256;

// A Track for one curve that counts integral() and offers the curve's
// segment (Taylor models) or not (the chain of certified integrals only).
class CountingTrack final : public Track {
 public:
  CountingTrack(const Curve& c, const Speed& s, bool models) : c_(c), s_(s), models_(models) {}
  bool identically_zero() const override { return s_.identically_zero(); }
  SpeedKind kind() const override { return s_.kind(); }
  Ball mu(long bits, const Options& opt) const override {
    ++count;
    return mean_speed(s_, bits, opt);
  }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    ++count;
    return integrate_speed(s_, RealAlgebraic(a), RealAlgebraic(b), bits, Options{}.max_prec);
  }
  double sigma_estimate(const Rational& x) const override { return uniparam::sigma_estimate(s_, x); }
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }
  std::vector<Segment> segments() const override {
    if (!models_) return {};
    return {Segment{Rational(0), Rational(1), &s_}};
  }
  mutable long count = 0;

 private:
  const Curve& c_;
  const Speed& s_;
  bool models_;
};

std::vector<Ball> samples_on(const Track& tr, long K, long digits) {
  Options opt;
  opt.digits = digits;
  Ball mu;
  std::vector<Ball> ts;
  exact_samples_on(tr, K, opt, mu, [&](long, const LocatedPoint& p) { ts.push_back(p.t); });
  return ts;
}

// The ends of a ball, as exact balls.
Ball lower_end(const Ball& x) {
  Ball r;
  arb_get_lbound_arf(arb_midref(r.get()), x.get(), kPrec);
  return r;
}
Ball upper_end(const Ball& x) {
  Ball r;
  arb_get_ubound_arf(arb_midref(r.get()), x.get(), kPrec);
  return r;
}

// G increasing, t_ball = [lo, hi]: G(lo) <= target <= G(hi) certainly.
template <class G>
bool brackets(const G& g, const Ball& t, const Ball& target) {
  Ball a = g(lower_end(t)), b = g(upper_end(t));
  arb_sub(a.get(), target.get(), a.get(), kPrec);
  arb_sub(b.get(), b.get(), target.get(), kPrec);
  return arb_is_nonnegative(a.get()) && arb_is_nonnegative(b.get());
}

Rational random_rational(std::mt19937& rng, int lo, int hi, int den) {
  std::uniform_int_distribution<int> d(lo, hi);
  return Rational(d(rng), den);
}

std::string q(const Rational& x) { return "(" + x.str() + ")"; }

// Random Bezier curves (quadratic and cubic, small integer control points).
std::vector<Curve> random_beziers(std::mt19937& rng, int n) {
  std::vector<Curve> out;
  std::uniform_int_distribution<int> coord(-20, 20), deg(2, 3);
  while (static_cast<int>(out.size()) < n) {
    std::vector<std::vector<Rational>> pts;
    const int d = deg(rng);
    for (int i = 0; i <= d; ++i) pts.push_back({Rational(coord(rng)), Rational(coord(rng))});
    const Curve c = BezierCurve(pts).to_curve();
    const Speed s(c, SpeedKind::Angular);
    if (s.identically_zero()) continue;  // collinear control points
    out.push_back(c);
  }
  return out;
}

}  // namespace

// A straight segment traced as P0 + (P1 - P0) (t^2 + a t) / (1 + a): its
// arc length is |P1 - P0| (t^2 + a t) / (1 + a), so t_k solves
// t^2 + a t = s_k (1 + a) exactly (a = 0: sigma vanishes at t = 0).
TEST(LocateModel, NonUniformSegmentContainsTheExactRoots) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 8; ++trial) {
    const Rational a = trial == 0 ? Rational(0) : random_rational(rng, 1, 40, 8);
    const Rational x0 = random_rational(rng, -9, 9, 2), y0 = random_rational(rng, -9, 9, 2);
    const Rational dx = random_rational(rng, 1, 99, 3), dy = random_rational(rng, -99, 99, 7);
    const std::string u = "((t^2 + " + q(a) + "*t) / " + q(Rational(1) + a) + ")";
    const Curve c = Curve::parse("(" + q(x0) + " + " + q(dx) + "*" + u + ", " + q(y0) + " + " + q(dy) + "*" + u + ")");
    const Speed s(c, SpeedKind::Parametric);
    for (long K : {11L, 101L}) {
      const ExactSamples e = exact_samples(c, s, K);
      ASSERT_EQ(e.points.size(), static_cast<std::size_t>(K));
      for (long k = 0; k < K; ++k) {
        // t = (-a + sqrt(a^2 + 4 s (1 + a))) / 2
        Ball A(a, kPrec), sk(Rational(k, K - 1) * (Rational(1) + a) * Rational(4), kPrec), t;
        arb_mul(t.get(), A.get(), A.get(), kPrec);
        arb_add(t.get(), t.get(), sk.get(), kPrec);
        arb_sqrt(t.get(), t.get(), kPrec);
        arb_sub(t.get(), t.get(), A.get(), kPrec);
        arb_mul_2exp_si(t.get(), t.get(), -1);
        const Ball& got = e.points[static_cast<std::size_t>(k)].t;
        EXPECT_TRUE(got.contains(t)) << c.str() << " K=" << K << " k=" << k;
        EXPECT_TRUE(got.meets_digits(16));
      }
    }
  }
}

// The parabola (t, c t^2): G(t) = (w sqrt(1 + w^2) + asinh w) / (4 c), w = 2 c t.
TEST(LocateModel, ParabolaPointsBracketEqualStepsOfTheClosedForm) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 8; ++trial) {
    const Rational cr = trial == 0 ? Rational(1) : random_rational(rng, 1, 400, 16);
    const Curve c = Curve::parse("(t, " + q(cr) + "*t^2)");
    const Speed s(c, SpeedKind::Parametric);
    const Ball C(cr, kPrec);
    auto G = [&](const Ball& t) {
      Ball w, r, as;
      arb_mul(w.get(), t.get(), C.get(), kPrec);
      arb_mul_2exp_si(w.get(), w.get(), 1);
      arb_mul(r.get(), w.get(), w.get(), kPrec);
      arb_add_ui(r.get(), r.get(), 1, kPrec);
      arb_sqrt(r.get(), r.get(), kPrec);
      arb_mul(r.get(), r.get(), w.get(), kPrec);
      arb_asinh(as.get(), w.get(), kPrec);
      arb_add(r.get(), r.get(), as.get(), kPrec);
      arb_div(r.get(), r.get(), C.get(), kPrec);
      arb_mul_2exp_si(r.get(), r.get(), -2);
      return r;
    };
    const Ball mu = G(Ball(1));
    for (long K : {11L, 101L}) {
      const ExactSamples e = exact_samples(c, s, K);
      EXPECT_TRUE(e.mu.contains(mu)) << c.str();
      for (long k = 1; k + 1 < K; ++k) {
        Ball target;
        arb_mul_si(target.get(), mu.get(), k, kPrec);
        arb_div_si(target.get(), target.get(), K - 1, kPrec);
        const Ball& t = e.points[static_cast<std::size_t>(k)].t;
        EXPECT_TRUE(brackets(G, t, target)) << c.str() << " K=" << K << " k=" << k;
        EXPECT_TRUE(t.meets_digits(16));
      }
    }
  }
}

// The rational circle of radius R: arc length 2 R atan t, turning angle
// 2 atan t, so t_k = tan(k pi / (4 (K - 1))) for both speeds.
TEST(LocateModel, CircleBothSpeedsContainTanOfEqualSteps) {
  for (const Rational R : {Rational(1), Rational(3, 7), Rational(1000)}) {
    const Curve c = Curve::parse("(" + q(R) + "*(1 - t^2)/(1 + t^2), " + q(R) + "*2*t/(1 + t^2))");
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const Speed s(c, kind);
      const long K = 101;
      const ExactSamples e = exact_samples(c, s, K);
      for (long k = 0; k + 1 < K; ++k) {  // t = 1 exactly at k = K - 1
        Ball t;
        arb_const_pi(t.get(), kPrec);
        arb_mul_si(t.get(), t.get(), k, kPrec);
        arb_div_si(t.get(), t.get(), 4 * (K - 1), kPrec);
        arb_tan(t.get(), t.get(), kPrec);
        EXPECT_TRUE(e.points[static_cast<std::size_t>(k)].t.contains(t)) << to_string(kind) << " R=" << R.str();
      }
    }
  }
}

// Random Bezier curves (inflections: irrational zeros of the angular speed)
// and rational curves, both speeds: each 15-digit ball contains the
// 40-digit ball of the chain of certified integrals.
TEST(LocateModel, RandomCurvesContainTheFortyDigitChain) {
  std::mt19937 rng(7);
  std::vector<Curve> curves = random_beziers(rng, 6);
  curves.push_back(Curve::parse("((1 + 2*t - t^3)/(1 + t^2), (t - 3*t^2)/(2 + t + t^2))"));
  curves.push_back(Curve::parse("(t^2, t^3 - t/3, 1/(3 + t))"));
  for (const Curve& c : curves) {
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const Speed s(c, kind);
      const CountingTrack chain(c, s, false);
      const std::vector<Ball> ref = samples_on(chain, 11, 40);
      const ExactSamples e = exact_samples(c, s, 11);
      for (std::size_t k = 0; k < ref.size(); ++k)
        EXPECT_TRUE(e.points[k].t.contains(ref[k])) << c.str() << " " << to_string(kind) << " k=" << k;
    }
  }
}

// Zeros of the parametric speed: the cusp of ((2t - 1)^2, (2t - 1)^3) at the
// rational 1/2 (a cell boundary: sigma's continuation is analytic across
// it) and that of (u^2, u^3), u = t^2 - 1/2, at the irrational 1/sqrt(2)
// (a short gap of certified integrals), besides sigma = 0 at t = 0.
TEST(LocateModel, CuspsRationalAndIrrationalContainTheFortyDigitChain) {
  for (const std::string text : {"((2*t - 1)^2, (2*t - 1)^3)", "((t^2 - 1/2)^2, (t^2 - 1/2)^3)"}) {
    const Curve c = Curve::parse(text);
    const Speed s(c, SpeedKind::Parametric);
    ASSERT_FALSE(s.zeros().empty());
    for (long K : {11L, 52L}) {
      const CountingTrack chain(c, s, false);
      const std::vector<Ball> ref = samples_on(chain, K, 40);
      const CountingTrack models(c, s, true);
      const std::vector<Ball> got = samples_on(models, K, 15);
      ASSERT_EQ(got.size(), ref.size());
      for (std::size_t k = 0; k < ref.size(); ++k) {
        EXPECT_TRUE(got[k].contains(ref[k])) << text << " K=" << K << " k=" << k;
        EXPECT_TRUE(got[k].meets_digits(16));
      }
    }
  }
}

// A composite curve (the curve cut at rationals, each part re-parameterized
// onto [0, 1]) is the same parameterized curve: its points contain the
// single curve's 40-digit ones.
TEST(LocateModel, CompositeCurveContainsTheSingleCurvesFortyDigitPoints) {
  const Curve c = Curve::parse("(t^2 + t, t^3 - t)");
  const Speed s(c, SpeedKind::Parametric);
  const CountingTrack chain(c, s, false);
  const std::vector<Ball> ref = samples_on(chain, 21, 40);
  std::vector<Curve> segs;
  const std::vector<Rational> knots = {Rational(0), Rational(1, 3), Rational(5, 7), Rational(1)};
  for (std::size_t j = 0; j + 1 < knots.size(); ++j) {
    const std::string x = "(" + q(knots[j]) + " + " + q(knots[j + 1] - knots[j]) + "*t)";
    segs.push_back(Curve::parse("(" + x + "^2 + " + x + ", " + x + "^3 - " + x + ")"));
  }
  const CompositeCurve cc(segs, knots);
  const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
  Ball mu;
  long n = 0;
  exact_samples_each(cc, sp, 21, Options{}, mu, [&](long k, const LocatedPoint& p) {
    EXPECT_TRUE(p.t.contains(ref[static_cast<std::size_t>(k)])) << k;
    ++n;
  });
  EXPECT_EQ(n, 21);
}

// The work: on smooth arcs the models replace the certified integrals
// altogether (mu and every point from the models: fewer than one integral
// per 20 points, where the chain takes at least 2 a point), and the library's
// exact_samples takes that path (the same balls as the counted track with
// models). Near the irrational cusp the gap costs a few integrals in all.
TEST(LocateModel, ModelsTakeFewerCertifiedIntegralsPerPoint) {
  const std::vector<std::string> curves = {
      "(t, t^2)",
      "((1-t)^2*170 + 2*t*(1-t)*272 + t^2*753/2, (1-t)^2*272 + 2*t*(1-t)*208 + t^2*351/2)",
      "(t, t^3 - t/2)",
      "((1 - t^2)/(1 + t^2), 2*t/(1 + t^2))",
      "((t^2 - 1/2)^2, (t^2 - 1/2)^3)",
  };
  const long K = 101;
  for (const std::string& text : curves) {
    const Curve c = Curve::parse(text);
    const Speed s(c, SpeedKind::Parametric);
    CountingTrack chain(c, s, false), models(c, s, true);
    samples_on(chain, K, 15);
    const std::vector<Ball> got = samples_on(models, K, 15);
    const double per_chain = static_cast<double>(chain.count) / (K - 2);
    const double per_model = static_cast<double>(models.count) / (K - 2);
    EXPECT_GE(per_chain, 2.0) << text;
    EXPECT_LT(per_model * 4, per_chain) << text;
    if (s.zeros().empty()) EXPECT_LT(per_model, 0.05) << text;
    const ExactSamples lib = exact_samples(c, s, K);
    for (std::size_t k = 0; k < got.size(); ++k)
      EXPECT_TRUE(arb_equal(got[k].get(), lib.points[k].t.get())) << text << " k=" << k;
  }
}
