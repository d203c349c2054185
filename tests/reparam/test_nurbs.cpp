// p o r as a NURBS (reparam/nurbs.hpp): property tests with an exact oracle.
// Random rational curves and random rational Moebius maps; the NURBS is
// evaluated by an independent de Boor algorithm on its knot vector and
// homogeneous control points, exactly, and compared with p(r(s)) computed
// from the map's formula.
#include <gtest/gtest.h>

#include <random>

#include "support/de_boor.hpp"
#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::iterations;
using uniparam::test_support::random_poly;

namespace {

Rational random_unit(std::mt19937_64& rng, long den) {
  std::uniform_int_distribution<long> d(1, den - 1);
  return Rational(d(rng), den);
}

// A random rational curve of degree <= 3 in dimension 2 or 3 with a common or
// separate denominators positive on [0, 1]; some denominators have negative
// Bernstein coefficients on [0, 1] (t^2 - t + k, 1/4 < k < 1/2).
Curve random_curve(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 2), dim(2, 3), deg(1, 3);
  const int n = dim(rng);
  for (;;) {
    Poly W(1);
    const int k = kind(rng);
    if (k == 1) W = Poly(std::vector<long>{1, 0, 1});                     // 1 + t^2
    if (k == 2) W = Poly(std::vector<long>{3, -10, 10});                  // 10 (t^2 - t + 3/10)
    std::vector<RatFunc> comps;
    for (int i = 0; i < n; ++i) comps.push_back(RatFunc(random_poly(rng, deg(rng), 5), W));
    try {
      return Curve(comps);
    } catch (const DomainError&) {
      continue;  // constant curve: draw again
    }
  }
}

// A random rational C0 piecewise Moebius map with N pieces.
MoebiusResult random_map(std::mt19937_64& rng, long N, long prec) {
  auto sorted_points = [&](long n) {
    std::vector<Rational> v{Rational(0), Rational(1)};
    while (static_cast<long>(v.size()) < n + 1) {
      const Rational x = random_unit(rng, 97);
      if (std::find(v.begin(), v.end(), x) == v.end()) v.push_back(x);
    }
    std::sort(v.begin(), v.end());
    return v;
  };
  MoebiusResult r;
  r.kind = SpeedKind::Parametric;
  r.exact.emplace();
  r.exact->T = sorted_points(N);
  r.exact->S = sorted_points(N);
  for (long i = 0; i < N; ++i) r.exact->alpha.push_back(random_unit(rng, 31));
  for (const auto& t : r.exact->T) r.T.push_back(Breakpoint{RealAlgebraic(t), 0, 0, 0});
  for (const auto& s : r.exact->S) r.S.emplace_back(s, prec);
  for (const auto& a : r.exact->alpha) r.alpha.emplace_back(a, prec);
  return r;
}

// r(s) from the map's formula (2.1).
Rational r_exact(const MoebiusResult& r, const Rational& s) {
  std::size_t i = 0;
  while (i + 1 < r.pieces() && s > r.exact->S[i + 1]) ++i;
  const Rational u = (s - r.exact->S[i]) / (r.exact->S[i + 1] - r.exact->S[i]);
  const Rational& a = r.exact->alpha[i];
  const Rational num = (Rational(1) - a) * u;
  return r.exact->T[i] + (r.exact->T[i + 1] - r.exact->T[i]) * num / (num + a * (Rational(1) - u));
}

// De Boor's algorithm, exactly (tests/support/de_boor.hpp).
std::vector<Rational> de_boor(const Nurbs& n, const Rational& s) {
  return test_support::de_boor(n.degree, n.knots_exact, n.points_exact, n.weights_exact, s);
}

// Clamped knot vector of degree p with interior multiplicities <= p, sizes
// consistent with the control points, all weights positive.
void expect_valid(const Nurbs& n) {
  const auto& U = n.knots_exact;
  const std::size_t p = static_cast<std::size_t>(n.degree);
  ASSERT_EQ(U.size(), n.points_exact.size() + p + 1);
  ASSERT_EQ(n.weights_exact.size(), n.points_exact.size());
  for (std::size_t i = 0; i <= p; ++i) {
    EXPECT_EQ(U[i], Rational(0));
    EXPECT_EQ(U[U.size() - 1 - i], Rational(1));
  }
  std::size_t run = 1;
  for (std::size_t i = 1; i < U.size(); ++i) {
    ASSERT_LE(U[i - 1], U[i]);
    run = U[i] == U[i - 1] ? run + 1 : 1;
    if (U[i] != Rational(0) && U[i] != Rational(1)) EXPECT_LE(run, p);
  }
  for (const auto& w : n.weights_exact) EXPECT_GT(w.sign(), 0);
}

}  // namespace

