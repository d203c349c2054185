// Composite curves: a curve cut at rational parameters into segments (each
// re-parameterized onto [0, 1] exactly) is the same parameterized curve, so
// its composite uniformity, located points and samples must agree with the
// single curve's, and the composite method on breakpoints at the cuts must
// give the single curve's optimal C0 map for those breakpoints.
#include <gtest/gtest.h>

#include <arb.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

// p restricted to [a, b], re-parameterized onto [0, 1]: p(a + (b - a) s).
Curve restrict(const Curve& c, const Rational& a, const Rational& b) {
  const RatFunc lin = parse_expression("(" + a.str() + ") + ((" + b.str() + ") - (" + a.str() + "))*t");
  std::vector<RatFunc> comp;
  for (const RatFunc& f : c.components()) comp.push_back(compose(f, lin));
  return Curve(comp);
}

// The curve cut at `cuts` (strictly inside (0, 1), increasing).
CompositeCurve cut(const Curve& c, const std::vector<Rational>& cuts) {
  std::vector<Rational> knots{Rational(0)};
  for (const Rational& x : cuts) knots.push_back(x);
  knots.push_back(Rational(1));
  std::vector<Curve> segs;
  for (std::size_t j = 0; j + 1 < knots.size(); ++j) segs.push_back(restrict(c, knots[j], knots[j + 1]));
  return CompositeCurve(segs, knots);
}

bool overlap(const Ball& a, const Ball& b) { return arb_overlaps(a.get(), b.get()); }

std::vector<std::string> curves() {
  return {"(t, t^2)", "(t^2 + t, t^3 - t)", "((1 - t^2)/(1 + t^2), 2*t/(1 + t^2))", "(t, 1/(2 + t), t^2 - t)",
          "(3*t^3 - t, t^2 + 1/3*t)"};
}

// Random cut points: 1 to 3 rationals with small denominators.
std::vector<Rational> random_cuts(std::mt19937& rng) {
  std::uniform_int_distribution<int> count(1, 3), num(1, 30);
  std::vector<Rational> cuts;
  const int n = count(rng);
  while (static_cast<int>(cuts.size()) < n) {
    const Rational x(num(rng), 31);
    bool fresh = true;
    for (const Rational& y : cuts) fresh = fresh && y != x;
    if (fresh) cuts.push_back(x);
  }
  std::sort(cuts.begin(), cuts.end(), [](const Rational& a, const Rational& b) { return a < b; });
  return cuts;
}

TEST(Composite, CutCurveHasTheSameUniformityProperty) {
  std::mt19937 rng(7);
  for (const std::string& text : curves())
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const Curve c = Curve::parse(text);
      const CompositeCurve cc = cut(c, random_cuts(rng));
      const UniformityResult one = uniformity(c, kind);
      const CompositeUniformity many = uniformity(cc, kind);
      EXPECT_TRUE(overlap(one.mu, many.mu)) << text;
      EXPECT_TRUE(overlap(one.mean_square, many.mean_square)) << text;
      EXPECT_TRUE(overlap(one.u, many.u)) << text;
      EXPECT_TRUE(many.u.meets_digits(15));
      for (const Joint& j : many.joints) {
        EXPECT_TRUE(j.continuous && j.smooth) << text;
        EXPECT_TRUE(j.angle.certainly_zero());
      }
    }
}

TEST(Composite, CornerAnglesOfAPolyline) {
  // (0,0) -> (1,0) -> (1,1) -> (0,0): turns of pi/2 and 3 pi/4.
  const CompositeCurve c({Curve::parse("(t, 0)"), Curve::parse("(1, t)"), Curve::parse("(1 - t, 1 - t)")},
                         {Rational(0), Rational(1, 3), Rational(2, 3), Rational(1)});
  const std::vector<Joint> j = joints(c, 128);
  ASSERT_EQ(j.size(), 2u);
  Ball pi;
  arb_const_pi(pi.get(), 128);
  Ball half = pi, three_quarters = pi;
  arb_mul_2exp_si(half.get(), half.get(), -1);
  arb_mul_ui(three_quarters.get(), pi.get(), 3, 128);
  arb_mul_2exp_si(three_quarters.get(), three_quarters.get(), -2);
  EXPECT_TRUE(j[0].continuous);
  EXPECT_FALSE(j[0].smooth);
  EXPECT_TRUE(overlap(j[0].angle, half));
  EXPECT_TRUE(overlap(j[1].angle, three_quarters));
  // Arc length of the polyline: 1 + 1 + sqrt 2.
  const CompositeUniformity u = uniformity(c, SpeedKind::Parametric);
  Ball len(2);
  Ball r2(2);
  arb_sqrt(r2.get(), r2.get(), 128);
  arb_add(len.get(), len.get(), r2.get(), 128);
  EXPECT_TRUE(overlap(u.mu, len));
  // The angular speed of straight segments is identically zero.
  const CompositeUniformity a = uniformity(c, SpeedKind::Angular);
  EXPECT_TRUE(a.identically_zero);
  EXPECT_TRUE(a.mu.certainly_zero());
}

