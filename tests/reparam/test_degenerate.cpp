// Degenerate but valid curves get correct answers: lines, cusps, circles,
// zeros of the speed exactly at 0 and 1 or 10^-30 apart, poles 10^-30
// outside [0, 1], hundred-digit coefficients, degree 500. Every expected
// value is an independent closed form evaluated with Arb (no quadrature):
// for a graph (t, y(t)) the angular mean mu is the total variation of the
// tangent angle atan y', and for a polynomial curve int |p'|^2 is an exact
// rational; invariances (scaling, translation) compare two computations.
#include <gtest/gtest.h>

#include <arb.h>

#include <string>
#include <vector>

#include "support/reference.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

constexpr long kPrec = 512;  // working precision of the oracles

Ball exact(const Rational& q) { return Ball(q, kPrec); }
Ball ratio(long p, long q) { return exact(Rational(p, q)); }
Ball atan_of(const Ball& x) {
  Ball r;
  arb_atan(r.get(), x.get(), kPrec);
  return r;
}
Ball add(const Ball& a, const Ball& b) { Ball r; arb_add(r.get(), a.get(), b.get(), kPrec); return r; }
Ball sub(const Ball& a, const Ball& b) { Ball r; arb_sub(r.get(), a.get(), b.get(), kPrec); return r; }
Ball mul(const Ball& a, const Ball& b) { Ball r; arb_mul(r.get(), a.get(), b.get(), kPrec); return r; }
Ball div(const Ball& a, const Ball& b) { Ball r; arb_div(r.get(), a.get(), b.get(), kPrec); return r; }
Ball abs_of(const Ball& a) { Ball r; arb_abs(r.get(), a.get()); return r; }
Ball sqrt_of(const Ball& a) { Ball r; arb_sqrt(r.get(), a.get(), kPrec); return r; }

/// The certified ball `got` and the oracle `want` (a tiny ball) overlap:
/// since both contain the true value, a miss proves a wrong number.
::testing::AssertionResult agrees(const Ball& got, const Ball& want) {
  if (!got.is_finite()) return ::testing::AssertionFailure() << "not finite: " << got.str(30);
  if (arb_overlaps(got.get(), want.get())) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << got.str(40) << " misses " << want.str(40);
}

/// Evaluates the polynomial with rational coefficients c_0 + c_1 x + ... at a ball.
Ball eval(const std::vector<Rational>& c, const Ball& x) {
  Ball r(0);
  for (std::size_t i = c.size(); i-- > 0;) r = add(mul(r, x), exact(c[i]));
  return r;
}

Rational pow10(long k) { return Rational::parse("1e" + std::to_string(k)); }

}  // namespace

// ---- straight lines ------------------------------------------------------------------

TEST(Degenerate, LinesHaveAngularUniformityExactlyOne) {
  for (const char* line : {"(t, 2t)", "(t^2, 2t^2 + 1)", "((t^3+t)/(t^2+1), 5)", "(1 - t, 3 - 3t, t - 1)"}) {
    const Curve c = parse_curve(line);
    const UniformityResult u = uniformity(c, SpeedKind::Angular);
    EXPECT_TRUE(u.identically_zero) << line;
    EXPECT_TRUE(u.u.contains(Rational(1)) && u.u.is_exact()) << line;
    EXPECT_TRUE(u.mu.certainly_zero()) << line;
    const RadicalResult r = radical(c, SpeedKind::Angular);
    EXPECT_TRUE(r.identically_zero) << line;
    EXPECT_TRUE(r.u_after.contains(Rational(1))) << line;
    const MoebiusResult m = moebius_optimal(c, SpeedKind::Angular);
    EXPECT_TRUE(m.u_after.contains(Rational(1))) << line;
  }
}

// (t^2, 2t^2 + 1): |p'| = 2 sqrt(5) t, so mu = sqrt 5, int |p'|^2 = 20/3 and
// u = 3/4 exactly; the radical map t = sqrt(s) makes it uniform: u = 1.
TEST(Degenerate, LineWithAZeroOfParametricSpeedIsMadeUniformByTheRadicalMethod) {
  const Curve c = parse_curve("(t^2, 2t^2 + 1)");
  const UniformityResult u = uniformity(c, SpeedKind::Parametric);
  ASSERT_EQ(u.zeros.size(), 1u);
  EXPECT_EQ(u.zeros[0].t.rational(), Rational(0));
  EXPECT_EQ(u.zeros[0].multiplicity, 1);
  EXPECT_TRUE(agrees(u.mu, sqrt_of(Ball(5))));
  EXPECT_TRUE(agrees(u.mean_square, ratio(20, 3)));
  EXPECT_TRUE(agrees(u.u, ratio(3, 4)));
  const RadicalResult r = radical(c, SpeedKind::Parametric);
  ASSERT_EQ(r.pieces(), 1u);
  EXPECT_EQ(r.T[0].multiplicity, 1);
  EXPECT_TRUE(agrees(r.u_radical, Ball(1)));
  EXPECT_TRUE(agrees(r.u_after, Ball(1)));
}

