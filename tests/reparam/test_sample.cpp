// Certified samples of p o r (sample.hpp): the parameters are exactly
// k/(K-1); t, the point and the speed agree with an independent evaluation of
// the piecewise maps written out here from the results' data (T, S or Z,
// alpha, radical indices) and with Speed::eval_squared times r'; and the
// samples' speeds are as uniform as the methods report.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/reference.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

const char* kCubic = "(t, t^3)";  // Hong, Wang, Yang 2023, Example 16: a zero of the angular speed at t = 0
const char* kInflection = "(t, (2t - 1)^3)";  // a zero at t = 1/2: radical pieces on both sides
const char* kSlide =
    "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";  // ImUp's slides

// r(s) and r'(s) of one piece, from the result's data only.
struct Independent {
  Ball t, dt;  // dt may be infinite (a radical end at a zero of the speed)
  bool ok = false;
};

// The piece i whose open interval (lo_i, lo_{i+1}) certainly contains s; -1 if none.
long piece_of(const std::vector<Ball>& joints, const Ball& s) {
  for (std::size_t i = 0; i + 1 < joints.size(); ++i)
    if (!arb_lt(s.get(), joints[i].get()) && !arb_gt(s.get(), joints[i + 1].get()) &&
        (i == 0 || arb_gt(s.get(), joints[i].get())) &&
        (i + 2 == joints.size() || arb_lt(s.get(), joints[i + 1].get())))
      return static_cast<long>(i);
  return -1;
}

// Piecewise Moebius (ImUp): r(s) = t_i + Dt x(u), u = (s - s_i)/Ds.
Independent moebius_independent(const MoebiusResult& r, const Rational& s, long prec) {
  Independent out;
  const Ball sb(s, prec);
  const long i = piece_of(r.S, sb);
  if (i < 0) return out;
  const auto k = static_cast<std::size_t>(i);
  Ball ta = r.T[k].t.to_ball(prec), tb = r.T[k + 1].t.to_ball(prec), Dt, Ds, u, x, dx;
  arb_sub(Dt.get(), tb.get(), ta.get(), prec);
  arb_sub(Ds.get(), r.S[k + 1].get(), r.S[k].get(), prec);
  arb_sub(u.get(), sb.get(), r.S[k].get(), prec);
  arb_div(u.get(), u.get(), Ds.get(), prec);
  test_support::local_moebius(x, dx, u, r.alpha[k], prec);
  arb_mul(out.t.get(), x.get(), Dt.get(), prec);
  arb_add(out.t.get(), out.t.get(), ta.get(), prec);
  arb_mul(out.dt.get(), dx.get(), Dt.get(), prec);
  arb_div(out.dt.get(), out.dt.get(), Ds.get(), prec);
  out.ok = true;
  return out;
}

// Hong, Wang, Yang 2023: r = phi o m on piece i: x = m(u) (local Moebius), y = x^(1/k)
// (zero at the left end) or 1 - (1 - x)^(1/k) (right end), r = t_i + Dt y.
Independent radical_independent(const RadicalResult& r, const Rational& z, long prec) {
  Independent out;
  const Ball zb(z, prec);
  const long i = piece_of(r.Z, zb);
  if (i < 0) return out;
  const auto k = static_cast<std::size_t>(i);
  Ball ta = r.T[k].t.to_ball(prec), tb = r.T[k + 1].t.to_ball(prec), Dt, Dz, u, x, dx, y, dy;
  arb_sub(Dt.get(), tb.get(), ta.get(), prec);
  arb_sub(Dz.get(), r.Z[k + 1].get(), r.Z[k].get(), prec);
  arb_sub(u.get(), zb.get(), r.Z[k].get(), prec);
  arb_div(u.get(), u.get(), Dz.get(), prec);
  test_support::local_moebius(x, dx, u, r.integrals[k].alpha, prec);
  const int n = r.root_index(k);
  const ZeroSide side = r.side(k);
  if (side == ZeroSide::None) {
    y = x;
    dy = Ball(1);
  } else {
    Ball base;
    if (side == ZeroSide::Left) base = x;
    else { arb_sub_si(base.get(), x.get(), 1, prec); arb_neg(base.get(), base.get()); }
    arb_root_ui(y.get(), base.get(), static_cast<ulong>(n), prec);  // base^(1/n)
    arb_div(dy.get(), y.get(), base.get(), prec);                    // base^(1/n - 1) (infinite at base = 0)
    arb_div_ui(dy.get(), dy.get(), static_cast<ulong>(n), prec);
    if (side == ZeroSide::Right) { arb_sub_si(y.get(), y.get(), 1, prec); arb_neg(y.get(), y.get()); }
  }
  arb_mul(out.t.get(), y.get(), Dt.get(), prec);
  arb_add(out.t.get(), out.t.get(), ta.get(), prec);
  arb_mul(out.dt.get(), dy.get(), dx.get(), prec);
  arb_mul(out.dt.get(), out.dt.get(), Dt.get(), prec);
  arb_div(out.dt.get(), out.dt.get(), Dz.get(), prec);
  out.ok = true;
  return out;
}

