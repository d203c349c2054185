// Speeds with narrow features inside (0, 1): peak_split's parts, each
// balanced on its own, give the uniformity at a cost independent of the
// features' width, and the same certified values as the direct integrals.
#include <gtest/gtest.h>

#include <arb.h>

#include <random>
#include <string>
#include <vector>

#include "support/reference.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/all.hpp"
#include "uniparam/reparam/scaling.hpp"

using namespace uniparam;

namespace {

// A random integer with `digits` decimal digits, the first nonzero.
std::string random_digits(std::mt19937& rng, int digits) {
  std::string s(1, static_cast<char>('1' + rng() % 9));
  for (int i = 1; i < digits; ++i) s += static_cast<char>('0' + rng() % 10);
  return s;
}

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

// (t, C (t - c)^2) for random centres c in (0, 1) and 40-digit C: a peak
// of width 1/(2C) at c, found and split at; the uniformity part by part
// overlaps the direct integrals (uniformity(Speed): no split, no balance),
// and mu the closed form atan(2 C c) + atan(2 C (1 - c)).
TEST(PeakSplit, PartsAgreeWithTheDirectIntegrals) {
  TimeBudget budget(300);
  std::mt19937 rng(20261203);
  for (int trial = 0; trial < 6; ++trial) {
    const std::string C = random_digits(rng, 40);
    const long den = 3 + static_cast<long>(rng() % 17);
    const long num = 1 + static_cast<long>(rng() % static_cast<unsigned long>(den - 1));
    const std::string centre = std::to_string(num) + "/" + std::to_string(den);
    const std::string extra = trial % 2 ? " + t^3" : "";
    const Curve p = Curve::parse("(t, " + C + "*(t - " + centre + ")^2" + extra + ")");
    SCOPED_TRACE(p.str());
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(p, kind);
      const std::optional<PeakSplit> split = peak_split(s);
      ASSERT_TRUE(split.has_value());
      // A feature knot within 2^-100 of the centre (the peak's width is
      // about 2^-133): the part's end is on the peak's own scale.
      bool at_centre = false;
      for (std::size_t i = 0; i < split->knots.size(); ++i) {
        const Rational d = split->knots[i] - Rational(num, den);
        at_centre = at_centre || (split->feature[i] && d <= pow2(-100) && Rational(0) - d <= pow2(-100));
      }
      EXPECT_TRUE(at_centre) << "no feature at the peak";
      Options o;
      o.digits = 20;
      const UniformityResult parts = uniformity(p, kind, o);
      const UniformityResult direct = uniformity(s, o);
      EXPECT_TRUE(arb_overlaps(parts.mu.get(), direct.mu.get())) << parts.mu.str(25) << " vs " << direct.mu.str(25);
      EXPECT_TRUE(arb_overlaps(parts.mean_square.get(), direct.mean_square.get()))
          << parts.mean_square.str(25) << " vs " << direct.mean_square.str(25);
      EXPECT_TRUE(arb_overlaps(parts.u.get(), direct.u.get())) << parts.u.str(25) << " vs " << direct.u.str(25);
      if (kind == SpeedKind::Angular && extra.empty()) {
        Ball c2, a, b, mu;
        arb_set_str(c2.get(), C.c_str(), 512);
        arb_mul_2exp_si(c2.get(), c2.get(), 1);
        arb_mul(a.get(), c2.get(), Ball(Rational(num, den), 512).get(), 512);
        arb_mul(b.get(), c2.get(), Ball(Rational(den - num, den), 512).get(), 512);
        arb_atan(a.get(), a.get(), 512);
        arb_atan(b.get(), b.get(), 512);
        arb_add(mu.get(), a.get(), b.get(), 512);
        EXPECT_TRUE(arb_overlaps(parts.mu.get(), mu.get())) << parts.mu.str(25) << " vs " << mu.str(25);
      }
    }
  }
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