// ---- the cusp (t^2, t^3) ---------------------------------------------------------------

// Angular: omega = 6/(4 + 9t^2) after cancelling t^2: finite, no zero.
// mu = atan(3/2); int omega^2 = (3/2) (3/13 + atan(3/2)/2).
TEST(Degenerate, CuspAngularSpeedIsFiniteAfterCancellation) {
  const UniformityResult u = uniformity(parse_curve("(t^2, t^3)"), SpeedKind::Angular);
  EXPECT_TRUE(u.zeros.empty());
  const Ball a = atan_of(ratio(3, 2));
  EXPECT_TRUE(agrees(u.mu, a));
  const Ball ms = mul(ratio(3, 2), add(ratio(3, 13), div(a, Ball(2))));
  EXPECT_TRUE(agrees(u.mean_square, ms));
  EXPECT_TRUE(agrees(u.u, div(mul(a, a), ms)));
  const RadicalResult r = radical(parse_curve("(t^2, t^3)"), SpeedKind::Angular);
  EXPECT_TRUE(agrees(r.mu, a));
}

// Parametric: |p'| = t sqrt(4 + 9t^2), zero of multiplicity 1 at 0.
// mu = (13^(3/2) - 8)/27, int |p'|^2 = 47/15; phi: t = sqrt(s) gives
// q = (s, s^(3/2)) with int |q'|^2 = 17/8, so u(p o phi) = 8 mu^2 / 17.
TEST(Degenerate, CuspParametricZeroIsLiftedByTheRadicalMethod) {
  const Curve c = parse_curve("(t^2, t^3)");
  const Ball mu = div(sub(mul(Ball(13), sqrt_of(Ball(13))), Ball(8)), Ball(27));
  const UniformityResult u = uniformity(c, SpeedKind::Parametric);
  ASSERT_EQ(u.zeros.size(), 1u);
  EXPECT_EQ(u.zeros[0].t.rational(), Rational(0));
  EXPECT_EQ(u.zeros[0].multiplicity, 1);
  EXPECT_TRUE(agrees(u.mu, mu));
  EXPECT_TRUE(agrees(u.mean_square, ratio(47, 15)));
  const RadicalResult r = radical(c, SpeedKind::Parametric);
  ASSERT_EQ(r.pieces(), 1u);
  EXPECT_EQ(r.root_index(0), 2);
  EXPECT_TRUE(agrees(r.u_radical, div(mul(Ball(8), mul(mu, mu)), Ball(17))));
}

// ---- circles -------------------------------------------------------------------------

// p = c + R ((1 - k^2 t^2)/(1 + k^2 t^2), 2kt/(1 + k^2 t^2)), k = 3 (more than a
// half circle): omega = 2k/(1 + k^2 t^2), |p'| = R omega.
// mu = 2 atan k, int omega^2 = 2k (k/(1 + k^2) + atan k).
TEST(Degenerate, CircleArcMatchesClosedForms) {
  const Curve c = parse_curve("(1 + 5(1 - 9t^2)/(1 + 9t^2), -2 + 5*6t/(1 + 9t^2))");
  const Ball at = atan_of(Ball(3));
  const Ball mu = mul(Ball(2), at), ms = mul(Ball(6), add(ratio(3, 10), at));
  const UniformityResult a = uniformity(c, SpeedKind::Angular);
  EXPECT_TRUE(a.zeros.empty());
  EXPECT_TRUE(agrees(a.mu, mu));
  EXPECT_TRUE(agrees(a.mean_square, ms));
  const UniformityResult p = uniformity(c, SpeedKind::Parametric);
  EXPECT_TRUE(agrees(p.mu, mul(Ball(5), mu)));
  EXPECT_TRUE(agrees(p.mean_square, mul(Ball(25), ms)));
  EXPECT_TRUE(agrees(p.u, a.u));  // a circle's two speeds are proportional
  // Quarter circle: the docs/math.md section 6 values (alpha* = 2 - sqrt 2).
  const MoebiusResult m = moebius_optimal(parse_curve("((1-t^2)/(1+t^2), 2t/(1+t^2))"), SpeedKind::Angular);
  EXPECT_TRUE(agrees(m.alpha.at(0), sub(Ball(2), sqrt_of(Ball(2)))));
  EXPECT_TRUE(test_support::contains_ref(m.u_after, "0.9977912002415711604419615"));
}

