// Robust evaluation of the reparameterizations: the rational rounding of
// alpha keeps 0 < alpha < 1 with a relative accuracy (make_rational); the
// samples of an ill-conditioned but well-posed map refine its data instead of
// failing, and contain independently computed values (a map computed to far
// more digits, or exact rational arithmetic for a rational map); exact ends
// stay exact; sample_each hands over each sample as soon as it is certified.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

const char* kSteep = "(t, 10000000000*(t-1/2)^3)";  // well-posed, but r(s) is very sensitive to r's data
const char* kEndsAtOrigin = "(t^2 - t, t^3 - 1)";  // p(1) = (0, 0)
const char* kCubic = "(t, t^3)";
const char* kSlide =
    "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";

Curve parse_curve(const char* s) { return Curve::parse(s); }

Rational pow10_inv(long d) {
  Integer p(1);
  for (long i = 0; i < d; ++i) p = p * Integer(10);
  return Rational(Integer(1), p);
}

// |q - alpha| <= tol * min(alpha, 1 - alpha) certainly, for the true alpha in
// the (narrow) reference ball `alpha`.
bool within_relative(const Rational& q, const Ball& alpha, const Rational& tol) {
  const long prec = 512;
  Ball d, m, one_minus, bound;
  const Ball qb(q, prec), tb(tol, prec);
  arb_sub(d.get(), qb.get(), alpha.get(), prec);
  arb_abs(d.get(), d.get());
  arb_sub_si(one_minus.get(), alpha.get(), 1, prec);
  arb_neg(one_minus.get(), one_minus.get());
  arb_min(m.get(), alpha.get(), one_minus.get(), prec);
  arb_mul(bound.get(), tb.get(), m.get(), prec);
  return arb_le(d.get(), bound.get());
}

}  // namespace

TEST(EvalRobust, RationalAlphaNearZeroOrOneStaysInsideWithRelativeAccuracy) {
  // The optimal alpha of (t, 1/(t - 1 - eps)) is about eps, that of
  // (t, 1/(t + eps)) about 1 - eps: rounded to an absolute 10^-8 they became
  // 0 or 1 (k = (1 - alpha) / alpha: division by zero).
  Options o;
  Options ref;
  ref.digits = 40;
  for (const char* e : {"1/1000000", "1/1000000000", "1/1000000000000"}) {
    for (const std::string curve : {std::string("(t, 1/(t - 1 - ") + e + "))", std::string("(t, 1/(t + ") + e + "))"}) {
      SCOPED_TRACE(curve);
      const Curve c = Curve::parse(curve);
      for (long rd : {4L, 8L, 12L}) {
        SCOPED_TRACE(rd);
        MoebiusResult q;
        ASSERT_NO_THROW(q = make_rational(c, moebius_optimal(c, SpeedKind::Parametric, o), rd, o));
        ASSERT_EQ(q.exact->alpha.size(), 1u);
        EXPECT_GT(q.exact->alpha[0], Rational(0));
        EXPECT_LT(q.exact->alpha[0], Rational(1));
        const MoebiusResult exact = moebius_optimal(c, SpeedKind::Parametric, ref);
        EXPECT_TRUE(within_relative(q.exact->alpha[0], exact.alpha[0], pow10_inv(rd)))
            << q.exact->alpha[0].str() << " vs " << exact.alpha[0].str(45);
        EXPECT_TRUE(q.u_after.meets_digits(o.digits));
      }
    }
  }
}

TEST(EvalRobust, RationalAlphaOfChosenBreakpointsHasRelativeAccuracy) {
  // Every rounded alpha is certainly within 10^-d min(alpha, 1 - alpha) of the
  // optimal alpha of the map's own (unrounded) T, computed again to 40 digits.
  Options o;
  Options ref;
  ref.digits = 40;
  for (const char* curve : {kCubic, kSlide}) {
    SCOPED_TRACE(curve);
    const Curve c = parse_curve(curve);
    const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 3, o);
    std::vector<RealAlgebraic> T;
    for (const auto& b : r.T) T.push_back(b.t);
    const MoebiusResult exact = moebius_c0(c, SpeedKind::Angular, T, ref);
    for (long rd : {3L, 6L, 8L, 12L}) {
      SCOPED_TRACE(rd);
      const MoebiusResult q = make_rational(c, r, rd, o);
      for (std::size_t i = 0; i < q.pieces(); ++i)
        EXPECT_TRUE(within_relative(q.exact->alpha[i], exact.alpha[i], pow10_inv(rd)))
            << "piece " << i << ": " << q.exact->alpha[i].str() << " vs " << exact.alpha[i].str(45);
    }
  }
}

