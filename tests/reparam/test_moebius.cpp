// C0 piecewise Moebius reparameterization with fixed breakpoints (ImUp's
// MoebiusTransformation and ReparameterizationN): docs/math.md section 6 values
// inside the certified balls, monotonicity of u, and input validation.
#include <gtest/gtest.h>

#include <vector>

#include "support/reference.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

const char* kParabola = "(t, t^2)";
const char* kCircle = "((1 - t^2)/(1 + t^2), 2t/(1 + t^2))";
const char* kCubic = "(t, t^3)";

std::vector<RealAlgebraic> halves() { return {RealAlgebraic(0), RealAlgebraic(Rational(1, 2)), RealAlgebraic(1)}; }

// sqrt(n) at prec bits.
Ball sqrt_ui(unsigned long n, long prec) {
  Ball x;
  arb_sqrt_ui(x.get(), n, prec);
  return x;
}

void expect_well_formed(const MoebiusResult& r, std::size_t pieces, long digits) {
  ASSERT_EQ(r.T.size(), pieces + 1);
  ASSERT_EQ(r.integrals.size(), pieces);
  ASSERT_EQ(r.S.size(), pieces + 1);
  EXPECT_TRUE(r.S.front().certainly_zero());
  EXPECT_TRUE(r.S.back().contains(Rational(1)) && r.S.back().is_exact());
  for (std::size_t i = 0; i + 1 < r.S.size(); ++i) EXPECT_TRUE(arb_lt(r.S[i].get(), r.S[i + 1].get()));
  for (const auto& b : r.T) EXPECT_EQ(b.multiplicity, 0);
  EXPECT_TRUE(r.mu.meets_digits(digits));
  EXPECT_TRUE(r.u_before.meets_digits(digits));
  EXPECT_TRUE(r.u_after.meets_digits(digits));
  for (const auto& s : r.S) EXPECT_TRUE(s.meets_digits(digits));
  for (const auto& pi : r.integrals) {
    for (const Ball* b : {&pi.A, &pi.B, &pi.C, &pi.L, &pi.M, &pi.alpha}) EXPECT_TRUE(b->meets_digits(digits));
    EXPECT_TRUE(pi.alpha.certainly_positive());
    EXPECT_TRUE(arb_lt(pi.alpha.get(), Ball(1).get()));
  }
}

}  // namespace

TEST(Moebius, SingleOptimalParabola) {
  Options o;
  o.digits = 25;
  const MoebiusResult r = moebius_optimal(parse_curve(kParabola), SpeedKind::Angular, o);
  expect_well_formed(r, 1, o.digits);
  EXPECT_FALSE(r.identically_zero);
  EXPECT_FALSE(r.speed_vanishes);
  // alpha* = sqrt5 / (1 + sqrt5)
  Ball a = sqrt_ui(5, 256), den;
  arb_add_ui(den.get(), a.get(), 1, 256);
  arb_div(a.get(), a.get(), den.get(), 256);
  EXPECT_TRUE(arb_overlaps(r.integrals[0].alpha.get(), a.get())) << r.integrals[0].alpha.str(30);
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].alpha, "0.6909830056250525758977066"));
  EXPECT_TRUE(test_support::contains_ref(r.mu, "1.107148717794090503017065"));
  EXPECT_TRUE(test_support::contains_ref(r.u_before, "0.8133094424199794137403804"));
  EXPECT_TRUE(test_support::contains_ref(r.u_after, "0.9908946827138343953409911")) << r.u_after.str(30);
}

TEST(Moebius, SingleOptimalQuarterCircle) {
  Options o;
  o.digits = 25;
  const MoebiusResult r = moebius_optimal(parse_curve(kCircle), SpeedKind::Angular, o);
  expect_well_formed(r, 1, o.digits);
  // alpha* = 2 - sqrt 2
  Ball a = sqrt_ui(2, 256);
  arb_neg(a.get(), a.get());
  arb_add_ui(a.get(), a.get(), 2, 256);
  EXPECT_TRUE(arb_overlaps(r.integrals[0].alpha.get(), a.get())) << r.integrals[0].alpha.str(30);
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].alpha, "0.5857864376269049511983113"));
  Ball half_pi;
  arb_const_pi(half_pi.get(), 256);
  arb_mul_2exp_si(half_pi.get(), half_pi.get(), -1);
  EXPECT_TRUE(arb_overlaps(r.mu.get(), half_pi.get()));
  EXPECT_TRUE(test_support::contains_ref(r.u_before, "0.9597808564432393298507263"));
  EXPECT_TRUE(test_support::contains_ref(r.u_after, "0.9977912002415711604419615")) << r.u_after.str(30);
}

TEST(Moebius, SingleOptimalCubicRunsDespiteTheZeroOfTheSpeed) {
  Options o;
  o.digits = 25;
  const MoebiusResult r = moebius_optimal(parse_curve(kCubic), SpeedKind::Angular, o);
  expect_well_formed(r, 1, o.digits);
  EXPECT_TRUE(r.speed_vanishes);  // angular speed 6t/(9t^4+1) vanishes at 0
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].alpha, "0.5105988478747678635097211"));
  EXPECT_TRUE(test_support::contains_ref(r.mu, "1.249045772398254425829917"));
  EXPECT_TRUE(test_support::contains_ref(r.u_before, "0.8456952431533663418830113"));
  EXPECT_TRUE(test_support::contains_ref(r.u_after, "0.8461305492113560212003557")) << r.u_after.str(30);
}