// ---- zeros of the speed exactly at 0 and 1 -----------------------------------------------

// y = t^3 (1 - t)^3: y'' = 6t(1 - t)(5t^2 - 5t + 1) vanishes at 0, 1 and
// (5 -+ sqrt 5)/10; y' = 3t^2 (1-t)^2 (1-2t) is antisymmetric about 1/2, so
// the tangent angle goes 0 -> a -> -a -> 0 with a = atan y'(t1): mu = 4|a|.
TEST(Degenerate, ZerosExactlyAtBothEnds) {
  const Curve c = parse_curve("(t, t^3 (1 - t)^3)");
  const UniformityResult u = uniformity(c, SpeedKind::Angular);
  ASSERT_EQ(u.zeros.size(), 4u);
  EXPECT_TRUE(u.zeros.front().t.is_rational());
  EXPECT_EQ(u.zeros.front().t.rational(), Rational(0));
  EXPECT_TRUE(u.zeros.back().t.is_rational());
  EXPECT_EQ(u.zeros.back().t.rational(), Rational(1));
  const Ball s5 = sqrt_of(Ball(5));
  const Ball t1 = div(sub(Ball(5), s5), Ball(10)), t2 = div(add(Ball(5), s5), Ball(10));
  EXPECT_TRUE(agrees(u.zeros[1].t.to_ball(kPrec), t1));
  EXPECT_TRUE(agrees(u.zeros[2].t.to_ball(kPrec), t2));
  for (const auto& z : u.zeros) EXPECT_EQ(z.multiplicity, 1);
  const Ball one_minus = sub(Ball(1), t1);
  const Ball dy = mul(mul(Ball(3), mul(mul(t1, t1), mul(one_minus, one_minus))), sub(Ball(1), mul(Ball(2), t1)));
  EXPECT_TRUE(agrees(u.mu, mul(Ball(4), abs_of(atan_of(dy)))));
  const RadicalResult r = radical(c, SpeedKind::Angular);
  EXPECT_EQ(r.T.front().multiplicity, 1);
  EXPECT_EQ(r.T.back().multiplicity, 1);
  EXPECT_TRUE(agrees(r.mu, u.mu));
  EXPECT_TRUE(r.u_after.certainly_positive());
}

// ---- zeros 10^-30 apart ---------------------------------------------------------------------

// y'' = (t - a)(t - b), a = 1/2, b = 1/2 + 10^-30, y'(0) = 0: the tangent
// angle atan y' is monotone between the zeros, so
// mu = |atan y'(a)| + |atan y'(b) - atan y'(a)| + |atan y'(1) - atan y'(b)|.
TEST(Degenerate, RationalZerosTenToTheMinusThirtyApart) {
  const Rational a(1, 2), b = Rational(1, 2) + pow10(-30);
  // y = t^4/12 - (a+b) t^3/6 + ab t^2/2
  const std::string y = "t^4/12 - (" + (a + b).str() + ")t^3/6 + (" + (a * b).str() + ")t^2/2";
  const Curve c = parse_curve("(t, " + y + ")");
  const UniformityResult u = uniformity(c, SpeedKind::Angular);
  ASSERT_EQ(u.zeros.size(), 2u);
  EXPECT_TRUE(u.zeros[0].t.is_rational() && u.zeros[0].t.rational() == a);
  EXPECT_TRUE(u.zeros[1].t.is_rational() && u.zeros[1].t.rational() == b);
  const std::vector<Rational> dy{Rational(0), a * b, (a + b) * Rational(-1, 2), Rational(1, 3)};
  const Ball ya = atan_of(eval(dy, exact(a))), yb = atan_of(eval(dy, exact(b))), y1 = atan_of(eval(dy, Ball(1)));
  const Ball mu = add(add(abs_of(ya), abs_of(sub(yb, ya))), abs_of(sub(y1, yb)));
  EXPECT_TRUE(agrees(u.mu, mu));
  // Two zeros in a row get a breakpoint between them (docs/math.md section 4).
  const RadicalResult r = radical(c, SpeedKind::Angular);
  EXPECT_TRUE(agrees(r.mu, mu));
  bool between = false;
  for (const auto& t : r.T) between = between || (RealAlgebraic(a) < t.t && t.t < RealAlgebraic(b));
  EXPECT_TRUE(between);
}