TEST(EvalRobust, IllConditionedMapIsSampledByRefiningItsData) {
  // r of kSteep computed to 15 digits cannot give r(s) to 15 digits at any
  // working precision: its data must be refined. The samples contain the
  // values of the same map computed to 60 digits and evaluated at 600 bits.
  const Curve c = parse_curve(kSteep);
  const Speed sp(c, SpeedKind::Angular);
  Options o;
  const RadicalResult r = radical(c, SpeedKind::Angular, o);
  Options ro;
  ro.digits = 60;
  const RadicalResult fine = radical(c, SpeedKind::Angular, ro);
  const long K = 11;
  Samples smp;
  ASSERT_NO_THROW(smp = sample(c, sp, Reparameterization(r), K, 15, o.max_prec));
  ASSERT_TRUE(meets_digits(smp, 15));
  const long prec = 600;
  for (long k = 0; k < K; ++k) {
    SCOPED_TRACE(k);
    const SamplePoint& p = smp.after[static_cast<std::size_t>(k)];
    const Ball z(Rational(k, K - 1), prec);
    const Ball t = eval_r(fine, z, prec);
    ASSERT_TRUE(t.meets_digits(25));  // at the joint z = 1/2, r is Hoelder-1/2: half the 60 digits
    EXPECT_TRUE(p.t.contains(t)) << p.t.str() << " vs " << t.str(45);
    const std::vector<Ball> pt = c.eval(t, prec);
    for (std::size_t j = 0; j < pt.size(); ++j) EXPECT_TRUE(p.point[j].contains(pt[j])) << j;
    if (!p.at_joint) {
      const Ball v = eval_speed(fine, sp, z, prec);
      ASSERT_TRUE(v.meets_digits(30));
      EXPECT_TRUE(p.speed.contains(v)) << p.speed.str() << " vs " << v.str(35);
    }
  }
  // the Sampler reports the refinement, and its map's joints are the finer ones
  Sampler ev(c, sp, Reparameterization(r), 15, o.max_prec);
  ev.at(Rational(1, 10));
  EXPECT_GE(ev.refinements(), 1);
  for (std::size_t i = 0; i < r.Z.size(); ++i) EXPECT_TRUE(r.Z[i].contains(ev.map().joints_s()[i]));
}

TEST(EvalRobust, RationalMapSamplesContainTheExactValues) {
  // A rational map (make_rational) has exact data: at a rational s, r(s),
  // p(r(s)) and the squared parametric speed |p'(r(s))|^2 r'(s)^2 are exact
  // rationals, computed here in exact arithmetic from T, S, alpha.
  Options o;
  for (const char* curve : {kCubic, kSlide, kEndsAtOrigin}) {
    SCOPED_TRACE(curve);
    const Curve c = parse_curve(curve);
    const Speed sp(c, SpeedKind::Parametric);
    const MoebiusResult q = make_rational(c, reparam_c0(c, SpeedKind::Parametric, 3, o), 6, o);
    const long K = 13;
    const Samples smp = sample(c, sp, Reparameterization(q), K, 15, o.max_prec);
    for (long k = 0; k < K; ++k) {
      SCOPED_TRACE(k);
      const Rational s(k, K - 1);
      const SamplePoint& p = smp.after[static_cast<std::size_t>(k)];
      std::size_t i = 0;
      while (i + 1 < q.pieces() && s > q.exact->S[i + 1]) ++i;
      const Rational ds = q.exact->S[i + 1] - q.exact->S[i], dt = q.exact->T[i + 1] - q.exact->T[i];
      const Rational u = (s - q.exact->S[i]) / ds, a = q.exact->alpha[i];
      const Rational den = a + (Rational(1) - Rational(2) * a) * u;
      const Rational t = q.exact->T[i] + dt * (Rational(1) - a) * u / den;
      const Rational dr = dt / ds * a * (Rational(1) - a) / (den * den);
      EXPECT_TRUE(p.t.contains(t)) << p.t.str() << " vs " << t.str();
      for (std::size_t j = 0; j < c.dimension(); ++j) EXPECT_TRUE(p.point[j].contains(c.components()[j](t))) << j;
      if (!p.at_joint) {
        Rational sq(0);
        for (const auto& X : c.derivative_numerators()) sq = sq + X(t) * X(t);
        const Rational w = c.derivative_denominator()(t);
        sq = sq / (w * w) * dr * dr;
        Ball v2;
        arb_mul(v2.get(), p.speed.get(), p.speed.get(), 512);
        EXPECT_TRUE(v2.contains(sq));
      }
    }
  }
}