Independent independent(const Reparameterization& r, const Rational& s, long prec) {
  if (const auto* x = r.radical_result()) return radical_independent(*x, s, prec);
  if (const auto* m = r.moebius_result()) return moebius_independent(*m, s, prec);
  Independent out;  // r = id
  out.t = Ball(s, prec);
  out.dt = Ball(1);
  out.ok = true;
  return out;
}

// p(t) evaluated from the components' numerators and denominators.
std::vector<Ball> point_at(const Curve& c, const Ball& t, long prec) {
  std::vector<Ball> out;
  for (const auto& x : c.components()) {
    Ball n = BallPoly(x.num())(t, prec), d = BallPoly(x.den())(t, prec), v;
    arb_div(v.get(), n.get(), d.get(), prec);
    out.push_back(v);
  }
  return out;
}

// sigma_p(t) * r' from Speed::eval_squared.
Ball speed_times(const Speed& sp, const Ball& t, const Ball& dr, long prec) {
  Ball v = sp.eval_real(t, prec);
  arb_mul(v.get(), v.get(), dr.get(), prec);
  return v;
}

struct Case {
  const char* curve;
  const char* method;  // "radical", "c0", "c1" (target 0.99) or "none"
  long pieces;
};

Reparameterization make(const Curve& c, const Case& k, const Options& o) {
  const std::string m = k.method;
  if (m == "radical") return Reparameterization(radical(c, SpeedKind::Angular, o));
  if (m == "c0") return Reparameterization(reparam_c0(c, SpeedKind::Angular, k.pieces, o));
  if (m == "c1") return Reparameterization(reparam_c1(c, SpeedKind::Angular, Rational(99, 100), o));
  const UniformityResult u = uniformity(c, SpeedKind::Angular, o);
  return Reparameterization::identity(u.mu, u.u);
}

const Case kCases[] = {
    {kCubic, "radical", 0}, {kInflection, "radical", 0}, {kSlide, "c0", 3}, {kCubic, "c0", 2},
    {kSlide, "c1", 0},      {kCubic, "none", 0},
};

}  // namespace

TEST(Sample, ParametersAreExactlyEquallySpacedFromZeroToOne) {
  Options o;
  o.digits = 18;
  const Curve c = parse_curve(kCubic);
  const Speed sp(c, SpeedKind::Angular);
  const Reparameterization r(radical(c, SpeedKind::Angular, o));
  for (long K : {2L, 3L, 11L}) {
    const Samples smp = sample(c, sp, r, K, 15, o.max_prec);
    ASSERT_EQ(smp.after.size(), static_cast<std::size_t>(K));
    ASSERT_EQ(smp.before.size(), static_cast<std::size_t>(K));
    EXPECT_EQ(smp.after.front().s, Rational(0));
    EXPECT_EQ(smp.after.back().s, Rational(1));
    for (long k = 0; k < K; ++k) {
      EXPECT_EQ(smp.after[k].s, Rational(k, K - 1));
      EXPECT_EQ(smp.before[k].s, Rational(k, K - 1));
      EXPECT_TRUE(smp.before[k].t.contains(Rational(k, K - 1)));  // r = id before
    }
    // r(0) = 0 and r(1) = 1: the reparameterization keeps the end points.
    EXPECT_TRUE(smp.after.front().t.contains(Rational(0)));
    EXPECT_TRUE(smp.after.back().t.contains(Rational(1)));
  }
  EXPECT_THROW(sample(c, sp, r, 1, 15, o.max_prec), InvalidArgument);
}

