// Bezier curves and their optimal bilinear reparameterization (Farouki 1997; Juettler 1997):
// eq. (21) against exact integration in the power basis, eq. (22)'s exact
// alpha against the general optimal Moebius map of docs/math.md section 2, the new
// weights against p o m, the quarter circle of docs/math.md section 6, the exact
// quadratic surds, and input validation.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "support/reference.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using test_support::iterations;

namespace {

Rational random_rational(std::mt19937_64& rng, long bound) {
  std::uniform_int_distribution<long> num(-bound, bound), den(1, 4);
  return Rational(num(rng), den(rng));
}

BezierCurve random_bezier(std::mt19937_64& rng, long degree, std::size_t dim, bool rational) {
  for (;;) {
    std::vector<std::vector<Rational>> pts(static_cast<std::size_t>(degree + 1));
    for (auto& p : pts)
      for (std::size_t k = 0; k < dim; ++k) p.push_back(random_rational(rng, 5));
    std::vector<Rational> w;
    if (rational) {
      std::uniform_int_distribution<long> num(1, 6), den(1, 3);
      for (long i = 0; i <= degree; ++i) w.emplace_back(num(rng), den(rng));
    }
    bool constant = true;
    for (const auto& p : pts) constant = constant && p == pts.front();
    if (!constant) return BezierCurve(pts, w);
  }
}

RatFunc bernstein(long n, long i) {
  Integer b;
  fmpz_bin_uiui(b.get(), static_cast<unsigned long>(n), static_cast<unsigned long>(i));
  const RatFunc t = RatFunc::t();
  return RatFunc(Rational(b)) * t.pow(i) * (RatFunc(1) - t).pow(n - i);
}

// The components of the Bezier curve, built here from Bernstein polynomials
// with rational-function arithmetic (independent of BezierCurve::to_curve).
std::vector<RatFunc> oracle_components(const BezierCurve& b) {
  const long n = b.degree();
  const auto v = b.weights();
  std::vector<RatFunc> num(b.dimension(), RatFunc(0));
  RatFunc den(0);
  for (long i = 0; i <= n; ++i) {
    const RatFunc Bi = bernstein(n, i) * RatFunc(v[static_cast<std::size_t>(i)]);
    den = den + Bi;
    for (std::size_t k = 0; k < b.dimension(); ++k)
      num[k] = num[k] + Bi * RatFunc(b.points()[static_cast<std::size_t>(i)][k]);
  }
  for (auto& c : num) c = c / den;
  return num;
}

// int_0^1 f for a polynomial f (a RatFunc with constant denominator), exactly.
Rational integrate_poly(const RatFunc& f) {
  const Poly num = f.num(), den = f.den();
  EXPECT_LE(den.degree(), 0);
  Rational s(0);
  for (long k = 0; k <= num.degree(); ++k) s = s + Rational(num.coeff(k), Integer(k + 1));
  return s / Rational(den.coeff(0));
}

// A = int (1-t)^2 |p'|^2, B = int 2t(1-t) |p'|^2, C = int t^2 |p'|^2 by exact
// integration of the power-basis polynomials (integral curves).
BezierMoments oracle_moments(const BezierCurve& b) {
  RatFunc sq(0);
  for (const auto& c : oracle_components(b)) sq = sq + c.derivative() * c.derivative();
  const RatFunc t = RatFunc::t(), one_minus = RatFunc(1) - t;
  return {integrate_poly(sq * one_minus * one_minus), integrate_poly(sq * RatFunc(2) * t * one_minus),
          integrate_poly(sq * t * t)};
}

// de Casteljau in ball arithmetic in homogeneous coordinates (v_i p_i, v_i),
// then divided: the point of the rational Bezier curve with weights w at t.
std::vector<Ball> eval_bezier(const BezierCurve& b, const std::vector<Ball>& w, const Ball& t, long prec) {
  const std::size_t n1 = b.points().size(), d = b.dimension();
  std::vector<std::vector<Ball>> h(n1, std::vector<Ball>(d + 1));
  for (std::size_t i = 0; i < n1; ++i) {
    for (std::size_t k = 0; k < d; ++k) {
      Ball x(b.points()[i][k], prec);
      arb_mul(h[i][k].get(), x.get(), w[i].get(), prec);
    }
    h[i][d] = w[i];
  }
  Ball one_minus;
  arb_sub_si(one_minus.get(), t.get(), 1, prec);
  arb_neg(one_minus.get(), one_minus.get());
  for (std::size_t r = 1; r < n1; ++r)
    for (std::size_t i = 0; i + r < n1; ++i)
      for (std::size_t k = 0; k <= d; ++k) {
        Ball a, c;
        arb_mul(a.get(), h[i][k].get(), one_minus.get(), prec);
        arb_mul(c.get(), h[i + 1][k].get(), t.get(), prec);
        arb_add(h[i][k].get(), a.get(), c.get(), prec);
      }
  std::vector<Ball> out(d);
  for (std::size_t k = 0; k < d; ++k) arb_div(out[k].get(), h[0][k].get(), h[0][d].get(), prec);
  return out;
}

Ball pi_ball(long prec) {
  Ball p;
  arb_const_pi(p.get(), prec);
  return p;
}

}  // namespace

