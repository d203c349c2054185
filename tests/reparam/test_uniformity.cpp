// Certified uniformity: reference values of docs/math.md section 6 (independent
// 40-digit values), exact special cases, and invariance properties.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include <random>

#include "support/curves.hpp"
#include "support/reference.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

struct Reference {
  const char* curve;
  const char* mu;
  const char* u;
};

const Reference kRefs[] = {
    {"(t, t^3)", "1.249045772398254425829917077281", "0.845695243153366341883011346954"},
    {"(t, t^2)", "1.107148717794090503017065", "0.8133094424199794137403804"},
    {"((1-t^2)/(1+t^2), 2t/(1+t^2))", "1.570796326794896619231322", "0.9597808564432393298507263"},
};

}  // namespace

class ReferenceValues : public ::testing::TestWithParam<long> {};

TEST_P(ReferenceValues, AngularMuAndUContainReferenceAndMeetDigits) {
  const long digits = GetParam();
  for (const auto& r : kRefs) {
    Options o;
    o.digits = digits;
    auto res = uniformity(parse_curve(r.curve), SpeedKind::Angular, o);
    EXPECT_TRUE(test_support::contains_ref(res.mu, r.mu)) << r.curve << " mu " << res.mu.str(40);
    EXPECT_TRUE(test_support::contains_ref(res.u, r.u)) << r.curve << " u " << res.u.str(40);
    EXPECT_TRUE(res.mu.meets_digits(digits)) << res.mu.str(40);
    EXPECT_TRUE(res.u.meets_digits(digits)) << res.u.str(40);
  }
}

INSTANTIATE_TEST_SUITE_P(Digits, ReferenceValues, ::testing::Values(15L, 40L));

TEST(Uniformity, RunningExampleZeroAtOriginWithMultiplicityOne) {
  auto r = uniformity(parse_curve("(t, t^3)"), SpeedKind::Angular);
  ASSERT_EQ(r.zeros.size(), 1u);
  EXPECT_TRUE(r.zeros[0].t.is_rational());
  EXPECT_EQ(r.zeros[0].t.rational(), Rational(0));
  EXPECT_EQ(r.zeros[0].multiplicity, 1);
  // omega^2 = 36 t^2 / (9 t^4 + 1)^2 exactly.
  Poly t = Poly::t();
  Poly d = Poly(9) * t.pow(4) + Poly(1);
  EXPECT_EQ(r.speed_squared, RatFunc(Poly(36) * t * t, d * d));
}

TEST(Uniformity, StraightLineHasAngularUniformityExactlyOne) {
  auto r = uniformity(parse_curve("(1 + 2t, 3 - t/2)"), SpeedKind::Angular);
  EXPECT_TRUE(r.identically_zero);
  EXPECT_TRUE(r.mu.certainly_zero());
  EXPECT_TRUE(r.u.is_exact());
  EXPECT_TRUE(r.u.contains(Rational(1)));
  // ... and constant parametric speed: u = 1 certified (ball contains 1).
  auto p = uniformity(parse_curve("(1 + 2t, 3 - t/2)"), SpeedKind::Parametric);
  EXPECT_FALSE(p.identically_zero);
  EXPECT_TRUE(p.u.contains(Rational(1)));
}

TEST(Uniformity, ParametricSpeedOfParabolaMatchesClosedForm) {
  // |p'| = sqrt(1 + 4t^2): arc length (2 sqrt 5 + asinh 2) / 4, int |p'|^2 = 7/3.
  Options o;
  o.digits = 30;
  auto r = uniformity(parse_curve("(t, t^2)"), SpeedKind::Parametric, o);
  Ball mu, a;
  arb_sqrt_ui(mu.get(), 5, 256);
  arb_mul_2exp_si(mu.get(), mu.get(), 1);
  arb_set_si(a.get(), 2);
  arb_asinh(a.get(), a.get(), 256);
  arb_add(mu.get(), mu.get(), a.get(), 256);
  arb_mul_2exp_si(mu.get(), mu.get(), -2);
  EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(40) << " vs " << mu.str(40);
  EXPECT_TRUE(r.mean_square.contains(Rational(7, 3))) << r.mean_square.str(40);
  EXPECT_TRUE(r.zeros.empty());
}

TEST(Uniformity, CuspAngularSpeedIsFiniteParametricSpeedVanishes) {
  const Curve c = parse_curve("(t^2, t^3)");
  auto a = uniformity(c, SpeedKind::Angular);
  EXPECT_TRUE(a.zeros.empty());  // omega = 6 / (4 + 9 t^2) after cancellation
  Poly t = Poly::t();
  Poly d = Poly(9) * t * t + Poly(4);
  EXPECT_EQ(a.speed_squared, RatFunc(Poly(36), d * d));
  auto p = uniformity(c, SpeedKind::Parametric);
  ASSERT_EQ(p.zeros.size(), 1u);
  EXPECT_EQ(p.zeros[0].t.rational(), Rational(0));
  EXPECT_EQ(p.zeros[0].multiplicity, 1);
  // mu = int_0^1 t sqrt(4 + 9t^2) = (13^{3/2} - 8) / 27
  Ball mu;
  arb_set_ui(mu.get(), 13);
  arb_sqrt(mu.get(), mu.get(), 256);
  arb_mul_ui(mu.get(), mu.get(), 13, 256);
  arb_sub_ui(mu.get(), mu.get(), 8, 256);
  arb_div_ui(mu.get(), mu.get(), 27, 256);
  EXPECT_TRUE(arb_overlaps(p.mu.get(), mu.get())) << p.mu.str(30);
}