TEST(Sample, PointsAndSpeedsAgreeWithIndependentEvaluation) {
  Options o;
  o.digits = 18;
  const long digits = 15, K = 23, prec = 256;
  for (const Case& k : kCases) {
    SCOPED_TRACE(std::string(k.curve) + " " + k.method);
    const Curve c = parse_curve(k.curve);
    const Speed sp(c, SpeedKind::Angular);
    const Reparameterization r = make(c, k, o);
    const Samples smp = sample(c, sp, r, K, digits, o.max_prec);
    long speed_checks = 0;
    for (const SamplePoint& p : smp.after) {
      SCOPED_TRACE("s = " + p.s.str());
      // the accuracy contract (a sample on a joint gives enclosures only)
      if (!p.at_joint) {
        EXPECT_TRUE(p.t.meets_digits(digits));
        for (const auto& b : p.point) EXPECT_TRUE(b.meets_digits(digits));
        EXPECT_TRUE(p.speed.meets_digits(digits));
      }
      EXPECT_TRUE(p.speed.is_finite());
      // the point is p(t) at the sample's t, and t = r(s) independently
      const std::vector<Ball> at_t = point_at(c, p.t, prec);
      ASSERT_EQ(p.point.size(), c.dimension());
      for (std::size_t i = 0; i < at_t.size(); ++i) EXPECT_TRUE(arb_overlaps(p.point[i].get(), at_t[i].get()));
      const Independent ind = independent(r, p.s, prec);
      if (!ind.ok) {
        EXPECT_TRUE(p.at_joint) << "s lies on no piece yet is not marked at_joint";
        continue;
      }
      EXPECT_TRUE(arb_overlaps(p.t.get(), ind.t.get())) << p.t.str() << " vs " << ind.t.str();
      const std::vector<Ball> at_ind = point_at(c, ind.t, prec);
      for (std::size_t i = 0; i < at_ind.size(); ++i) EXPECT_TRUE(arb_overlaps(p.point[i].get(), at_ind[i].get()));
      // speed of p o r = sigma_p(r(s)) r'(s), where r' is finite
      if (ind.dt.is_finite()) {
        const Ball v = speed_times(sp, ind.t, ind.dt, prec);
        EXPECT_TRUE(arb_overlaps(p.speed.get(), v.get())) << p.speed.str() << " vs " << v.str();
        ++speed_checks;
      }
    }
    EXPECT_GE(speed_checks, K - 2);  // at most the end points are radical ends
  }
}

TEST(Sample, OriginalSamplesAreThePlainCurve) {
  const Curve c = parse_curve(kSlide);
  const Speed sp(c, SpeedKind::Parametric);
  const UniformityResult u = uniformity(c, SpeedKind::Parametric);
  const Reparameterization id = Reparameterization::identity(u.mu, u.u);
  const Samples smp = sample(c, sp, id, 9, 15, 4096);
  for (long k = 0; k < 9; ++k) {
    const Rational t(k, 8);
    // exact oracle: each component is an exact rational at t
    for (std::size_t i = 0; i < c.dimension(); ++i) {
      const RatFunc& x = c.components()[i];
      const Rational v = x(t);
      EXPECT_TRUE(smp.before[k].point[i].contains(v));
      EXPECT_TRUE(smp.after[k].point[i].contains(v));
    }
    // |p'(t)|^2 exactly from the derivative numerators over W
    Rational sq(0);
    for (const auto& X : c.derivative_numerators()) sq = sq + X(t) * X(t);
    const Rational w = c.derivative_denominator()(t);
    sq = sq / (w * w);
    Ball v2;
    arb_mul(v2.get(), smp.before[k].speed.get(), smp.before[k].speed.get(), 256);
    EXPECT_TRUE(v2.contains(sq));
  }
}

