// ImUp's ReparameterizationU (C1 piecewise Moebius to a target uniformity)
// and the exact rational output of both piecewise Moebius methods.
// The independent oracle: the pieces of p o r, built exactly by composition
// and integrated as curves of their own (no A, B, C machinery involved).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

const char* kSlide =
    "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";

// r_i on [s_i, s_{i+1}] composed with s = s_i + ds x, as a rational function of x in [0, 1].
RatFunc piece_map(const MoebiusResult& r, std::size_t i) {
  const Rational &ti = r.exact->T[i], &tj = r.exact->T[i + 1], &a = r.exact->alpha[i];
  const RatFunc x = RatFunc::t();
  // (2.1): t~ = (1-a) x / ((1-a) x + a (1-x))
  const RatFunc tt = RatFunc(Rational(1) - a) * x / (RatFunc(Rational(1) - a) * x + RatFunc(a) * (RatFunc(1) - x));
  return RatFunc(ti) + RatFunc(tj - ti) * tt;
}

// u of the exact rational map r, integrated piece by piece as separate curves:
// int_{s_i}^{s_{i+1}} sigma_{p o r}^2 ds = (1 / ds_i) int_0^1 sigma_{q_i}^2 dx.
Ball independent_u(const Curve& c, const MoebiusResult& r, SpeedKind kind, long digits) {
  Options o;
  o.digits = digits;
  const long prec = 4 * digits + 64;
  Ball total(0);
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    std::vector<RatFunc> comps;
    for (const auto& x : c.components()) comps.push_back(compose(x, piece_map(r, i)));
    const UniformityResult q = uniformity(Curve(comps), kind, o);
    const Ball ids(Rational(1) / (r.exact->S[i + 1] - r.exact->S[i]), prec);
    arb_addmul(total.get(), q.mean_square.get(), ids.get(), prec);
  }
  Ball u;
  arb_mul(u.get(), r.mu.get(), r.mu.get(), prec);
  arb_div(u.get(), u.get(), total.get(), prec);
  return u;
}

// r' at s_{i+1} from the left and from the right, exactly.
Rational left_derivative(const MoebiusResult& r, std::size_t i) {
  const Rational rho = (r.exact->T[i + 1] - r.exact->T[i]) / (r.exact->S[i + 1] - r.exact->S[i]);
  return rho * r.exact->alpha[i] / (Rational(1) - r.exact->alpha[i]);
}
Rational right_derivative(const MoebiusResult& r, std::size_t i) {
  const Rational rho = (r.exact->T[i + 1] - r.exact->T[i]) / (r.exact->S[i + 1] - r.exact->S[i]);
  return rho * (Rational(1) - r.exact->alpha[i]) / r.exact->alpha[i];
}

void expect_exactly_c1(const MoebiusResult& r) {
  ASSERT_TRUE(r.exact.has_value());
  ASSERT_EQ(r.exact->T.size(), r.pieces() + 1);
  EXPECT_EQ(r.exact->T.front(), Rational(0));
  EXPECT_EQ(r.exact->T.back(), Rational(1));
  EXPECT_EQ(r.exact->S.front(), Rational(0));
  EXPECT_EQ(r.exact->S.back(), Rational(1));
  for (std::size_t i = 0; i + 1 < r.pieces(); ++i)
    EXPECT_EQ(left_derivative(r, i), right_derivative(r, i + 1)) << "joint " << i + 1;
}

}  // namespace

TEST(ReparamC1, SlideCurveReachesTheTargetWithAnExactlyC1RationalMap) {
  const Curve c = parse_curve(kSlide);
  const MoebiusResult r = reparam_c1(c, SpeedKind::Angular, Rational(99, 100), {});
  EXPECT_EQ(r.continuity, Continuity::C1);
  EXPECT_TRUE(r.target.has_value() && r.target->reached);
  EXPECT_TRUE(arb_ge(r.u_after.get(), Ball(Rational(99, 100), 64).get()));
  EXPECT_GT(r.pieces(), 1u);
  // the first T are the zeros of sigma' (certified: sigma'(t_i) = 0 means N1(t_i) = 0)
  const MoebiusResult q = make_rational(c, r, 8, {});
  expect_exactly_c1(q);
  EXPECT_TRUE(q.target->reached);
  const Ball u = independent_u(c, q, SpeedKind::Angular, 15);
  EXPECT_TRUE(arb_overlaps(u.get(), q.u_after.get())) << u.str(20) << " vs " << q.u_after.str(20);
}

TEST(ReparamC1, TargetReachedOnCurvesWithoutZerosOfTheSpeed) {
  std::vector<std::pair<const char*, SpeedKind>> cases = {
      {"(t, t^2)", SpeedKind::Angular},
      {"((1 - t^2)/(1 + t^2), 2t/(1 + t^2))", SpeedKind::Angular},
      {"(t, t^2, t^3)", SpeedKind::Angular},
      {"(t^2 + t, t^3 - t, t)", SpeedKind::Parametric},
      {"(t, t^3 + 1/2 t)", SpeedKind::Parametric},
  };
  for (const auto& [curve, kind] : cases) {
    const Curve c = parse_curve(curve);
    ASSERT_TRUE(Speed(c, kind).zeros().empty()) << curve;
    const MoebiusResult r = reparam_c1(c, kind, Rational(99, 100), {});
    EXPECT_TRUE(r.target->reached) << curve << " u = " << r.u_after.str(10);
    const MoebiusResult q = make_rational(c, r, 8, {});
    expect_exactly_c1(q);
    EXPECT_TRUE(q.target->reached) << curve;
  }
}