// Eq. (21) (Bernstein products) equals -A and C of docs/math.md section 2 computed
// by exact integration in the power basis: checks the sign and normalisation
// conventions (P = -A, Q = C on [0, 1], sigma = |p'|) and B.
TEST(Bezier, EquationTwentyOneMatchesExactIntegration) {
  std::mt19937_64 rng(21);
  for (long it = 0; it < iterations(4); ++it)
    for (long n = 1; n <= 7; ++n)
      for (std::size_t dim : {2u, 3u, 4u}) {
        const BezierCurve b = random_bezier(rng, n, dim, false);
        const BezierMoments m = bezier_moments(b), o = oracle_moments(b);
        EXPECT_EQ(m.A, o.A) << b.str();
        EXPECT_EQ(m.B, o.B) << b.str();
        EXPECT_EQ(m.C, o.C) << b.str();
        EXPECT_GT(m.A.sign(), 0);
        EXPECT_GT(m.C.sign(), 0);
      }
}

// The power-basis conversion is exact for integral and rational curves.
TEST(Bezier, ToCurveEqualsBernsteinSum) {
  std::mt19937_64 rng(4);
  for (long it = 0; it < iterations(3); ++it)
    for (long n = 1; n <= 8; ++n)
      for (bool rational : {false, true}) {
        const BezierCurve b = random_bezier(rng, n, 2 + static_cast<std::size_t>(n % 3), rational);
        const Curve c = b.to_curve();
        const auto o = oracle_components(b);
        ASSERT_EQ(c.components().size(), o.size());
        for (std::size_t k = 0; k < o.size(); ++k) EXPECT_EQ(c.components()[k], o[k]) << b.str();
        // end points interpolate p_0 and p_n
        for (std::size_t k = 0; k < o.size(); ++k) {
          EXPECT_EQ(c.components()[k](Rational(0)), b.points().front()[k]);
          EXPECT_EQ(c.components()[k](Rational(1)), b.points().back()[k]);
        }
      }
}