TEST(Sample, JointOnAnEqualStepIsMarked) {
  // (t, (2t-1)^3) is symmetric about t = 1/2, a zero of the angular speed of
  // multiplicity 1: the radical method's middle joint is z = 1/2 (up to its
  // ball), which K = 5 samples exactly. There r is only Hoelder-1/2
  // continuous, so t meets 15 digits once r is known to 2 * 15 + 3 digits.
  const Curve c = parse_curve(kInflection);
  const Speed sp(c, SpeedKind::Angular);
  for (long rdigits : {18L, 33L}) {
    Options o;
    o.digits = rdigits;
    const RadicalResult rr = radical(c, SpeedKind::Angular, o);
    ASSERT_EQ(rr.pieces() % 2, 0u);
    const std::size_t mid = rr.pieces() / 2;
    ASSERT_TRUE(rr.Z[mid].contains(Rational(1, 2)));
    ASSERT_EQ(rr.T[mid].multiplicity, 1);
    const Samples smp = sample(c, sp, Reparameterization(rr), 5, 15, o.max_prec);
    EXPECT_TRUE(smp.after[2].at_joint);
    EXPECT_TRUE(smp.after[2].t.contains(Rational(1, 2)));
    EXPECT_TRUE(smp.after[2].point[1].contains(Rational(0)));
    for (long k : {0L, 1L, 3L, 4L}) EXPECT_FALSE(smp.after[k].at_joint);
    if (rdigits == 33) {
      EXPECT_TRUE(smp.after[2].t.meets_digits(15));
      EXPECT_TRUE(meets_digits(smp, 15));
    }
  }
}

TEST(Sample, SampledSpeedsAreAsUniformAsReported) {
  // With K equal steps the trapezoid rule gives mean(sigma) and mean(sigma^2),
  // hence a discrete uniformity; it converges to u with error O(1/K) (the new
  // speed jumps at the joints) and O(1/K^2) for a smooth speed. At K = 801 it
  // must lie within 1e-3 of the certified u before and after (observed: at
  // most 1.2e-4), and order them.
  Options o;
  o.digits = 18;
  const long K = 801;
  for (const Case& k : kCases) {
    if (std::string(k.method) == "none") continue;
    SCOPED_TRACE(std::string(k.curve) + " " + k.method);
    const Curve c = parse_curve(k.curve);
    const Speed sp(c, SpeedKind::Angular);
    const Reparameterization r = make(c, k, o);
    const Samples smp = sample(c, sp, r, K, 6, o.max_prec);
    auto discrete_u = [&](const std::vector<SamplePoint>& v) {
      double m1 = 0, m2 = 0;
      for (std::size_t i = 0; i < v.size(); ++i) {
        const double w = (i == 0 || i + 1 == v.size()) ? 0.5 : 1.0;
        const double x = mid_double(v[i].speed);
        m1 += w * x;
        m2 += w * x * x;
      }
      m1 /= static_cast<double>(v.size() - 1);
      m2 /= static_cast<double>(v.size() - 1);
      return m1 * m1 / m2;
    };
    const double ub = discrete_u(smp.before), ua = discrete_u(smp.after);
    EXPECT_NEAR(ub, mid_double(r.u_before()), 1e-3);
    EXPECT_NEAR(ua, mid_double(r.u_after()), 1e-3);
    EXPECT_GT(ua, ub);
  }
}

TEST(Sample, StraightLineUnderTheAngularSpeedIsTheIdentity) {
  const Curve c = parse_curve("(t, 2t + 1)");
  const Speed sp(c, SpeedKind::Angular);
  const Reparameterization r(radical(c, SpeedKind::Angular));
  const Samples smp = sample(c, sp, r, 4, 15, 4096);
  for (long k = 0; k < 4; ++k) {
    EXPECT_TRUE(smp.after[k].t.contains(Rational(k, 3)));
    EXPECT_TRUE(smp.after[k].speed.certainly_zero() || smp.after[k].speed.contains(Rational(0)));
  }
}

