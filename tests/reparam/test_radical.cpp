// Piecewise radical reparameterization (Hong, Wang, Yang 2023): the running example
// against docs/math.md section 6, and a family of curves each checked against an
// independent direct integration of the reparameterized speed.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "uniparam/reparam/radical.hpp"
#include "support/curves.hpp"
#include "support/reference.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {


}  // namespace

TEST(Radical, RunningExampleMatchesReferenceValuesAt30Digits) {
  Options o;
  o.digits = 30;
  const RadicalResult r = radical(parse_curve("(t, t^3)"), SpeedKind::Angular, o);
  ASSERT_EQ(r.T.size(), 3u);
  EXPECT_EQ(r.T[0].t.rational(), Rational(0));
  EXPECT_EQ(r.T[0].multiplicity, 1);
  EXPECT_EQ(r.T[1].multiplicity, 0);
  EXPECT_EQ(r.T[2].multiplicity, 0);
  // t_1 = 27^(-1/4) exactly: a root of 27 t^4 - 1.
  EXPECT_EQ(sign_at(Poly(std::vector<long>{-1, 0, 0, 0, 27}), r.T[1].t), 0);
  const long d = 30;
  EXPECT_TRUE(test_support::contains_ref(r.mu, "1.249045772398254425829917077281"));
  EXPECT_TRUE(test_support::contains_ref(r.u_before, "0.845695243153366341883011346954"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].L, "0.276149947019518154216173188137"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[1].L, "0.590279575143189635488639654483"));
  EXPECT_TRUE(test_support::contains_ref(r.S[1], "0.406168831108629768655940029023"));
  EXPECT_TRUE(test_support::contains_ref(r.u_radical, "0.932019351227728622029065116125"));
  EXPECT_TRUE(test_support::contains_ref(r.A[0], "0.257527855578109157004177949541"));
  EXPECT_TRUE(test_support::contains_ref(r.B[0], "0.229215810648925481482561967406"));
  EXPECT_TRUE(test_support::contains_ref(r.C[0], "0.193145891683581867753133462156"));
  EXPECT_TRUE(test_support::contains_ref(r.A[1], "0.517982180256045372477228084291"));
  EXPECT_TRUE(test_support::contains_ref(r.B[1], "0.316652946386679794846275379578"));
  EXPECT_TRUE(test_support::contains_ref(r.C[1], "0.159384059391562820188836381580"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].M, "0.274272465295050174093452161519"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[1].M, "0.529288527718361753759590666857"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[0].alpha, "0.535898384862245412945107316988"));
  EXPECT_TRUE(test_support::contains_ref(r.integrals[1].alpha, "0.643207280514345359287585612170"));
  EXPECT_TRUE(test_support::contains_ref(r.Z[1], "0.418555543917801150534662317152"));
  EXPECT_TRUE(test_support::contains_ref(r.u_after, "0.996507782374800406168303796755"));
  for (const Ball* b : {&r.mu, &r.u_radical, &r.u_after, &r.S[1], &r.Z[1]}) EXPECT_TRUE(b->meets_digits(d));
}

TEST(Radical, RunningExampleReproducesThePapersPrintedDigits) {
  // Examples 2-16 print 3 decimals: each must be the rounding of our ball.
  const RadicalResult r = radical(parse_curve("(t, t^3)"), SpeedKind::Angular);
  auto rounds_to = [](const Ball& b, const char* three_decimals) {
    Rational v = Rational::parse(three_decimals), h = Rational(1, 2000);
    Ball lo(v - h, 128), hi(v + h, 128);
    return arb_gt(b.get(), lo.get()) && arb_lt(b.get(), hi.get());
  };
  EXPECT_TRUE(rounds_to(r.mu, "1.249"));
  EXPECT_TRUE(rounds_to(r.u_before, "0.846"));
  EXPECT_TRUE(rounds_to(r.T[1].t.to_ball(64), "0.439"));
  EXPECT_TRUE(rounds_to(r.integrals[0].L, "0.276"));
  EXPECT_TRUE(rounds_to(r.integrals[1].L, "0.590"));
  EXPECT_TRUE(rounds_to(r.S[1], "0.406"));
  EXPECT_TRUE(rounds_to(r.u_radical, "0.932"));
  EXPECT_TRUE(rounds_to(r.A[0], "0.258"));
  EXPECT_TRUE(rounds_to(r.B[0], "0.229"));
  EXPECT_TRUE(rounds_to(r.C[0], "0.193"));
  EXPECT_TRUE(rounds_to(r.A[1], "0.518"));
  EXPECT_TRUE(rounds_to(r.B[1], "0.317"));
  EXPECT_TRUE(rounds_to(r.C[1], "0.159"));
  EXPECT_TRUE(rounds_to(r.integrals[0].M, "0.274"));
  EXPECT_TRUE(rounds_to(r.integrals[1].M, "0.529"));
  EXPECT_TRUE(rounds_to(r.integrals[0].alpha, "0.536"));
  EXPECT_TRUE(rounds_to(r.integrals[1].alpha, "0.643"));
  EXPECT_TRUE(rounds_to(r.Z[1], "0.419"));
  EXPECT_TRUE(rounds_to(r.u_after, "0.997"));
  // Example 16: phi = 0.688 sqrt(s) on the first piece: phi(s) at s = S_1 is t_1,
  // and r(z) = phi(m(z)) maps the joints to the breakpoints.
  const Speed s(parse_curve("(t, t^3)"), SpeedKind::Angular);
  Ball at = eval_r(r, r.Z[1], 128);
  EXPECT_TRUE(arb_overlaps(at.get(), r.T[1].t.to_ball(128).get()));
  EXPECT_TRUE(eval_r(r, Ball(0), 128).contains(Rational(0)));
  EXPECT_TRUE(eval_r(r, Ball(1), 128).contains(Rational(1)));
}