TEST(Composite, CuspAtAJointHasItsTurningAngle) {
  // Two quadratic arcs meeting with reversed tangents: angle pi.
  const CompositeCurve c({Curve::parse("(t, t^2)"), Curve::parse("(1 - t, 1 - 2*t + t^2)")},
                         {Rational(0), Rational(1, 2), Rational(1)});
  const std::vector<Joint> j = joints(c, 128);
  Ball pi;
  arb_const_pi(pi.get(), 128);
  EXPECT_TRUE(overlap(j[0].angle, pi));
}

TEST(Composite, BreakpointsAtTheCutsGiveTheSingleCurvesOptimalMapProperty) {
  std::mt19937 rng(11);
  for (const std::string& text : curves()) {
    const Curve c = Curve::parse(text);
    const std::vector<Rational> cuts = random_cuts(rng);
    const CompositeCurve cc = cut(c, cuts);
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      std::vector<RealAlgebraic> T{RealAlgebraic(0)};
      std::vector<Rational> Tq{Rational(0)};
      for (const Rational& x : cuts) T.emplace_back(x), Tq.push_back(x);
      T.emplace_back(1);
      Tq.push_back(Rational(1));
      const MoebiusResult one = moebius_c0(c, kind, T);
      CompositeMethod m;
      m.kind = CompositeMethod::Kind::Moebius;
      const std::vector<Speed> sp = cc.speeds(kind);
      const CompositeMap many = composite_map(cc, sp, m);
      EXPECT_TRUE(overlap(one.u_after, many.u_after())) << text;
      EXPECT_TRUE(overlap(one.u_before, many.u_before())) << text;
      EXPECT_TRUE(overlap(one.mu, many.mu())) << text;
      // The same through --breakpoints given in the global parameter.
      m.kind = CompositeMethod::Kind::Breakpoints;
      m.breakpoints = Tq;
      EXPECT_TRUE(overlap(one.u_after, composite_map(cc, sp, m).u_after())) << text;
    }
  }
}

TEST(Composite, MethodsImproveAndCountPieces) {
  const Curve c = Curve::parse("(t^2 + t, t^3 - t)");
  const CompositeCurve cc = cut(c, {Rational(1, 3), Rational(1, 2)});
  const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Pieces;
  m.pieces = 7;
  const CompositeMap p = composite_map(cc, sp, m);
  EXPECT_EQ(p.pieces(), 7u);
  EXPECT_GE(mid_double(p.u_after()), mid_double(p.u_before()));
  m.pieces = 2;
  EXPECT_THROW(composite_map(cc, sp, m), InvalidArgument);
  m.kind = CompositeMethod::Kind::Radical;
  const CompositeMap r = composite_map(cc, sp, m);
  // u = (sum mu_j)^2 / (sum mu_j / sqrt u_j)^2 lies between the parts' extremes.
  double lo_u = 2, hi_u = 0;
  for (const Reparameterization& part : r.parts())
    lo_u = std::min(lo_u, mid_double(part.u_after())), hi_u = std::max(hi_u, mid_double(part.u_after()));
  EXPECT_GE(mid_double(r.u_after()), lo_u - 1e-14);
  EXPECT_LE(mid_double(r.u_after()), hi_u + 1e-14);
  EXPECT_GT(mid_double(r.u_after()), mid_double(r.u_before()));
  m.kind = CompositeMethod::Kind::Target;
  m.target = Rational(999, 1000);
  const CompositeMap t = composite_map(cc, sp, m);
  EXPECT_TRUE(t.target_reached());
  Ball lo = t.u_after();
  arb_sub(lo.get(), lo.get(), Ball(Rational(999, 1000), 128).get(), 128);
  EXPECT_TRUE(lo.certainly_positive());
  m.kind = CompositeMethod::Kind::Moebius;
  m.rational = true;
  const CompositeMap q = composite_map(cc, sp, m);
  for (const Reparameterization& part : q.parts()) EXPECT_TRUE(part.moebius_result()->exact.has_value());
}

TEST(Composite, StraightSegmentRefusedForAngularMaps) {
  const CompositeCurve c({Curve::parse("(t, t^2)"), Curve::parse("(1 + t, 1 + 2*t)")},
                         {Rational(0), Rational(1, 2), Rational(1)});
  const std::vector<Speed> sp = c.speeds(SpeedKind::Angular);
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Moebius;
  EXPECT_THROW(composite_map(c, sp, m), DomainError);
  m.kind = CompositeMethod::Kind::None;
  EXPECT_NO_THROW(composite_map(c, sp, m));
}