TEST(Sample, MethodNamesAndJoints) {
  Options o;
  const Curve c = parse_curve(kCubic);
  const RadicalResult rr = radical(c, SpeedKind::Angular, o);
  const Reparameterization r(rr);
  EXPECT_EQ(r.method(), "radical");
  ASSERT_EQ(r.pieces(), rr.pieces());
  for (std::size_t i = 0; i <= r.pieces(); ++i) EXPECT_TRUE(arb_overlaps(r.joints_s()[i].get(), rr.Z[i].get()));
  const Reparameterization m(reparam_c0(c, SpeedKind::Angular, 2, o));
  EXPECT_EQ(m.method(), "C0 piecewise Moebius");
  EXPECT_EQ(m.pieces(), 2u);
  const MoebiusResult c1 = reparam_c1(parse_curve(kSlide), SpeedKind::Angular, Rational(99, 100), o);
  const Reparameterization m1(c1);
  EXPECT_EQ(m1.method(), "C1 piecewise Moebius");
  ASSERT_EQ(m1.pieces(), c1.pieces());
  for (std::size_t i = 0; i <= m1.pieces(); ++i) EXPECT_TRUE(arb_overlaps(m1.joints_s()[i].get(), c1.S[i].get()));
  const UniformityResult u = uniformity(c, SpeedKind::Angular, o);
  EXPECT_EQ(Reparameterization::identity(u.mu, u.u).method(), "none");
  EXPECT_THROW(r.eval_r(Ball(2), 64), InvalidArgument);
}

TEST(Sample, SpeedAtAJointBallIsBothOneSidedSpeeds) {
  // At a joint ball eval_speed unites both one-sided speeds. For the C1 map
  // the two agree, so the union stays tight. For the radical map of (t, t^3)
  // they differ (about 1.19 left and 1.06 right of Z_1, Hong, Wang, Yang 2023, Example
  // 16): the union then contains the speeds just left and right of the joint.
  Options o;
  o.digits = 20;
  {
    const Curve c = parse_curve(kSlide);
    const Speed sp(c, SpeedKind::Angular);
    const Reparameterization c1(reparam_c1(c, SpeedKind::Angular, Rational(99, 100), o));
    ASSERT_GE(c1.pieces(), 2u);
    for (std::size_t i = 1; i < c1.pieces(); ++i) {
      const Ball v = c1.eval_speed(sp, c1.joints_s()[i], 256);
      EXPECT_TRUE(v.meets_digits(8)) << "joint " << i << ": " << v.str();
    }
  }
  const Curve c = parse_curve(kCubic);
  const Speed sp(c, SpeedKind::Angular);
  const Reparameterization r(radical(c, SpeedKind::Angular, o));
  ASSERT_EQ(r.pieces(), 2u);
  const Ball& z = r.joints_s()[1];
  const Ball at = r.eval_speed(sp, z, 256);
  // 1e-12 away from the joint, outside its ball (radius <= 1e-20)
  Ball h, left, right;
  arb_set_str(h.get(), "1e-12", 256);
  arb_sub(left.get(), z.get(), h.get(), 256);
  arb_add(right.get(), z.get(), h.get(), 256);
  const Ball vl = r.eval_speed(sp, left, 256), vr = r.eval_speed(sp, right, 256);
  Ball gap;
  arb_sub(gap.get(), vl.get(), vr.get(), 256);
  Ball tenth;
  arb_set_str(tenth.get(), "0.1", 256);
  EXPECT_TRUE(arb_gt(gap.get(), tenth.get())) << vl.str() << " vs " << vr.str();
  // the one-sided speeds move by O(1e-12) from the joint: widen by 1e-9
  Ball widened = at;
  mag_t e;
  mag_init(e);
  mag_set_d(e, 1e-9);
  arb_add_error_mag(widened.get(), e);
  mag_clear(e);
  EXPECT_TRUE(arb_contains(widened.get(), vl.get()));
  EXPECT_TRUE(arb_contains(widened.get(), vr.get()));
}