TEST(Uniformity, IrrationalInteriorZeroIsIsolatedAndIntegratedAcross) {
  // x = t, y = t^3/3 - t/2 ... y'' = 2t: inflection at 0; shift to get an
  // irrational inflection: y = (t - r)^3 with r = 1/sqrt(2) is not rational,
  // so use y'' ~ 2t^2 - 1: y = t^4/6 - t^2/2.
  auto r = uniformity(parse_curve("(t, t^4/6 - t^2/2)"), SpeedKind::Angular);
  ASSERT_EQ(r.zeros.size(), 1u);
  EXPECT_FALSE(r.zeros[0].t.is_rational());
  Ball z = r.zeros[0].t.to_ball(128), s;
  arb_sqrt_ui(s.get(), 2, 128);
  arb_inv(s.get(), s.get(), 128);
  EXPECT_TRUE(arb_overlaps(z.get(), s.get()));
  EXPECT_TRUE(r.u.meets_digits(15));
}

TEST(Uniformity, SpaceCurveIsSupported) {
  auto r = uniformity(parse_curve("(t, t^2, t^3)"), SpeedKind::Angular);
  EXPECT_TRUE(r.zeros.empty());  // the twisted cubic has no inflection
  EXPECT_TRUE(r.u.meets_digits(15));
  EXPECT_TRUE(arb_is_positive(r.u.get()));
  // A planar curve embedded in space has the same uniformity.
  auto plane = uniformity(parse_curve("(t, t^3)"), SpeedKind::Angular);
  auto space = uniformity(parse_curve("(t, t^3, 0)"), SpeedKind::Angular);
  EXPECT_TRUE(arb_overlaps(plane.u.get(), space.u.get()));
  EXPECT_EQ(space.zeros.size(), 1u);
}

TEST(Uniformity, NonRegularCurvesAreDomainErrors) {
  EXPECT_THROW(parse_curve("(1/(t - 1/2), t)"), DomainError);
  EXPECT_THROW(parse_curve("(1/(2t^2 - 1), t)"), DomainError);  // irrational pole
  EXPECT_THROW(parse_curve("(t, 1/(t - 1))"), DomainError);     // pole at the end
  EXPECT_THROW(parse_curve("(t, 1/t)"), DomainError);           // pole at 0
  EXPECT_THROW(parse_curve("(1, 2)"), DomainError);             // constant
  EXPECT_THROW(parse_curve("(t)"), InvalidArgument);            // one component
  EXPECT_NO_THROW(parse_curve("(t, 1/(t + 1/1000))"));         // pole just outside
}

TEST(Uniformity, OptionsAreValidated) {
  Options o;
  o.digits = 0;
  EXPECT_THROW(uniformity(parse_curve("(t, t^2)"), SpeedKind::Angular, o), InvalidArgument);
  o.digits = 15;
  o.max_degree = 2;
  EXPECT_THROW(uniformity(parse_curve("(t, t^3)"), SpeedKind::Angular, o), BudgetExceeded);
}

// mu is invariant under reparameterization, and both speeds are invariant
// under rotation+translation (angular also under scaling). Random rational
// curves, random Moebius maps with rational alpha: the certified balls of the
// original and of the exactly composed curve must overlap.
TEST(UniformityProperty, MeanIsInvariantUnderMoebiusReparameterization) {
  std::mt19937_64 rng(20261122);
  const int iters = test_support::iterations(8);
  // Moebius maps with alpha in [0.3, 0.6]: stronger compressions create
  // near-singular speeds whose certified integration is slow (see docs/benchmarks.md).
  std::uniform_int_distribution<long> ad(3, 6);
  for (int it = 0; it < iters; ++it) {
    const long deg = 2 + it % 4;
    std::vector<RatFunc> comps;
    for (int k = 0; k < 2 + it % 2; ++k) {
      Poly num = test_support::random_poly(rng, deg, 9);
      // denominators positive on [0, 1]: 10 + t^2 * small
      Poly den = Poly(20) + test_support::random_poly(rng, 1, 3) * Poly::t();
      comps.emplace_back(num, den);
    }
    Curve c(comps);
    const Rational alpha(ad(rng), 10);
    // t = (1 - a) s / ((1 - a) s + a (1 - s))
    RatFunc s = RatFunc::t();
    RatFunc one_minus_a(Rational(1) - alpha), a(alpha);
    RatFunc r = one_minus_a * s / (one_minus_a * s + a * (RatFunc(1) - s));
    std::vector<RatFunc> composed;
    for (const auto& x : comps) composed.push_back(test_support::compose(x, r));
    Curve cr(composed);
    for (auto kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      auto u0 = uniformity(c, kind), u1 = uniformity(cr, kind);
      EXPECT_TRUE(arb_overlaps(u0.mu.get(), u1.mu.get()))
          << c.str() << " alpha " << alpha.str() << " " << u0.mu.str(20) << " vs " << u1.mu.str(20);
      EXPECT_EQ(u0.zeros.size(), u1.zeros.size()) << c.str();
    }
  }
}