// y'' = (t - 1/2)^2 - 2 * 10^-62: irrational zeros 1/2 -+ sqrt(2) 10^-31.
TEST(Degenerate, IrrationalZerosTenToTheMinusThirtyApart) {
  const Rational e = Rational(2) * pow10(-62);
  // y' = (t-1/2)^3/3 - e t + 1/24, y = (t-1/2)^4/12 - e t^2/2 + t/24
  const Curve c = parse_curve("(t, (t - 1/2)^4/12 - (" + e.str() + ")t^2/2 + t/24)");
  const UniformityResult u = uniformity(c, SpeedKind::Angular);
  ASSERT_EQ(u.zeros.size(), 2u);
  EXPECT_FALSE(u.zeros[0].t.is_rational());
  EXPECT_TRUE(u.zeros[0].t < u.zeros[1].t);
  const Ball d = mul(sqrt_of(Ball(2)), exact(pow10(-31)));
  EXPECT_TRUE(agrees(u.zeros[0].t.to_ball(kPrec), sub(ratio(1, 2), d)));
  EXPECT_TRUE(agrees(u.zeros[1].t.to_ball(kPrec), add(ratio(1, 2), d)));
  for (const auto& z : u.zeros) EXPECT_EQ(z.multiplicity, 1);
}

// A pole 10^-30 outside [0, 1] is valid; 10^-30 inside it is not.
TEST(Degenerate, PolesTenToTheMinusThirtyFromTheInterval) {
  const UniformityResult u = uniformity(parse_curve("(t, 1/(t + 1e-30))"), SpeedKind::Angular);
  // y' = -1/(t + e)^2 is monotone: mu = atan(1/e^2) - atan(1/(1+e)^2).
  const Ball e = exact(pow10(-30));
  const Ball mu = sub(atan_of(div(Ball(1), mul(e, e))), atan_of(div(Ball(1), mul(add(Ball(1), e), add(Ball(1), e)))));
  EXPECT_TRUE(agrees(u.mu, mu));
  EXPECT_NO_THROW(parse_curve("(t, 1/(t - 1 - 1e-30))"));
  EXPECT_THROW(parse_curve("(t, 1/(t - 1e-30))"), DomainError);
  EXPECT_THROW(parse_curve("(t, 1/(t - 1 + 1e-30))"), DomainError);
}

// ---- hundred-digit coefficients ---------------------------------------------------------

// Scaling by A/B (hundreds of digits) and translating by 300-digit constants
// leaves the angular speed unchanged and scales the parametric mean by A/B.
TEST(Degenerate, HundredDigitCoefficients) {
  const Rational A = pow10(150) + Rational(7), B = Rational::parse("3") * pow10(120) + Rational(1);
  const Rational C = pow10(300) + Rational(1, 3);
  const std::string s = "(" + (A / B).str() + ")";
  const Curve big = parse_curve("(" + s + "t + " + C.str() + ", " + s + "t^3 - " + C.str() + ")");
  const UniformityResult ua = uniformity(big, SpeedKind::Angular);
  EXPECT_TRUE(test_support::contains_ref(ua.mu, "1.249045772398254425829917077281"));
  EXPECT_TRUE(test_support::contains_ref(ua.u, "0.845695243153366341883011346954"));
  ASSERT_EQ(ua.zeros.size(), 1u);
  EXPECT_EQ(ua.zeros[0].t.rational(), Rational(0));
  const UniformityResult small = uniformity(parse_curve("(t, t^3)"), SpeedKind::Parametric);
  const UniformityResult up = uniformity(big, SpeedKind::Parametric);
  EXPECT_TRUE(agrees(up.mu, mul(small.mu, exact(A / B))));
  EXPECT_TRUE(agrees(up.u, small.u));
  // A graph with a 101-digit slope: mu = atan(3c).
  const Rational cc = pow10(100) + Rational(1);
  const UniformityResult g = uniformity(parse_curve("(t, " + cc.str() + " t^3)"), SpeedKind::Angular);
  EXPECT_TRUE(agrees(g.mu, atan_of(exact(Rational(3) * cc))));
}

// ---- degree 500 -----------------------------------------------------------------------------