// The exact alpha is the root in (0, 1) of P (1 - a)^2 + Q a^2 (eq. 22),
// checked exactly in Q(sqrt c); its polynomial form has the same root.
TEST(Bezier, ExactAlphaSolvesEquationTwentyTwo) {
  std::mt19937_64 rng(22);
  Options o;
  o.digits = 10;
  for (long it = 0; it < iterations(2); ++it)
    for (long n = 1; n <= 5; ++n) {
      const BezierCurve b = random_bezier(rng, n, n % 2 ? 2 : 3, false);
      const BezierResult r = bezier_optimal(b, o);
      ASSERT_TRUE(r.exact);
      const QuadraticSurd& a = *r.alpha_exact;
      const QuadraticSurd one(Rational(1)), om = one - a;
      const QuadraticSurd f = QuadraticSurd(*r.P_exact) * om * om + QuadraticSurd(*r.Q_exact) * a * a;
      EXPECT_TRUE(f.is_rational() && f.rational().is_zero()) << b.str() << ": " << f.str();
      EXPECT_EQ(a.sign(), 1);
      EXPECT_EQ(om.sign(), 1);
      EXPECT_EQ(sign_at(r.alpha_algebraic->poly(), *r.alpha_algebraic), 0);
      EXPECT_TRUE(r.alpha.contains(r.alpha_algebraic->to_ball(300)));
      // the new weights, exactly
      const std::size_t n1 = static_cast<std::size_t>(n) + 1;
      ASSERT_EQ(r.weights_exact.size(), n1);
      for (std::size_t i = 0; i < n1; ++i) {
        QuadraticSurd w(Rational(1));
        for (std::size_t k = 0; k < i; ++k) w = w * om;
        for (std::size_t k = i; k + 1 < n1; ++k) w = w * a;
        EXPECT_EQ((w - r.weights_exact[i]).sign(), 0);
        EXPECT_TRUE(r.weights[i].contains(w.to_ball(300)));
      }
    }
}

// Must show: alpha of eq. (22) equals the alpha of the general optimal
// Moebius map (docs/math.md section 2) for the parametric speed, for several
// degrees and dimensions; so do mu, u before and u after.
TEST(Bezier, ExactAlphaInsideGeneralMoebiusBall) {
  std::mt19937_64 rng(2022);
  Options o;
  o.digits = 12;
  for (long it = 0; it < iterations(1); ++it)
    for (long n = 2; n <= 6; ++n)
      for (std::size_t dim : {2u, 3u}) {
        std::uniform_int_distribution<long> small(-3, 3);
        std::vector<std::vector<Rational>> pts(static_cast<std::size_t>(n + 1));
        for (auto& p : pts)
          for (std::size_t k = 0; k < dim; ++k) p.emplace_back(small(rng), 1 + (small(rng) + 3) % 3);
        const BezierCurve b(pts);
        const BezierResult r = bezier_optimal(b, o);
        const MoebiusResult m = moebius_optimal(b.to_curve(), SpeedKind::Parametric, o);
        const Ball exact = r.alpha_exact->to_ball(400);
        EXPECT_TRUE(m.alpha.at(0).contains(exact)) << b.str() << ": alpha " << r.alpha_exact->str() << " = "
                                                   << exact.str(30) << " vs " << m.alpha[0].str(30);
        EXPECT_TRUE(r.alpha.contains(exact));
        // P = -A and Q = C of the general integrals
        EXPECT_TRUE(m.integrals[0].A.contains(-*r.P_exact)) << b.str();
        EXPECT_TRUE(m.integrals[0].C.contains(*r.Q_exact)) << b.str();
        EXPECT_TRUE(m.integrals[0].L.contains(*r.mean_square_exact)) << b.str();
        EXPECT_TRUE(arb_overlaps(r.mu.get(), m.mu.get()));
        EXPECT_TRUE(arb_overlaps(r.u_before.get(), m.u_before.get()));
        EXPECT_TRUE(arb_overlaps(r.u_after.get(), m.u_after.get()));
        for (const Ball* x : {&r.mu, &r.u_before, &r.u_after, &r.alpha}) EXPECT_TRUE(x->meets_digits(o.digits + 1));
      }
}