TEST(Moebius, C0AtHalvesMatchesReferenceValues) {
  Options o;
  o.digits = 20;
  struct Case {
    const char* curve;
    const char* u;
  } cases[] = {{kParabola, "0.99841495791246707038"},
               {kCircle, "0.99982152048030391816"},
               {kCubic, "0.96292290406696645388"}};
  for (const auto& k : cases) {
    SCOPED_TRACE(k.curve);
    const MoebiusResult r = moebius_c0(parse_curve(k.curve), SpeedKind::Angular, halves(), o);
    expect_well_formed(r, 2, o.digits);
    EXPECT_EQ(r.T[1].t.rational(), Rational(1, 2));
    EXPECT_TRUE(test_support::contains_ref(r.u_after, k.u)) << r.u_after.str(30);
  }
}

TEST(Moebius, NeverWorseThanTheCurveNorThanCoarserBreakpoints) {
  // u(p o r) >= u(p) (alpha = 1/2, s = t is the identity), and refining T
  // cannot lose (a Moebius map restricted to a sub-interval is again one).
  const char* curves[] = {kParabola, kCircle, kCubic, "(t, t^4/6 - t^2/2)", "(t, t^2, t^3)",
                          "(t^2 + t, t^3 - 2t)", "(1/(1 + t), t^2/(1 + t^2))"};
  for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
    for (const char* cv : curves) {
      SCOPED_TRACE(cv);
      const Curve c = parse_curve(cv);
      const MoebiusResult one = moebius_optimal(c, kind);
      const MoebiusResult two = moebius_c0(c, kind, halves());
      const MoebiusResult three = moebius_c0(
          c, kind, {RealAlgebraic(0), RealAlgebraic(Rational(1, 4)), RealAlgebraic(Rational(1, 2)), RealAlgebraic(1)});
      expect_well_formed(three, 3, Options{}.digits);
      EXPECT_FALSE(arb_lt(one.u_after.get(), one.u_before.get()));
      EXPECT_FALSE(arb_lt(two.u_after.get(), one.u_after.get()));
      EXPECT_FALSE(arb_lt(three.u_after.get(), two.u_after.get()));
      EXPECT_FALSE(arb_gt(three.u_after.get(), Ball(1).get()));
    }
  }
}

TEST(Moebius, IrrationalBreakpoint) {
  // t_1 = 1/sqrt 2, a root of 2 t^2 - 1 in [0, 1].
  const RealAlgebraic t1(Poly(std::vector<long>{-1, 0, 2}), Rational(1, 2), Rational(1));
  const MoebiusResult r = moebius_c0(parse_curve(kParabola), SpeedKind::Angular, {RealAlgebraic(0), t1, RealAlgebraic(1)});
  expect_well_formed(r, 2, Options{}.digits);
  const MoebiusResult one = moebius_optimal(parse_curve(kParabola), SpeedKind::Angular);
  EXPECT_FALSE(arb_lt(r.u_after.get(), one.u_after.get()));
}

TEST(Moebius, StraightLineIsLeftAlone) {
  const MoebiusResult r = moebius_c0(parse_curve("(1 + 2t, 3 - t/2)"), SpeedKind::Angular, halves());
  EXPECT_TRUE(r.identically_zero);
  ASSERT_EQ(r.integrals.size(), 2u);
  ASSERT_EQ(r.S.size(), 3u);
  EXPECT_TRUE(r.u_after.contains(Rational(1)));
  EXPECT_TRUE(r.u_before.contains(Rational(1)));
  EXPECT_TRUE(r.S[1].contains(Rational(1, 2)));
  for (const auto& pi : r.integrals) EXPECT_TRUE(pi.alpha.contains(Rational(1, 2)));
  // The parametric speed of a line is constant: already uniform, alpha = 1/2.
  const MoebiusResult p = moebius_optimal(parse_curve("(1 + 2t, 3 - t/2)"), SpeedKind::Parametric);
  EXPECT_FALSE(p.identically_zero);
  EXPECT_TRUE(p.u_after.contains(Rational(1)));
  EXPECT_TRUE(p.integrals[0].alpha.contains(Rational(1, 2)));
}

TEST(Moebius, RejectsBadBreakpoints) {
  const Curve c = parse_curve(kParabola);
  const RealAlgebraic z(0), h(Rational(1, 2)), q(Rational(1, 4)), o(1);
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {h, o}), InvalidArgument);           // does not start at 0
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {z, h}), InvalidArgument);           // does not end at 1
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {z, h, q, o}), InvalidArgument);     // not increasing
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {z, h, h, o}), InvalidArgument);     // repeated
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {z}), InvalidArgument);              // too short
  EXPECT_THROW(moebius_c0(c, SpeedKind::Angular, {}), InvalidArgument);
  Options bad;
  bad.digits = 0;
  EXPECT_THROW(moebius_optimal(c, SpeedKind::Angular, bad), InvalidArgument);
}

TEST(Moebius, BudgetExceededWhenThePrecisionCapIsTooLow) {
  Options o;
  o.digits = 200;
  o.max_prec = 128;
  EXPECT_THROW(moebius_optimal(parse_curve(kParabola), SpeedKind::Angular, o), BudgetExceeded);
}