TEST(Composite, IdentitySamplesAreTheCurvesPoints) {
  const Curve c = Curve::parse("(t^2 + t, t^3 - t)");
  const CompositeCurve cc = cut(c, {Rational(2, 7), Rational(3, 5)});
  const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
  const CompositeMap id = composite_map(cc, sp, CompositeMethod{});
  CompositeSampler smp(cc, sp, id, 20, 4096);
  for (long k = 0; k <= 20; ++k) {
    const Rational s(k, 20);
    const SamplePoint p = smp.at(s);
    EXPECT_TRUE(p.t.contains(s)) << k;
    const std::vector<Ball> ref = c.eval(Ball(s, 256), 256);
    for (std::size_t i = 0; i < ref.size(); ++i) EXPECT_TRUE(overlap(ref[i], p.point[i])) << k;
    EXPECT_TRUE(p.t.meets_digits(20));
  }
  // A joint of the cut: both sides' speeds (equal here) and at_joint.
  EXPECT_TRUE(smp.at(Rational(2, 7)).at_joint);
}

TEST(Composite, LocateAgreesWithTheSingleCurveProperty) {
  std::mt19937 rng(3);
  for (const std::string& text : curves()) {
    const Curve c = Curve::parse(text);
    const CompositeCurve cc = cut(c, random_cuts(rng));
    const Speed s(c, SpeedKind::Parametric);
    const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
    for (const Rational f : {Rational(0), Rational(1, 7), Rational(1, 2), Rational(5, 6), Rational(1)}) {
      const LocateResult one = locate(c, s, f, LocateTarget::Fraction);
      const LocateResult many = locate(cc, sp, f, LocateTarget::Fraction);
      EXPECT_TRUE(overlap(one.at.t, many.at.t)) << text << " " << f.str();
      EXPECT_TRUE(many.at.t.meets_digits(15));
    }
    Ball mu;
    long count = 0;
    const ExactSamples ref = exact_samples(c, s, 9);
    exact_samples_each(cc, sp, 9, Options{}, mu, [&](long k, const LocatedPoint& p) {
      EXPECT_TRUE(overlap(p.t, ref.points[k].t)) << text << " " << k;
      ++count;
    });
    EXPECT_EQ(count, 9);
  }
}

TEST(Composite, NurbsOfARationalMapIsExactlyTheMapsCurve) {
  // Degrees 1 and 3 in one NURBS (the line raised); exact data: the NURBS
  // at rational s equals p(r(s)) computed from the pieces' exact Moebius maps.
  const CompositeCurve cc({Curve::parse("(t, 0)"), Curve::parse("(1 + t, t^2 - t^3/3)")},
                          {Rational(0), Rational(1, 3), Rational(1)});
  const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
  CompositeMethod m;
  m.kind = CompositeMethod::Kind::Pieces;
  m.pieces = 4;
  m.rational = true;
  const CompositeMap r = composite_map(cc, sp, m);
  const Nurbs n = composite_nurbs(cc, r, 128);
  EXPECT_EQ(n.kind, Nurbs::Kind::Exact);
  EXPECT_EQ(n.degree, 3);
  CompositeSampler smp(cc, sp, r, 30, 4096);
  for (long k = 0; k <= 12; ++k) {
    const Rational s(k, 12);
    const std::vector<Rational> v = nurbs_eval(n, s);
    const SamplePoint p = smp.at(s);
    for (std::size_t i = 0; i < v.size(); ++i) EXPECT_TRUE(p.point[i].contains(v[i])) << k;
  }
  // A gap between the segments: no NURBS.
  const CompositeCurve gap({Curve::parse("(t, t^2)"), Curve::parse("(2 + t, t)")},
                           {Rational(0), Rational(1, 2), Rational(1)});
  const std::vector<Speed> gsp = gap.speeds(SpeedKind::Parametric);
  m.rational = false;
  m.pieces = 2;
  EXPECT_THROW(composite_nurbs(gap, composite_map(gap, gsp, m), 128), InvalidArgument);
}

TEST(Composite, ArcFractionAgreesWithTheSingleCurveProperty) {
  std::mt19937 rng(5);
  for (const std::string& text : curves()) {
    const Curve c = Curve::parse(text);
    const CompositeCurve cc = cut(c, random_cuts(rng));
    const Speed s(c, SpeedKind::Parametric);
    const std::vector<Speed> sp = cc.speeds(SpeedKind::Parametric);
    ArcFraction one(s, 80, Options{}), many(cc, sp, 80, Options{});
    EXPECT_TRUE(overlap(one.mu(), many.mu())) << text;
    for (long k = 0; k <= 16; ++k) {
      const Ball t(Rational(k, 16), 128);
      EXPECT_TRUE(overlap(one.at(t), many.at(t))) << text << " " << k;
    }
  }
}

TEST(Composite, BadKnotsAreRefused) {
  const Curve a = Curve::parse("(t, t^2)");
  EXPECT_THROW(CompositeCurve({a, a}, {Rational(0), Rational(1)}), InvalidArgument);
  EXPECT_THROW(CompositeCurve({a, a}, {Rational(0), Rational(1, 2), Rational(1, 2)}), InvalidArgument);
  EXPECT_THROW(CompositeCurve({a, a}, {Rational(0), Rational(2), Rational(1)}), InvalidArgument);
  EXPECT_THROW(CompositeCurve({a, Curve::parse("(t, t, t)")}, {Rational(0), Rational(1, 2), Rational(1)}),
               InvalidArgument);
}

}  // namespace