TEST(Nurbs, ExactNurbsEqualsPComposedWithRAtRandomParameters) {
  std::mt19937_64 rng(3801);
  std::uniform_int_distribution<long> pieces(1, 4);
  for (long it = 0; it < iterations(40); ++it) {
    const Curve c = random_curve(rng);
    const MoebiusResult r = random_map(rng, pieces(rng), 128);
    const Nurbs n = moebius_nurbs(c, r, 128);
    ASSERT_EQ(n.kind, Nurbs::Kind::Exact);
    expect_valid(n);
    std::vector<Rational> ss{Rational(0), Rational(1)};
    for (const auto& s : r.exact->S) ss.push_back(s);
    for (int k = 0; k < 10; ++k) ss.push_back(random_unit(rng, 1009));
    for (const Rational& s : ss) {
      const Rational t = r_exact(r, s);
      const std::vector<Rational> v = de_boor(n, s);
      const std::vector<Rational> e = nurbs_eval(n, s);
      ASSERT_EQ(v.size(), c.dimension());
      for (std::size_t k = 0; k < c.dimension(); ++k) {
        EXPECT_EQ(v[k], c.components()[k](t)) << c.str() << " at s = " << s.str();
        EXPECT_EQ(e[k], v[k]);
      }
    }
  }
}

TEST(Nurbs, BallNurbsContainsPComposedWithR) {
  std::mt19937_64 rng(3802);
  std::uniform_int_distribution<long> pieces(1, 4);
  const long prec = 96;
  for (long it = 0; it < iterations(30); ++it) {
    const Curve c = random_curve(rng);
    MoebiusResult r = random_map(rng, pieces(rng), prec);
    const MoebiusResult exact = r;
    r.exact.reset();  // the same map, built in ball arithmetic
    const Nurbs n = moebius_nurbs(c, r, prec);
    ASSERT_EQ(n.kind, Nurbs::Kind::Balls);
    const Nurbs q = moebius_nurbs(c, exact, prec);
    ASSERT_EQ(n.points.size(), q.points_exact.size());
    for (std::size_t i = 0; i < n.points.size(); ++i) {
      EXPECT_TRUE(n.weights[i].certainly_positive());
      EXPECT_TRUE(n.weights[i].contains(q.weights_exact[i]));
      for (std::size_t k = 0; k < c.dimension(); ++k) EXPECT_TRUE(n.points[i][k].contains(q.points_exact[i][k]));
    }
    for (std::size_t i = 0; i < n.knots.size(); ++i) EXPECT_TRUE(n.knots[i].contains(q.knots_exact[i]));
    for (int k = 0; k < 10; ++k) {
      const Rational s = random_unit(rng, 1009);
      const Rational t = r_exact(exact, s);
      const std::vector<Ball> v = nurbs_eval(n, Ball(s, prec), prec);
      for (std::size_t j = 0; j < c.dimension(); ++j) EXPECT_TRUE(v[j].contains(c.components()[j](t)));
    }
  }
}

TEST(Nurbs, NonPositiveBernsteinWeightsAreSubdividedAway) {
  // W = 10 t^2 - 10 t + 3 > 0 on [0, 1], Bernstein coefficients 3, -2, 3
  const Curve c = Curve::parse("(t/(10*t^2-10*t+3), 1/(10*t^2-10*t+3))");
  MoebiusResult r;
  r.kind = SpeedKind::Parametric;
  r.exact.emplace();
  r.exact->T = {Rational(0), Rational(1)};
  r.exact->S = {Rational(0), Rational(1)};
  r.exact->alpha = {Rational(1, 2)};
  for (const auto& t : r.exact->T) r.T.push_back(Breakpoint{RealAlgebraic(t), 0, 0, 0});
  r.S = {Ball(0), Ball(1)};
  r.alpha = {Ball(Rational(1, 2), 64)};
  const Nurbs n = moebius_nurbs(c, r, 64);
  EXPECT_GT(n.segments, 1u);
  EXPECT_EQ(n.subdivided, n.segments);
  expect_valid(n);
  for (int k = 0; k <= 16; ++k) {
    const Rational s(k, 16);
    const std::vector<Rational> v = de_boor(n, s);
    EXPECT_EQ(v[0], c.components()[0](s));
    EXPECT_EQ(v[1], c.components()[1](s));
  }
}

TEST(Nurbs, OptimalRationalMapOfTheCommandsIsExact) {
  const Curve c = Curve::parse("(t, t^3/(1+t^2))");
  Options opt;
  opt.digits = 10;
  const MoebiusResult r = make_rational(c, reparam_c0(c, SpeedKind::Angular, 3, opt), 8, opt);
  const Nurbs n = moebius_nurbs(c, r, 64);
  ASSERT_EQ(n.kind, Nurbs::Kind::Exact);
  expect_valid(n);
  EXPECT_EQ(n.segments, 3u);
  for (std::size_t i = 0; i <= 3; ++i) {
    const std::vector<Rational> v = de_boor(n, r.exact->S[i]);
    EXPECT_EQ(v[0], c.components()[0](r.exact->T[i]));
    EXPECT_EQ(v[1], c.components()[1](r.exact->T[i]));
  }
}

TEST(Nurbs, BezierIntegralCurveGivesExactSurdWeights) {
  const BezierCurve b = BezierCurve::parse("[[0,0],[1,2],[3,1],[4,4]]");
  const BezierResult r = bezier_optimal(b);
  const Nurbs n = bezier_nurbs(b, r, 128);
  ASSERT_EQ(n.kind, Nurbs::Kind::Surd);
  EXPECT_EQ(n.points_exact, b.points());
  ASSERT_EQ(n.weights_surd.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(n.weights_surd[i].str(), r.weights_exact[i].str());
    EXPECT_TRUE(n.weights[i].certainly_positive());
  }
  EXPECT_EQ(n.knots_exact.size(), 8u);
}