TEST(ReparamC1, StartsFromTheZerosOfTheSpeedDerivative) {
  // (t, t^3): omega = 6t/(9t^4+1), omega' = 0 at t = 27^(-1/4) (docs/math.md section 6)
  const MoebiusResult r = reparam_c1(parse_curve("(t, t^3)"), SpeedKind::Angular, Rational(1, 2), {});
  ASSERT_EQ(r.pieces(), 2u);  // u >= 1/2 already after the first construction
  EXPECT_EQ(r.T[1].t.poly(), Poly(std::vector<long>{-1, 0, 0, 0, 27}));
  EXPECT_EQ(r.target->rounds, 0);
}

TEST(ReparamC1, ReportsAnUnreachedTargetWithTheBestMap) {
  const Curve c = parse_curve(kSlide);
  const MoebiusResult r = reparam_c1(c, SpeedKind::Angular, Rational(999999, 1000000), {}, 3);
  EXPECT_FALSE(r.target->reached);
  EXPECT_LE(r.pieces(), 3u);
  EXPECT_TRUE(arb_gt(r.u_after.get(), r.u_before.get()));
}

// u_before comes from the pieces (sum L_i / Delta t_i for int sigma^2) and
// mu from mean_speed alone: both against the uniformity's own integrals on
// random curves (plane, space; angular and parametric).
TEST(ReparamC1, UBeforeAndMuFromThePiecesMatchTheUniformity) {
  std::mt19937_64 rng(777);
  for (long it = 0; it < test_support::iterations(6); ++it) {
    std::vector<RatFunc> comps{RatFunc(test_support::random_poly(rng, 3, 9)), RatFunc(test_support::random_poly(rng, 4, 9))};
    if (it % 3 == 2) comps.emplace_back(test_support::random_poly(rng, 3, 9));
    const Curve c(comps);
    const SpeedKind kind = it % 2 ? SpeedKind::Parametric : SpeedKind::Angular;
    if (Speed(c, kind).identically_zero()) continue;
    const MoebiusResult r = reparam_c1(c, kind, Rational(9, 10), {}, 6);
    const UniformityResult u = uniformity(c, kind);
    EXPECT_TRUE(arb_overlaps(r.u_before.get(), u.u.get())) << c.str() << ": " << r.u_before.str(20) << " vs "
                                                           << u.u.str(20);
    EXPECT_TRUE(r.u_before.meets_digits(16)) << r.u_before.str(25);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), u.mu.get())) << c.str();
  }
}

TEST(ReparamC1, RejectsBadTargets) {
  const Curve c = parse_curve("(t, t^2)");
  EXPECT_THROW(reparam_c1(c, SpeedKind::Angular, Rational(3, 2), {}), InvalidArgument);
  EXPECT_THROW(reparam_c1(c, SpeedKind::Angular, Rational(0), {}), InvalidArgument);
  EXPECT_THROW(reparam_c1(c, SpeedKind::Angular, Rational(1), {}), InvalidArgument);
  EXPECT_THROW(reparam_c1(c, SpeedKind::Angular, Rational(1, 2), {}, 0), InvalidArgument);
}

TEST(RationalOutput, C0MapsAreExactAndTheirUniformityIsIndependentlyConfirmed) {
  for (const char* curve : {kSlide, "(t, t^3)", "(t^2, t^3 + t/3)", "((1 - t^2)/(1 + t^2), 2t/(1 + t^2), t)"}) {
    const Curve c = parse_curve(curve);
    const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 3, {});
    const MoebiusResult q = make_rational(c, r, 6, {});
    ASSERT_TRUE(q.exact.has_value());
    EXPECT_EQ(q.continuity, Continuity::C0);
    for (std::size_t i = 0; i < q.pieces(); ++i) {
      EXPECT_TRUE(q.exact->S[i] < q.exact->S[i + 1]);
      EXPECT_TRUE(q.exact->alpha[i].sign() > 0 && q.exact->alpha[i] < Rational(1));
      // C0 exactly: piece i ends where piece i+1 starts
      EXPECT_EQ(piece_map(q, i)(Rational(1)), q.exact->T[i + 1]);
      EXPECT_EQ(piece_map(q, i)(Rational(0)), q.exact->T[i]);
    }
    const Ball u = independent_u(c, q, SpeedKind::Angular, 15);
    EXPECT_TRUE(arb_overlaps(u.get(), q.u_after.get())) << curve;
    // rounding to 6 digits costs at most a little uniformity
    Ball diff;
    arb_sub(diff.get(), r.u_after.get(), q.u_after.get(), 128);
    EXPECT_TRUE(arb_lt(diff.get(), Ball(Rational(1, 100000), 64).get())) << curve;
  }
}