// Must show: the rational quadratic Bezier of the quarter circle (weights
// 1, 1, 2: the curve ((1-t^2)/(1+t^2), 2t/(1+t^2))) reaches the uniformity of
// docs/math.md section 6 after its optimal reparameterization; P = 2 - pi,
// Q = pi/2 - 1, alpha = 2 - sqrt 2 in closed form. Reversed, scaled and
// translated copies reach the same u.
TEST(Bezier, QuarterCircleReachesReferenceUniformity) {
  Options o;
  o.digits = 25;
  const long prec = 300;
  struct Case { const char* control; const char* weights; long radius; bool reversed; };
  for (const Case& cs : {Case{"[[1,0],[1,1],[0,1]]", "[1,1,2]", 1, false},
                         Case{"[[1,0],[1,1],[0,1]]", "[2,1,1]", 1, true},
                         Case{"[[5,1],[5,3],[3,3]]", "[1,1,2]", 2, false}}) {
    const BezierCurve b = BezierCurve::parse(cs.control, cs.weights);
    const BezierResult r = bezier_optimal(b, o);
    EXPECT_FALSE(r.exact);
    EXPECT_TRUE(test_support::contains_ref(r.u_after, "0.9977912002415711604419615")) << r.u_after.str(30);
    EXPECT_TRUE(test_support::contains_ref(r.u_before, "0.9597808564432393298507263")) << r.u_before.str(30);
    // mu = radius * pi / 2
    Ball mu = pi_ball(prec);
    arb_mul_si(mu.get(), mu.get(), cs.radius, prec);
    arb_mul_2exp_si(mu.get(), mu.get(), -1);
    EXPECT_TRUE(r.mu.contains(mu)) << r.mu.str(30);
    if (cs.radius == 1) {
      // A = pi - 2 and C = pi/2 - 1 (swapped for the reversed parameterization)
      Ball A = pi_ball(prec), C = pi_ball(prec), a;
      arb_sub_si(A.get(), A.get(), 2, prec);
      arb_mul_2exp_si(C.get(), A.get(), -1);
      if (cs.reversed) std::swap(A, C);
      arb_neg(A.get(), A.get());
      EXPECT_TRUE(r.P.contains(A)) << r.P.str(30);
      EXPECT_TRUE(r.Q.contains(C)) << r.Q.str(30);
      arb_sqrt_ui(a.get(), 2, prec);
      if (cs.reversed) arb_sub_si(a.get(), a.get(), 1, prec);  // sqrt 2 - 1
      else { arb_neg(a.get(), a.get()); arb_add_si(a.get(), a.get(), 2, prec); }  // 2 - sqrt 2
      EXPECT_TRUE(r.alpha.contains(a)) << r.alpha.str(30);
    }
    for (const Ball* x : {&r.P, &r.Q, &r.alpha, &r.mu, &r.u_before, &r.u_after}) EXPECT_TRUE(x->meets_digits(26));
  }
}

// The reparameterized rational Bezier curve (same control points, weights
// v_i (1-alpha)^i alpha^(n-i)) is p o m with m(s) = (1-a)s / ((1-a)s + a(1-s)):
// evaluated at random rational s, both enclosures overlap; with the weights in
// the wrong order they are disjoint somewhere (the check has power).
TEST(Bezier, NewWeightsGiveTheReparameterizedCurve) {
  std::mt19937_64 rng(7);
  Options o;
  o.digits = 12;
  const long prec = 256;
  for (long it = 0; it < iterations(1); ++it)
    for (long n = 2; n <= 5; ++n)
      for (bool rational : {false, true}) {
        const BezierCurve b = random_bezier(rng, n, n % 2 ? 3 : 2, rational);
        const BezierResult r = bezier_optimal(b, o);
        std::vector<Ball> v;
        for (const auto& x : b.weights()) v.emplace_back(x, prec);
        std::vector<Ball> swapped(r.weights.rbegin(), r.weights.rend());
        for (std::size_t i = 0; i < swapped.size(); ++i) {
          Ball vi(b.weights()[i], prec), vr(b.weights()[swapped.size() - 1 - i], prec);
          arb_div(swapped[i].get(), swapped[i].get(), vr.get(), prec);
          arb_mul(swapped[i].get(), swapped[i].get(), vi.get(), prec);
        }
        bool swapped_differs = false;
        for (int k = 0; k < 6; ++k) {
          std::uniform_int_distribution<long> num(1, 99);
          const Rational s(num(rng), 100);
          const Ball sb(s, prec);
          // m(s)
          Ball one_a, as, den, t;
          arb_sub_si(one_a.get(), r.alpha.get(), 1, prec);
          arb_neg(one_a.get(), one_a.get());
          arb_mul(t.get(), one_a.get(), sb.get(), prec);
          Ball one_s(Rational(1) - s, prec);
          arb_mul(as.get(), r.alpha.get(), one_s.get(), prec);
          arb_add(den.get(), t.get(), as.get(), prec);
          arb_div(t.get(), t.get(), den.get(), prec);
          const auto lhs = eval_bezier(b, r.weights, sb, prec);
          const auto rhs = eval_bezier(b, v, t, prec);
          const auto bad = eval_bezier(b, swapped, sb, prec);
          for (std::size_t d = 0; d < lhs.size(); ++d) {
            EXPECT_TRUE(arb_overlaps(lhs[d].get(), rhs[d].get())) << b.str() << " at s = " << s.str();
            if (!arb_overlaps(bad[d].get(), rhs[d].get())) swapped_differs = true;
          }
        }
        EXPECT_TRUE(swapped_differs) << b.str();
      }
}