struct Case {
  const char* curve;
  SpeedKind kind;
  std::vector<int> multiplicities;  // of the zeros of sigma in [0, 1], in order
  const char* what;
};

class RadicalFamily : public ::testing::TestWithParam<Case> {};

TEST_P(RadicalFamily, FormulasAgreeWithDirectIntegrationOfTheReparameterizedSpeed) {
  const Case& c = GetParam();
  const Curve curve = parse_curve(c.curve);
  const Speed s(curve, c.kind);
  const RadicalResult r = radical(curve, c.kind);
  std::vector<int> mults;
  for (const auto& b : r.T)
    if (b.multiplicity > 0) mults.push_back(b.multiplicity);
  EXPECT_EQ(mults, c.multiplicities) << c.what;
  for (std::size_t i = 0; i + 1 < r.T.size(); ++i) {
    EXPECT_TRUE(r.T[i].t < r.T[i + 1].t);
    EXPECT_FALSE(r.T[i].multiplicity > 0 && r.T[i + 1].multiplicity > 0) << "two zeros in a row";
    EXPECT_TRUE(arb_lt(r.S[i].get(), r.S[i + 1].get()));
    EXPECT_TRUE(arb_lt(r.Z[i].get(), r.Z[i + 1].get()));
    EXPECT_TRUE(arb_gt(r.integrals[i].alpha.get(), Ball(0).get()));
    EXPECT_TRUE(arb_lt(r.integrals[i].alpha.get(), Ball(1).get()));
  }
  // 0 < u <= 1, and the Moebius layer never loses: M_k <= L_k.
  for (const Ball* u : {&r.u_before, &r.u_radical, &r.u_after}) {
    EXPECT_TRUE(arb_is_positive(u->get()));
    EXPECT_FALSE(arb_gt(u->get(), Ball(1).get())) << c.what << " u = " << u->str(20);
  }
  EXPECT_FALSE(arb_lt(r.u_after.get(), r.u_radical.get())) << c.what;
  EXPECT_TRUE(r.u_after.meets_digits(15));
  // u_before takes int sigma^2 from the pieces (L_i / Delta t_i where no
  // zero ends the piece, its own integral where one does): against the
  // uniformity's direct integral of sigma^2 over [0, 1].
  const UniformityResult u = uniformity(s);
  EXPECT_TRUE(arb_overlaps(r.u_before.get(), u.u.get())) << c.what << ": " << r.u_before.str(20) << " vs " << u.u.str(20);
  EXPECT_TRUE(arb_overlaps(r.mu.get(), u.mu.get())) << c.what;
  EXPECT_TRUE(r.u_before.meets_digits(16)) << r.u_before.str(25);
  // The independent check of the whole chain.
  Ball direct = radical_direct_uniformity(r, s, 12, 4096);
  EXPECT_TRUE(arb_overlaps(direct.get(), r.u_after.get()))
      << c.what << ": formulas " << r.u_after.str(20) << " direct " << direct.str(20);
  EXPECT_TRUE(direct.meets_digits(10)) << direct.str(20);
  // The reparameterized speed has no zero: sampled, it is certainly positive.
  for (int k = 0; k <= 16; ++k) {
    Ball z(Rational(k, 16), 128);
    Ball v = eval_speed(r, s, z, 128);
    EXPECT_TRUE(arb_is_positive(v.get())) << c.what << " at z = " << k << "/16: " << v.str(10);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Curves, RadicalFamily,
    ::testing::Values(
        Case{"(t, t^3)", SpeedKind::Angular, {1}, "running example"},
        Case{"(t, t^4)", SpeedKind::Angular, {2}, "zero of multiplicity 2"},
        Case{"(t, t^4/6 - t^2/2)", SpeedKind::Angular, {1}, "irrational interior zero 1/sqrt(2)"},
        Case{"(t, 4t^4/3 - 8t^3/3 + 3t^2/2)", SpeedKind::Angular, {1, 1}, "two interior zeros, one factor"},
        Case{"(t, (t-1)^3)", SpeedKind::Angular, {1}, "zero at t = 1"},
        Case{"((t-1/3)^3/(1+t^2), t/(2+t))", SpeedKind::Angular, {1}, "rational curve"},
        Case{"(t, t^3, t^4)", SpeedKind::Angular, {1}, "space curve"},
        Case{"(t, (t^2-1/2)^3)", SpeedKind::Angular, {1, 1}, "zeros at 0 (t y'' = 0) and 1/sqrt 2"},
        Case{"(t^2, t^3)", SpeedKind::Parametric, {1}, "cusp under parametric speed"},
        Case{"(t, t^2)", SpeedKind::Angular, {}, "no zero: C0 piecewise Moebius"}),
    [](const ::testing::TestParamInfo<Case>& info) { return "case" + std::to_string(info.index); });

TEST(Radical, MultiplicityTwoLiftedByCubeRoot) {
  const RadicalResult r = radical(parse_curve("(t, t^4)"), SpeedKind::Angular);
  EXPECT_EQ(r.root_index(0), 3);
  EXPECT_EQ(r.side(0), ZeroSide::Left);
  EXPECT_EQ(r.side(1), ZeroSide::None);
}

TEST(Radical, StraightLineIsLeftAlone) {
  const RadicalResult r = radical(parse_curve("(t, 2t + 1)"), SpeedKind::Angular);
  EXPECT_TRUE(r.identically_zero);
  EXPECT_TRUE(r.u_after.contains(Rational(1)));
  EXPECT_EQ(r.pieces(), 1u);
}

TEST(Radical, PointsOfTheReparameterizedCurveAreCertified) {
  const Curve c = parse_curve("(t, t^3)");
  const RadicalResult r = radical(c, SpeedKind::Angular);
  // r maps the joints z_i to the breakpoints t_i, so p(r(z_i)) = p(t_i).
  for (std::size_t i = 0; i < r.T.size(); ++i) {
    auto pt = eval_point(c, r, r.Z[i], 128);
    ASSERT_EQ(pt.size(), 2u);
    Ball t = r.T[i].t.to_ball(128), t3;
    arb_pow_ui(t3.get(), t.get(), 3, 128);
    EXPECT_TRUE(arb_overlaps(pt[0].get(), t.get()));
    EXPECT_TRUE(arb_overlaps(pt[1].get(), t3.get()));
  }
  // r is increasing: certified at sample points.
  Ball prev = eval_r(r, Ball(0), 128);
  for (int k = 1; k <= 32; ++k) {
    Ball cur = eval_r(r, Ball(Rational(k, 32), 128), 128);
    EXPECT_TRUE(arb_lt(prev.get(), cur.get())) << k;
    prev = cur;
  }
}

namespace {

// The critical points of sigma in [0, 1] the slow way: the real roots of the
// numerator of (sigma^2)' from its expanded power basis (exact isolation),
// minus the zeros of sigma (roots of g).
std::vector<RealAlgebraic> critical_points_exactly(const Speed& s) {
  const RatFunc d = s.squared().derivative();
  std::vector<RealAlgebraic> out;
  if (d.num().is_zero()) return out;
  for (const auto& r : isolate_real_roots(d.num(), Rational(0), Rational(1))) {
    RealAlgebraic t(r);
    if (sign_at(s.g(), t) != 0) out.push_back(t);
  }
  return out;
}

void expect_same_points(const std::vector<RealAlgebraic>& got, const std::vector<RealAlgebraic>& want,
                        const std::string& what) {
  ASSERT_EQ(got.size(), want.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_TRUE(got[i] == want[i]) << what << ": point " << i << " " << got[i].str() << " vs " << want[i].str();
    if (i > 0) EXPECT_TRUE(got[i - 1] < got[i]) << what;
  }
}

}  // namespace

TEST(CriticalPoints, ARootAtOneHalfIsFoundOnceThoughBothHalvesEndThere) {
  // critical_points isolates [0, 1/2] and [1/2, 1] side by side: curves
  // symmetric about t = 1/2 have an exact critical point there.
  for (const char* curve : {"(t, (t - 1/2)^2)", "(t, (2t - 1)^2, (2t - 1)^4)", "(t, 3(t - 1/2)^2 + (t - 1/2)^4)"}) {
    const Speed s(parse_curve(curve), SpeedKind::Angular);
    const std::vector<RealAlgebraic> got = critical_points(s);
    long at_half = 0;
    for (const auto& t : got) at_half += t == RealAlgebraic(Rational(1, 2)) ? 1 : 0;
    EXPECT_EQ(at_half, 1) << curve;
    expect_same_points(got, critical_points_exactly(s), curve);
  }
}

TEST(CriticalPoints, MatchTheRootsOfTheExpandedDerivativeOnRandomCurves) {
  // Low degrees (the exact isolation on each half) and degree 80 (P of
  // degree ~300: the evaluator's subdivision on each half).
  std::mt19937_64 rng(99);
  for (long it = 0; it < test_support::iterations(6); ++it) {
    const long deg = it == 0 ? 80 : 3 + it % 4;
    const Curve c({RatFunc(test_support::random_poly(rng, deg, 5)), RatFunc(test_support::random_poly(rng, deg, 5))});
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(c, kind);
      if (s.identically_zero()) continue;
      expect_same_points(critical_points(s), critical_points_exactly(s), c.str());
    }
  }
}