TEST(EvalRobust, ExactEndsGiveExactValues) {
  // r(0) = 0 and r(1) = 1 exactly, and p there is evaluated exactly: for
  // p(1) = (0, 0) the samples print an exact 0, not a ball around 1e-27.
  Options o;
  const Curve c = parse_curve(kEndsAtOrigin);
  const Speed sp(c, SpeedKind::Angular);
  std::vector<Reparameterization> maps;
  maps.emplace_back(radical(c, SpeedKind::Angular, o));
  maps.emplace_back(reparam_c0(c, SpeedKind::Angular, 3, o));
  maps.emplace_back(reparam_c1(c, SpeedKind::Angular, Rational(9, 10), o));
  maps.emplace_back(make_rational(c, reparam_c0(c, SpeedKind::Angular, 3, o), 8, o));
  for (const auto& r : maps) {
    SCOPED_TRACE(r.method());
    const Samples smp = sample(c, sp, r, 3, 15, o.max_prec);
    for (std::size_t k : {std::size_t{0}, std::size_t{2}}) {
      const SamplePoint& p = smp.after[k];
      const Rational t(k == 0 ? 0 : 1);
      EXPECT_TRUE(p.t.is_exact() && p.t.contains(t)) << p.t.str();
      for (std::size_t j = 0; j < c.dimension(); ++j) {
        const Rational v = c.components()[j](t);
        EXPECT_TRUE(p.point[j].is_exact() && p.point[j].contains(v)) << j << ": " << p.point[j].str();
      }
    }
    // the library evaluation itself, at any precision
    for (long prec : {64L, 300L}) {
      EXPECT_TRUE(r.eval_r(Ball(1), prec).is_exact());
      EXPECT_TRUE(r.eval_r(Ball(0), prec).certainly_zero());
    }
  }
}

TEST(EvalRobust, SampleEachHandsOverEachSampleAtOnce) {
  // The samples reach the sink one at a time, in order, and a sink that stops
  // (throws) ends the loop there: with K = 1000000 nothing is computed, or
  // kept, beyond the samples already handed over.
  Options o;
  const Curve c = parse_curve(kCubic);
  const Speed sp(c, SpeedKind::Angular);
  const Reparameterization r(radical(c, SpeedKind::Angular, o));
  std::vector<Rational> seen;
  sample_each(c, sp, r, 5, 15, o.max_prec, [&](long k, const SamplePoint& p) {
    EXPECT_EQ(k, static_cast<long>(seen.size()));
    EXPECT_EQ(p.s, Rational(k, 4));
    seen.push_back(p.s);
  });
  EXPECT_EQ(seen.size(), 5u);
  struct Stop {};
  long calls = 0;
  EXPECT_THROW(sample_each(c, sp, r, 1000000, 15, o.max_prec,
                           [&](long k, const SamplePoint&) {
                             ++calls;
                             if (k == 2) throw Stop{};
                           }),
               Stop);
  EXPECT_EQ(calls, 3);
  EXPECT_THROW(sample_each(c, sp, r, 1, 15, o.max_prec, [](long, const SamplePoint&) {}), InvalidArgument);
}