// A rational Bezier curve with all weights equal is the integral curve: the
// certified P, Q and alpha contain the exact ones; P (1-a)^2 + Q a^2 contains 0.
TEST(Bezier, EqualWeightsMatchIntegralCurve) {
  std::mt19937_64 rng(99);
  Options o;
  o.digits = 15;
  for (long n = 2; n <= 4; ++n) {
    const BezierCurve b = random_bezier(rng, n, 2, false);
    const BezierCurve bw(b.points(), std::vector<Rational>(b.points().size(), Rational(3, 2)));
    const BezierResult e = bezier_optimal(b, o), q = bezier_optimal(bw, o);
    EXPECT_TRUE(e.exact);
    EXPECT_FALSE(q.exact);
    EXPECT_TRUE(q.P.contains(*e.P_exact));
    EXPECT_TRUE(q.Q.contains(*e.Q_exact));
    EXPECT_TRUE(q.alpha.contains(e.alpha_exact->to_ball(300)));
    const long prec = 256;
    Ball om, f, g;
    arb_sub_si(om.get(), q.alpha.get(), 1, prec);
    arb_mul(f.get(), om.get(), om.get(), prec);
    arb_mul(f.get(), f.get(), q.P.get(), prec);
    arb_mul(g.get(), q.alpha.get(), q.alpha.get(), prec);
    arb_mul(g.get(), g.get(), q.Q.get(), prec);
    arb_add(f.get(), f.get(), g.get(), prec);
    EXPECT_TRUE(f.contains(Rational(0)));
    // weights scale by 3/2
    for (std::size_t i = 0; i < e.weights.size(); ++i) {
      Ball w;
      Ball s(Rational(3, 2), prec);
      arb_mul(w.get(), e.weights[i].get(), s.get(), prec);
      EXPECT_TRUE(arb_overlaps(w.get(), q.weights[i].get()));
    }
  }
}

// A straight segment (also degree-elevated) has constant speed: alpha = 1/2
// exactly and u = 1 before and after; the uniformity before equals the one of
// uniformity() for the parametric speed.
TEST(Bezier, LineAndUniformityBefore) {
  Options o;
  for (const char* ctrl : {"[[0,0],[3,4]]", "[[0,0],[1,1],[2,2],[3,3]]", "[[1,2,3],[2,3,4],[3,4,5]]"}) {
    const BezierResult r = bezier_optimal(BezierCurve::parse(ctrl), o);
    ASSERT_TRUE(r.alpha_exact->is_rational());
    EXPECT_EQ(r.alpha_exact->rational(), Rational(1, 2));
    EXPECT_TRUE(r.u_before.contains(Rational(1)));
    EXPECT_TRUE(r.u_after.contains(Rational(1)));
  }
  const BezierCurve b = BezierCurve::parse("[[0,0],[0,1],[3,1],[2,-1]]");
  const BezierResult r = bezier_optimal(b, o);
  const UniformityResult u = uniformity(b.to_curve(), SpeedKind::Parametric, o);
  EXPECT_TRUE(arb_overlaps(r.u_before.get(), u.u.get()));
  EXPECT_TRUE(u.mean_square.contains(*r.mean_square_exact));
  EXPECT_TRUE(arb_gt(r.u_after.get(), r.u_before.get()));
}