// (t, t^500): angular zero of multiplicity 498 at 0, mu = atan 500;
// parametric int |p'|^2 = 1 + 500^2/999 exactly.
TEST(Degenerate, DegreeFiveHundred) {
  const Curve c = parse_curve("(t, t^500)");
  const UniformityResult a = uniformity(c, SpeedKind::Angular);
  ASSERT_EQ(a.zeros.size(), 1u);
  EXPECT_EQ(a.zeros[0].t.rational(), Rational(0));
  EXPECT_EQ(a.zeros[0].multiplicity, 498);
  EXPECT_TRUE(agrees(a.mu, atan_of(Ball(500))));
  const UniformityResult p = uniformity(c, SpeedKind::Parametric);
  EXPECT_TRUE(agrees(p.mean_square, exact(Rational(1) + Rational(250000, 999))));
  const RadicalResult r = radical(c, SpeedKind::Angular);
  EXPECT_EQ(r.root_index(0), 499);
  EXPECT_TRUE(agrees(r.mu, atan_of(Ball(500))));
}

// A dense polynomial curve of degree 500: int |p'|^2 is the exact rational
// sum over the coefficients of x'^2 + y'^2 of c_i / (i + 1).
TEST(Degenerate, DenseDegreeFiveHundredParametricMeanSquareIsExact) {
  std::vector<long> xc(501), yc(501);
  for (long i = 0; i <= 500; ++i) {
    xc[i] = (i * 7919) % 5 - 2;  // in [-2, 2]
    yc[i] = (i * 104729) % 7 - 3;
  }
  xc[1] = 600;  // keep p' away from zero on [0, 1]
  const Poly x(xc), y(yc);
  std::string text = "(" + x.str() + ", " + y.str() + ")";
  const Curve c = parse_curve(text);
  ASSERT_EQ(c.degree(), 500);
  const Poly dx = x.derivative(), dy = y.derivative(), sq = dx * dx + dy * dy;
  Rational integral(0);
  for (long i = 0; i <= sq.degree(); ++i) integral = integral + Rational(sq.coeff(i), Integer(i + 1));
  const UniformityResult p = uniformity(c, SpeedKind::Parametric);
  EXPECT_TRUE(p.zeros.empty());
  EXPECT_TRUE(agrees(p.mean_square, exact(integral)));
}

// A zero of the speed exactly at t = 1, evaluated exactly at z = 1 (it used
// to stay uncertifiable: the breakpoints' radius went through the radical).
// p(t) = (t, (t-1)^3) is q(1 - t), q = (t, t^3), up to a rotation by pi, so
// r_p(z) = 1 - r_q(1 - z) and the new speeds satisfy s_p(z) = s_q(1 - z).
TEST(Degenerate, RadicalEvaluatesExactlyAtAZeroAtTheRightEnd) {
  const Curve p = parse_curve("(t, (t - 1)^3)"), q = parse_curve("(t, t^3)");
  const RadicalResult rp = radical(p, SpeedKind::Angular), rq = radical(q, SpeedKind::Angular);
  EXPECT_TRUE(agrees(rp.u_after, rq.u_after));
  const Speed sp(p, SpeedKind::Angular), sq(q, SpeedKind::Angular);
  for (long prec : {128L, 256L}) {
    const Ball one(1), zero(0);
    const Ball r1 = eval_r(rp, one, prec);
    EXPECT_TRUE(r1.contains(Rational(1)));
    const Ball v1 = eval_speed(rp, sp, one, prec), v0 = eval_speed(rq, sq, zero, prec);
    EXPECT_TRUE(agrees(v1, v0));
    EXPECT_TRUE(v1.meets_digits(15)) << v1.str(30);
    for (const auto& b : eval_point(p, rp, one, prec)) EXPECT_TRUE(b.meets_digits(15)) << b.str(30);
  }
}

// An expired TimeBudget stops every certified computation with
// BudgetExceeded naming --timeout (checked in the precision loops,
// quadrature and root isolation).
TEST(Degenerate, ExpiredTimeBudgetStopsEveryMethod) {
  const Curve c = parse_curve("(t, t^3)");
  const TimeBudget b(1e-9);
  EXPECT_THROW(uniformity(c, SpeedKind::Angular), BudgetExceeded);
  EXPECT_THROW(radical(c, SpeedKind::Angular), BudgetExceeded);
  EXPECT_THROW(moebius_optimal(c, SpeedKind::Angular), BudgetExceeded);
  try {
    uniformity(c, SpeedKind::Parametric);
    ADD_FAILURE() << "no exception";
  } catch (const BudgetExceeded& e) {
    EXPECT_NE(std::string(e.what()).find("--timeout"), std::string::npos) << e.what();
  }
}
