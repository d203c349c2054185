// ImUp's ReparameterizationN: C0 piecewise Moebius with optimised breakpoints.
// Properties: never worse than the equally spaced T, u grows with N, and the
// returned T is a certified local optimum (moving any breakpoint does not
// raise the certified u).
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

// ImUp's slide curve (Yang, Wang, Hong 2014, ImUp).
const char* kSlide =
    "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";

std::vector<RealAlgebraic> equal_T(long N) {
  std::vector<RealAlgebraic> T;
  for (long i = 0; i <= N; ++i) T.emplace_back(Rational(i, N));
  return T;
}

// a <= b up to the balls: fails only when a is certainly above b.
bool not_above(const Ball& a, const Ball& b) { return !arb_gt(a.get(), b.get()); }

std::vector<RealAlgebraic> rational_T(const MoebiusResult& r) {
  std::vector<RealAlgebraic> T;
  for (const auto& b : r.T) T.push_back(b.t);
  return T;
}

}  // namespace

TEST(ReparamC0, SlideCurveThreePiecesBeatsEqualSpacing) {
  const Curve c = parse_curve(kSlide);
  Options o;
  o.digits = 15;
  const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 3, o);
  ASSERT_EQ(r.pieces(), 3u);
  EXPECT_TRUE(r.optimiser.has_value());
  EXPECT_EQ(r.continuity, Continuity::C0);
  const MoebiusResult eq = moebius_c0(c, SpeedKind::Angular, equal_T(3), o);
  EXPECT_TRUE(not_above(eq.u_after, r.u_after));
  EXPECT_TRUE(arb_gt(r.u_after.get(), r.u_before.get()));
  EXPECT_LT(r.optimiser->stationarity, 1e-6);
  // certified phi is consistent with u = mu^2 / phi^2
  Ball u;
  arb_mul(u.get(), r.mu.get(), r.mu.get(), 256);
  arb_div(u.get(), u.get(), r.optimiser->phi.get(), 256);
  arb_div(u.get(), u.get(), r.optimiser->phi.get(), 256);
  EXPECT_TRUE(arb_overlaps(u.get(), r.u_after.get()));
}

TEST(ReparamC0, ReturnsACertifiedLocalOptimum) {
  const Curve c = parse_curve("((1 - t^2)/(1 + t^2), 2t/(1 + t^2), t^3)");
  Options o;
  o.digits = 15;
  const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 3, o);
  EXPECT_LT(r.optimiser->stationarity, 1e-6);
  // local optimality: moving one breakpoint by +-1e-3 never raises the certified u
  const std::vector<RealAlgebraic> T = rational_T(r);
  for (std::size_t j = 1; j + 1 < T.size(); ++j)
    for (long sgn : {-1L, 1L}) {
      std::vector<RealAlgebraic> T2 = T;
      T2[j] = RealAlgebraic(T[j].rational() + Rational(sgn, 1000));
      const MoebiusResult moved = moebius_c0(c, SpeedKind::Angular, T2, o);
      EXPECT_TRUE(not_above(moved.u_after, r.u_after)) << "breakpoint " << j << " moved by " << sgn << "/1000";
    }
}

TEST(ReparamC0, UniformityGrowsWithTheNumberOfPieces) {
  for (const char* curve : {"(t, t^3)", "(t, t^2)", "((1 - t^2)/(1 + t^2), 2t/(1 + t^2), t)"}) {
    const Curve c = parse_curve(curve);
    Ball prev;
    for (long N = 1; N <= 4; ++N) {
      const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, N, {});
      if (N > 1) EXPECT_TRUE(not_above(prev, r.u_after)) << curve << " N = " << N;
      prev = r.u_after;
    }
  }
}

TEST(ReparamC0, NeverWorseThanEqualSpacingOnRandomCurves) {
  std::mt19937_64 rng(2024);
  for (long it = 0; it < test_support::iterations(6); ++it) {
    const Curve c({RatFunc(test_support::random_poly(rng, 3, 9)), RatFunc(test_support::random_poly(rng, 4, 9))});
    SpeedKind kind = it % 2 ? SpeedKind::Parametric : SpeedKind::Angular;
    Speed s(c, kind);
    if (s.identically_zero()) continue;
    const long N = 2 + it % 3;
    const MoebiusResult r = reparam_c0(c, kind, N, {});
    const MoebiusResult eq = moebius_c0(c, kind, equal_T(N), {});
    EXPECT_TRUE(not_above(eq.u_after, r.u_after)) << c.str() << " N = " << N;
    EXPECT_TRUE(not_above(r.optimiser->phi, r.optimiser->phi_equal));
    // u_before from the pieces (sum L_i / Delta t_i for int sigma^2, at the
    // optimised and at the equal T) against the uniformity's own integrals
    const UniformityResult u = uniformity(s);
    for (const MoebiusResult* m : {&r, &eq}) {
      EXPECT_TRUE(arb_overlaps(m->u_before.get(), u.u.get())) << c.str() << ": " << m->u_before.str(20) << " vs "
                                                              << u.u.str(20);
      EXPECT_TRUE(m->u_before.meets_digits(16)) << m->u_before.str(25);
    }
  }
}

TEST(ReparamC0, StationaryLocalOptimaNearACusp) {
  // (w^2, w^3 + e w), w = t - a: a near-cusp, whose angular speed has a
  // peak of height ~1/e and width ~e at a. Phi is not convex along the
  // descent direction there: the optimiser must still end stationary (it
  // crawled for its 200 iterations with the BFGS update skipped, ending at
  // stationarity ~1e-6 to 1e-2), and no breakpoint moved by +-1e-3 may raise
  // the certified u.
  for (const char* a : {"7/10", "3/10", "11/20"})
    for (const char* e : {"1/1000", "1/300"}) {
      const std::string w = std::string("(t - ") + a + ")";
      const Curve c = parse_curve("(" + w + "^2, " + w + "^3 + " + e + " " + w + ")");
      const MoebiusResult r = reparam_c0(c, SpeedKind::Angular, 3, {});
      EXPECT_LT(r.optimiser->stationarity, 1e-6) << c.str() << " after " << r.optimiser->iterations << " iterations";
      const std::vector<RealAlgebraic> T = rational_T(r);
      for (std::size_t j = 1; j + 1 < T.size(); ++j)
        for (long sgn : {-1L, 1L}) {
          std::vector<RealAlgebraic> T2 = T;
          T2[j] = RealAlgebraic(T[j].rational() + Rational(sgn, 1000));
          if (!(T2[j - 1] < T2[j] && T2[j] < T2[j + 1])) continue;
          const MoebiusResult moved = moebius_c0(c, SpeedKind::Angular, T2, {});
          EXPECT_TRUE(not_above(moved.u_after, r.u_after))
              << c.str() << ": breakpoint " << j << " moved by " << sgn << "/1000 gives " << moved.u_after.str(20)
              << " > " << r.u_after.str(20);
        }
    }
}

TEST(ReparamC0, RejectsBadPieceCounts) {
  const Curve c = parse_curve("(t, t^2)");
  EXPECT_THROW(reparam_c0(c, SpeedKind::Angular, 0, {}), InvalidArgument);
  EXPECT_THROW(reparam_c0(c, SpeedKind::Angular, 1001, {}), InvalidArgument);
}