TEST(UniformityProperty, SplitPointsAreEveryInteriorMultipleOfOneOverParts) {
  // Random sorted ends (rationals and sqrt-type algebraic numbers) against
  // the oracle: the output is strictly increasing, holds every input end,
  // and besides them exactly the j / parts strictly inside (front, back).
  std::mt19937_64 rng(808);
  const int iters = test_support::iterations(200);
  for (int it = 0; it < iters; ++it) {
    const long parts = std::uniform_int_distribution<long>(1, 12)(rng);
    std::vector<RealAlgebraic> ends;
    const int n = std::uniform_int_distribution<int>(2, 5)(rng);
    while (static_cast<int>(ends.size()) < n) {
      const long m = std::uniform_int_distribution<long>(2, 30)(rng);
      const long den = std::uniform_int_distribution<long>(1, 24)(rng);
      const long num = std::uniform_int_distribution<long>(0, den)(rng);
      // sqrt(m)/6 (rational when m is a square), or num/den
      const RealAlgebraic x = rng() % 3 == 0 ? RealAlgebraic(Poly(std::vector<long>{-m, 0, 36}), Rational(0), Rational(1))
                                             : RealAlgebraic(Rational(num, den));
      bool dup = false;
      for (const auto& e : ends) dup = dup || e == x;
      if (!dup) ends.push_back(x);
    }
    std::sort(ends.begin(), ends.end(), [](const RealAlgebraic& a, const RealAlgebraic& b) { return a < b; });
    const std::vector<RealAlgebraic> out = detail::with_split_points(ends, parts);
    for (std::size_t i = 0; i + 1 < out.size(); ++i) EXPECT_TRUE(out[i] < out[i + 1]);
    for (const auto& e : ends) EXPECT_EQ(std::count(out.begin(), out.end(), e), 1) << e.str();
    std::size_t expected = ends.size();
    for (long j = 1; j < parts; ++j) {
      const RealAlgebraic q(Rational(j, parts));
      const bool inside = ends.front() < q && q < ends.back();
      const bool given = std::count(ends.begin(), ends.end(), q) > 0;
      EXPECT_EQ(std::count(out.begin(), out.end(), q), inside || given ? 1 : 0) << j << "/" << parts;
      if (inside && !given) ++expected;
    }
    EXPECT_EQ(out.size(), expected);
  }
}

// From degree 100 of sigma^2's numerator, uniformity() splits its integrals
// into equal parts (tasks for the worker threads): the sums of the parts
// must agree with the whole integrals over [0, 1] (integrate_speed and
// integrate_speed_squared split only at the zeros of sigma), and the parts
// must not cost the requested digits.
TEST(UniformityProperty, SplitIntegralsAgreeWithWholeOnes) {
  std::mt19937_64 rng(5150);
  const int iters = test_support::iterations(3);
  Options o;
  o.digits = 20;
  const long bits = digits_to_bits(o.digits) + 8;
  for (int it = 0; it < iters; ++it) {
    const long deg = std::uniform_int_distribution<long>(30, 40)(rng);
    const Curve c({RatFunc(test_support::random_poly(rng, deg, 20)), RatFunc(test_support::random_poly(rng, deg, 20))});
    const Speed s(c, SpeedKind::Angular);
    ASSERT_GE(s.squared().num().degree(), 100) << c.str();
    const UniformityResult u = uniformity(s, o);
    const Ball mu = integrate_speed(s, RealAlgebraic(0), RealAlgebraic(1), bits, o.max_prec);
    const Ball sq = integrate_speed_squared(s, RealAlgebraic(0), RealAlgebraic(1), bits, o.max_prec);
    EXPECT_TRUE(arb_overlaps(u.mu.get(), mu.get())) << c.str() << ": " << u.mu.str(25) << " vs " << mu.str(25);
    EXPECT_TRUE(arb_overlaps(u.mean_square.get(), sq.get()))
        << c.str() << ": " << u.mean_square.str(25) << " vs " << sq.str(25);
    EXPECT_TRUE(u.mu.meets_digits(o.digits) && u.mean_square.meets_digits(o.digits) && u.u.meets_digits(o.digits));
  }
}