TEST(EvalRobust, RefinedMapIsTheSameMapKnownBetter) {
  // refined() recomputes the data of the map the method defines for its
  // breakpoints: every refined joint, alpha and value of r lies in the
  // original balls, and meets the new digits.
  Options o;
  const Curve c = parse_curve(kSlide);
  const Speed sp(c, SpeedKind::Angular);
  std::vector<Reparameterization> maps;
  maps.emplace_back(radical(c, SpeedKind::Angular, o));
  maps.emplace_back(reparam_c0(c, SpeedKind::Angular, 3, o));
  maps.emplace_back(reparam_c1(c, SpeedKind::Angular, Rational(99, 100), o));
  maps.emplace_back(make_rational(c, reparam_c0(c, SpeedKind::Angular, 2, o), 6, o));
  for (const auto& r : maps) {
    SCOPED_TRACE(r.method());
    const Reparameterization f = r.refined(sp, 40, o.max_prec);
    ASSERT_EQ(f.pieces(), r.pieces());
    for (std::size_t i = 0; i < r.joints_s().size(); ++i) {
      EXPECT_TRUE(f.joints_s()[i].meets_digits(40)) << i;
      EXPECT_TRUE(r.joints_s()[i].contains(f.joints_s()[i])) << i;
    }
    const std::vector<Ball>* a0 = nullptr;
    const std::vector<Ball>* a1 = nullptr;
    std::vector<Ball> ra, fa;
    if (const auto* x = r.radical_result()) {
      for (const auto& p : x->integrals) ra.push_back(p.alpha);
      for (const auto& p : f.radical_result()->integrals) fa.push_back(p.alpha);
      a0 = &ra;
      a1 = &fa;
    } else {
      a0 = &r.moebius_result()->alpha;
      a1 = &f.moebius_result()->alpha;
    }
    for (std::size_t i = 0; i < a0->size(); ++i) {
      EXPECT_TRUE((*a1)[i].meets_digits(40)) << i;
      EXPECT_TRUE((*a0)[i].contains((*a1)[i])) << i;
    }
    for (long k = 0; k <= 8; ++k) {
      const Ball s(Rational(k, 8), 256);
      EXPECT_TRUE(r.eval_r(s, 256).contains(f.eval_r(s, 256))) << k;
    }
  }
}

TEST(EvalRobust, RationalJointsAreWithinTheRelativeAccuracyOfTheTrueJoints) {
  // With more --rational-digits than the map was computed to, the joints S
  // must be refined first: each rounded s_j is certainly within 10^-d times
  // the smaller neighbouring gap of the optimal s_j (computed to 60 digits).
  Options o;
  Options ref;
  ref.digits = 60;
  const Curve c = parse_curve(kCubic);
  const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 4, o);
  std::vector<RealAlgebraic> T;
  for (const auto& b : r.T) T.push_back(b.t);
  const MoebiusResult exact = moebius_c0(c, SpeedKind::Angular, T, ref);
  for (long rd : {8L, 30L}) {
    SCOPED_TRACE(rd);
    const MoebiusResult q = make_rational(c, r, rd, o);
    const Ball tol(pow10_inv(rd), 512);
    for (std::size_t j = 1; j < q.pieces(); ++j) {
      Ball d, left, right, gap;
      const Ball sq(q.exact->S[j], 512);
      arb_sub(d.get(), sq.get(), exact.S[j].get(), 512);
      arb_abs(d.get(), d.get());
      arb_sub(left.get(), exact.S[j].get(), exact.S[j - 1].get(), 512);
      arb_sub(right.get(), exact.S[j + 1].get(), exact.S[j].get(), 512);
      arb_min(gap.get(), left.get(), right.get(), 512);
      arb_mul(gap.get(), gap.get(), tol.get(), 512);
      EXPECT_TRUE(arb_le(d.get(), gap.get())) << "s_" << j << " = " << q.exact->S[j].str() << " vs "
                                              << exact.S[j].str(65);
    }
  }
}