TEST(QuadraticSurd, SquareFactorsArePulledOut) {
  const QuadraticSurd s = QuadraticSurd::make(Rational(0), Rational(1), Rational(12));
  EXPECT_EQ(s.c(), Integer(3));
  EXPECT_EQ(s.y(), Rational(2));
  EXPECT_TRUE(QuadraticSurd::make(Rational(1), Rational(1), Rational(9, 4)).is_rational());
  EXPECT_EQ(QuadraticSurd::make(Rational(1), Rational(1), Rational(9, 4)).rational(), Rational(5, 2));
  // sqrt(3/8) = sqrt(24)/8 = sqrt(6)/4
  const QuadraticSurd t = QuadraticSurd::make(Rational(0), Rational(1), Rational(3, 8));
  EXPECT_EQ(t.c(), Integer(6));
  EXPECT_EQ(t.y(), Rational(1, 4));
  EXPECT_THROW(QuadraticSurd::make(Rational(0), Rational(1), Rational(-2)), InvalidArgument);
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<long> d(1, 5000);
  for (long it = 0; it < iterations(200); ++it) {
    const Rational r(d(rng) * d(rng), d(rng));
    const QuadraticSurd q = QuadraticSurd::make(Rational(0), Rational(1), r);
    if (q.is_rational()) {
      EXPECT_EQ(q.rational() * q.rational(), r);
      continue;
    }
    // y^2 c = r exactly, c has no square factor below 1000
    EXPECT_EQ(q.y() * q.y() * Rational(q.c()), r);
    for (long p = 2; p < 1000; ++p) {
      Integer p2(p * p);
      EXPECT_FALSE(fmpz_divisible(q.c().get(), p2.get())) << q.c().str();
    }
    // the ball contains sqrt(r)
    Ball b = q.to_ball(200), e(r, 400);
    arb_sqrt(e.get(), e.get(), 400);
    EXPECT_TRUE(arb_overlaps(b.get(), e.get()));
  }
}

TEST(QuadraticSurd, ArithmeticSignAndPrinting) {
  // (-33 + 2 sqrt 330) / 7: the form of the example
  const QuadraticSurd a = QuadraticSurd::make(Rational(-33, 7), Rational(2, 7), Rational(330));
  EXPECT_EQ(a.a(), Integer(-33));
  EXPECT_EQ(a.b(), Integer(2));
  EXPECT_EQ(a.c(), Integer(330));
  EXPECT_EQ(a.d(), Integer(7));
  EXPECT_EQ(a.str(Format::Text), "(-33 + 2*sqrt(330))/7");
  EXPECT_EQ(a.str(Format::Latex), "\\frac{-33 + 2 \\sqrt{330}}{7}");
  EXPECT_EQ(a.str(Format::Maple), "(-33 + 2*sqrt(330))/7");
  EXPECT_EQ(QuadraticSurd::make(Rational(0), Rational(-1), Rational(2)).str(), "-sqrt(2)");
  EXPECT_EQ(QuadraticSurd::make(Rational(1, 2), Rational(-1, 3), Rational(5)).str(), "(3 - 2*sqrt(5))/6");
  EXPECT_EQ(QuadraticSurd(Rational(3, 4)).str(), "3/4");
  std::mt19937_64 rng(6);
  for (long it = 0; it < iterations(100); ++it) {
    const QuadraticSurd p = QuadraticSurd::make(random_rational(rng, 9), random_rational(rng, 9), Rational(7));
    const QuadraticSurd q = QuadraticSurd::make(random_rational(rng, 9), random_rational(rng, 9), Rational(7));
    const long prec = 200;
    Ball bp = p.to_ball(prec), bq = q.to_ball(prec), x;
    arb_mul(x.get(), bp.get(), bq.get(), prec);
    EXPECT_TRUE(arb_overlaps(x.get(), (p * q).to_ball(prec).get()));
    arb_add(x.get(), bp.get(), bq.get(), prec);
    EXPECT_TRUE(arb_overlaps(x.get(), (p + q).to_ball(prec).get()));
    arb_sub(x.get(), bp.get(), bq.get(), prec);
    EXPECT_TRUE(arb_overlaps(x.get(), (p - q).to_ball(prec).get()));
    const int s = (p - q).sign();
    if (s > 0) EXPECT_TRUE(x.certainly_positive());
    if (s < 0) EXPECT_TRUE(x.certainly_negative());
    if (s == 0) EXPECT_TRUE(x.contains(Rational(0)));
  }
  EXPECT_THROW(QuadraticSurd::make(Rational(0), Rational(1), Rational(2)) *
                   QuadraticSurd::make(Rational(0), Rational(1), Rational(3)),
               InvalidArgument);
}

TEST(Bezier, ParsesExactRationals) {
  const BezierCurve b = BezierCurve::parse(" [ [1/3, -2], (0.25 ,1e-3) ,[ -7/14,+5] ] ", "[1, 0.5, 2/3]");
  ASSERT_EQ(b.degree(), 2);
  ASSERT_EQ(b.dimension(), 2u);
  EXPECT_EQ(b.points()[0][0], Rational(1, 3));
  EXPECT_EQ(b.points()[0][1], Rational(-2));
  EXPECT_EQ(b.points()[1][0], Rational(1, 4));
  EXPECT_EQ(b.points()[1][1], Rational(1, 1000));
  EXPECT_EQ(b.points()[2][0], Rational(-1, 2));
  EXPECT_EQ(b.weights()[1], Rational(1, 2));
  EXPECT_EQ(b.weights()[2], Rational(2, 3));
  EXPECT_TRUE(b.is_rational());
  EXPECT_FALSE(BezierCurve::parse("[[0,0],[1,1]]").is_rational());
}

TEST(Bezier, RejectsBadInput) {
  EXPECT_THROW(BezierCurve::parse("[[0,0]]"), InvalidArgument);                     // too few points
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1,1]]"), InvalidArgument);             // mixed dimensions
  EXPECT_THROW(BezierCurve::parse("[[0],[1]]"), InvalidArgument);                   // dimension 1
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1]]", "[1,0]"), InvalidArgument);      // zero weight
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1]]", "[1,-1/2]"), InvalidArgument);   // negative weight
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1]]", "[1,2,3]"), InvalidArgument);    // wrong count
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1],[2,2]]", "[1]"), InvalidArgument);  // wrong count
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1],[2,2]]", "", 2), InvalidArgument);  // too many points
  for (const char* bad : {"", "  ", "[", "[]", "[[]]", "[[0,0],[1,x]]", "[[0,0],[1,1]]]", "[[0,0],[1,1]",
                          "[[0,0] [1,1]]", "[[0,0],[1,1/0]]", "[[0,0],[1,,1]]", "[[0,0],[1,1]] x", "0,0,1,1",
                          "[[0,0],[1,1.2.3]]", "[[0,0],[1,sin(1)]]"}) {
    EXPECT_THROW(BezierCurve::parse(bad), ParseError) << bad;
  }
  try {
    BezierCurve::parse("[[0,0],[1,x]]");
    FAIL();
  } catch (const ParseError& e) {
    EXPECT_EQ(e.column(), 11u);
    EXPECT_NE(std::string(e.what()).find("control points"), std::string::npos);
  }
  EXPECT_THROW(BezierCurve::parse("[[0,0],[1,1]]", "[1,y]"), ParseError);
  EXPECT_THROW(BezierCurve::parse("[[2,3],[2,3],[2,3]]").to_curve(), DomainError);  // constant
  Options o;
  o.max_degree = 3;
  EXPECT_THROW(bezier_optimal(BezierCurve::parse("[[0,0],[1,1],[2,0],[3,1],[4,0]]"), o), InvalidArgument);
  EXPECT_THROW(bezier_moments(BezierCurve::parse("[[0,0],[1,1]]", "[1,2]")), InvalidArgument);
}
