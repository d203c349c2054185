// Tests of uniparam/algebra/quadrature.hpp: the Gauss-Legendre steps'
// error bounds on ellipses (the subdivision without direct evaluations, the
// small ellipse, the strip covers) and QuadratureOptions::singularity_hints,
// each checked against the exact or an independent Arb value.
#include <acb.h>
#include <arb.h>
#include <arb_poly.h>
#include <arf.h>
#include <flint/fmpz_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdlib>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/poly.hpp"
#include "support/quadrature.hpp"

namespace uniparam {
namespace {

using namespace test_support;

TEST(Quadrature, SubdividesWithoutDirectEvaluationsWhereGaussLegendreSucceeds) {
  // An analytic integrand that needs subdivision (poles at +-i/20): the
  // segments are bounded on ellipses (analytic = true) and evaluated at the
  // nodes (narrow balls). A wide real segment with analytic = false (the
  // direct enclosure f([a, b]) (b - a)) is asked only once, on the whole
  // interval, for the tolerance: never per subinterval where
  // Gauss-Legendre succeeds.
  long direct = 0, ellipses = 0;
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    const bool wide = mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) >= 0;
    if (wide && !analytic && acb_is_real(z)) ++direct;
    if (analytic) ++ellipses;
    acb_mul(out, z, z, prec);
    acb_mul_ui(out, out, 400, prec);
    acb_add_ui(out, out, 1, prec);
    acb_inv(out, out, prec);
  };
  QuadratureOptions opt;
  opt.rel_goal_bits = 53;
  const Ball r = integrate(f, Rational(0), Rational(1), opt);
  arb_t ref;  // int_0^1 dt / (1 + 400 t^2) = atan(20) / 20
  arb_init(ref);
  arb_set_ui(ref, 20);
  arb_atan(ref, ref, 256);
  arb_div_ui(ref, ref, 20, 256);
  EXPECT_TRUE(overlaps(r, ref)) << r.str(30);
  EXPECT_TRUE(meets_rel(r, 53)) << r.str(30);
  arb_clear(ref);
  EXPECT_GT(ellipses, 2);  // it did subdivide (one ellipse per attempt at least)
  EXPECT_LE(direct, 1) << "direct evaluations on subintervals";
}

/// The calls the quadrature of 1 / ((t - 1/2)^2 + (a_num/20)^2) over [0, 1]
/// made: ellipse bounds (analytic) and narrow real points.
struct PolePairCalls {
  long ellipses = 0, nodes = 0;
};

/// That quadrature at a 53-bit goal; checks that the result holds the exact
/// (2 / a) atan(1 / (2 a)) and meets the goal, and returns the calls.
PolePairCalls integrate_pole_pair(long a_num) {
  PolePairCalls calls;
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    if (analytic) ++calls.ellipses;
    else if (mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) < 0) ++calls.nodes;
    acb_t h;
    acb_init(h);
    acb_set_ui(h, 1);
    acb_mul_2exp_si(h, h, -1);
    acb_sub(out, z, h, prec);  // t - 1/2
    acb_mul(out, out, out, prec);
    acb_set_ui(h, static_cast<ulong>(a_num * a_num));
    acb_div_ui(h, h, 400, prec);  // a^2
    acb_add(out, out, h, prec);
    acb_inv(out, out, prec);
    acb_clear(h);
  };
  QuadratureOptions opt;
  opt.rel_goal_bits = 53;
  const Ball r = integrate(f, Rational(0), Rational(1), opt);
  arb_t ref, a;  // (2 / a) atan(1 / (2 a))
  arb_init(ref);
  arb_init(a);
  arb_set_ui(a, static_cast<ulong>(a_num));
  arb_div_ui(a, a, 20, 256);
  arb_mul_2exp_si(ref, a, 1);
  arb_inv(ref, ref, 256);
  arb_atan(ref, ref, 256);
  arb_mul_2exp_si(ref, ref, 1);
  arb_div(ref, ref, a, 256);
  EXPECT_TRUE(overlaps(r, ref)) << "a = " << a_num << "/20: " << r.str(30);
  EXPECT_TRUE(meets_rel(r, 53)) << r.str(30);
  arb_clear(ref);
  arb_clear(a);
  return calls;
}

TEST(Quadrature, SmallEllipseSavesTheBisectionOfAPoleJustOutsideIt) {
  // f = 1 / ((t - 1/2)^2 + a^2) on [0, 1], poles at 1/2 +- a i. On the
  // bounding box of the ellipse X (half-widths X/2 and sqrt(X^2 - 1)/2 here),
  // ball arithmetic gives Re (z - 1/2)^2 in +-(r_x^2 + r_y^2): +-1.75 for
  // X = 2, +-0.53 for X = 5/4. For a^2 between the two, f's enclosure is
  // infinite on the first box and finite on the second. For a below the
  // ellipse X = 2's semi-minor axis 0.866 the pole 1/2 + a i is in the
  // first of the two halves [0, 1/2] x [0, 0.866], [1/2, 1] x [0, 0.866]
  // over its upper half, tried after the box: the step on [0, 1] must
  // succeed on the small ellipse after exactly three ellipse calls: X = 2's
  // box, that half (the other is not tried) and X = 5/4's box (Arb's rule
  // fails at X = 2 and bisects: two more ellipses at least).
  for (long a_num : {16L, 17L})  // a = 0.8, 0.85
    EXPECT_EQ(integrate_pole_pair(a_num).ellipses, 3) << "a = " << a_num << "/20";
}

TEST(Quadrature, UpperHalfStripsServeWhereTheBoundingBoxReachesAPole) {
  // The same f for a in [1.2, 1.3]: the poles 1/2 +- a i lie outside the
  // ellipse X = 2 (semi-minor axis 0.866) but in reach of ball arithmetic on
  // its bounding box (Re (z - 1/2)^2 in +-1.75 > a^2), so that box fails
  // (for a below ~1.1 the halves' balls reach the poles too). The two halves [-X, 0] x [0, Y], [0, X] x [0, Y] (around the midpoint,
  // times the half-length) cover the upper half of the ellipse with half the
  // box's radius, and f, real on [0, 1], is bounded on the lower half by
  // reflection: the step must succeed on X = 2 after exactly four ellipse
  // calls (the bounding box, the two halves, X = 4's box), with the nodes of
  // rho = 3.73 (at most 30 for this goal) where the small ellipse X = 5/4
  // (rho = 2) takes over 30. Without the halves it bisects (more ellipses)
  // or takes the small ellipse (more nodes).
  for (long a_num : {24L, 25L, 26L}) {  // a = 1.2 .. 1.3
    const PolePairCalls calls = integrate_pole_pair(a_num);
    EXPECT_EQ(calls.ellipses, 4) << "a = " << a_num << "/20";
    EXPECT_LE(calls.nodes, 30 + 7) << "a = " << a_num << "/20";  // (+ the start-precision probe's 7 points)
  }
}

/// Nodes the quadrature of 1 over [0, 1] takes when the integrand reports
/// a singularity at 1/2 + (x + y i)/2 and its conjugate (x, y in units of
/// the half-length): every ellipse box holding either point is answered
/// indeterminate, every other call exactly 1.
long nodes_with_virtual_singularity(double x, double y) {
  long nodes = 0;
  acb_t p, q;
  acb_init(p);
  acb_init(q);
  acb_set_d_d(p, 0.5 + 0.5 * x, 0.5 * y);
  acb_conj(q, p);
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long) {
    if (!analytic && mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) < 0) ++nodes;
    if (analytic && (acb_contains(z, p) || acb_contains(z, q))) acb_indeterminate(out);
    else acb_one(out);
  };
  QuadratureOptions opt;
  opt.rel_goal_bits = 53;
  const Ball r = integrate(f, Rational(0), Rational(1), opt);
  EXPECT_TRUE(r.contains(Rational(1))) << r.str(30);
  acb_clear(p);
  acb_clear(q);
  return nodes;
}

TEST(Quadrature, NoStripCoverServesWhereTheEllipseHoldsASingularity) {
  // Points inside the ellipse X = 2 and X = 5/4's halves [-5/4, 0] x
  // [0, 3/4], [0, 5/4] x [0, 3/4] (so both fail, and the quarters of X = 5/4
  // decide). (1.0, 0.7) is outside the small ellipse (height 0.45 at x = 1)
  // and every quarter (the outer ones reach 0.65): the quarters serve, the
  // step on [0, 1] takes rho = 2's nodes. (0.9, 0.45) is inside the small
  // ellipse (height 0.52 at x = 0.9) under the outer quarter [5/8, 5/4] x
  // [0, 0.65], (0.3, 0.7) inside it (height 0.73) under the inner quarter
  // [0, 5/8] x [0, 3/4]: the step must bisect, with more nodes. A quarter
  // lower than the ellipse over it, or quarters that miss part of the half
  // ellipse, accept these as well.
  const long served = nodes_with_virtual_singularity(1.0, 0.7);
  for (const auto& p : {std::pair<double, double>{0.9, 0.45}, std::pair<double, double>{0.3, 0.7}}) {
    const long inside = nodes_with_virtual_singularity(p.first, p.second);
    EXPECT_GT(inside, served) << "(" << p.first << ", " << p.second << "): " << inside
                              << " nodes, outside: " << served;
  }
}

/// p's integral over [0, 1] at a 53-bit goal, with these singularity hints.
Ball integrate_hinted(PolePair& p, std::vector<std::complex<double>> hints) {
  QuadratureOptions opt;
  opt.rel_goal_bits = 53;
  opt.singularity_hints = std::move(hints);
  return integrate(p.f(), Rational(0), Rational(1), opt);
}

TEST(QuadratureHints, HintsAtThePolesSkipTheFailingEllipses) {
  // Poles close to [0, 1] (a = 1/8 .. 1/64): without hints most subintervals
  // near 1/2 try ellipses whose bounds are infinite; the true poles as hints
  // must skip some of them, and both answers hold the true integral.
  for (long inv_a : {8L, 20L, 64L}) {
    const Rational a2(1, inv_a * inv_a);
    arb_t ref;
    arb_init(ref);
    pole_pair_reference(ref, a2);
    PolePair plain{a2}, hinted{a2};
    const Ball r0 = integrate_hinted(plain, {});
    const double a = 1.0 / static_cast<double>(inv_a);
    const Ball r1 = integrate_hinted(hinted, {{0.5, a}, {0.5, -a}});
    SCOPED_TRACE("a = 1/" + std::to_string(inv_a));
    EXPECT_TRUE(overlaps(r0, ref)) << r0.str(30);
    EXPECT_TRUE(overlaps(r1, ref)) << r1.str(30);
    EXPECT_TRUE(meets_rel(r1, 53)) << r1.str(30);
    EXPECT_GT(plain.failed, 0);
    EXPECT_LT(hinted.failed, plain.failed);
    EXPECT_LT(hinted.ellipses, plain.ellipses);
    arb_clear(ref);
  }
}

TEST(QuadratureHints, TheLargestEllipseTheHintsLeaveServesBetweenTheSmallOneAndX2) {
  // Poles at 1/2 +- 1.2 i. The hints at the poles block X = 2 on [0, 1]
  // (inside its box enlarged 1.75 times) but leave X ~ 1.69 (rho ~ 3.05):
  // one step with fewer nodes than on the small ellipse X = 5/4 (rho = 2),
  // which hints at 1/2 +- 0.8 i force (they leave only X ~ 1.36 < 1.4, not
  // worth trying). Both hold the true integral.
  const Rational a2(36, 25);
  arb_t ref;
  arb_init(ref);
  pole_pair_reference(ref, a2);
  PolePair mid{a2}, small{a2};
  const Ball r1 = integrate_hinted(mid, {{0.5, 1.2}, {0.5, -1.2}});
  const Ball r2 = integrate_hinted(small, {{0.5, 0.8}, {0.5, -0.8}});
  EXPECT_TRUE(overlaps(r1, ref)) << r1.str(30);
  EXPECT_TRUE(overlaps(r2, ref)) << r2.str(30);
  EXPECT_TRUE(meets_rel(r1, 53)) << r1.str(30);
  EXPECT_TRUE(meets_rel(r2, 53)) << r2.str(30);
  EXPECT_EQ(mid.failed, 0);
  EXPECT_LT(mid.points, small.points);
  arb_clear(ref);
}

TEST(QuadratureHints, WrongHintsCostTimeNotCorrectness) {
  // Hints on the segment itself (where f is analytic) refuse every ellipse
  // near them; from depth 12 on the quadrature tries the ellipses anyway, so
  // it converges to the true value at a bounded cost (without that rule it
  // would bisect on: 101 ellipses for the two hints on the segment, against
  // 59 with it and 10 without hints).
  const Rational a2(1, 4);
  arb_t ref;
  arb_init(ref);
  pole_pair_reference(ref, a2);
  PolePair none{a2};
  EXPECT_TRUE(overlaps(integrate_hinted(none, {}), ref));
  for (const auto& hints : std::vector<std::vector<std::complex<double>>>{
           {{0.3, 0}}, {{0.5, 0}, {0.25, 1e-9}}, {{100, 100}}, {{0.5, 0.5}, {0.5, -0.5}}}) {
    PolePair p{a2};
    const Ball r = integrate_hinted(p, hints);
    SCOPED_TRACE("first hint " + std::to_string(hints[0].real()) + " + " + std::to_string(hints[0].imag()) + " i");
    EXPECT_TRUE(overlaps(r, ref)) << r.str(30);
    EXPECT_TRUE(meets_rel(r, 53)) << r.str(30);
    EXPECT_LE(p.ellipses, 8 * none.ellipses);
  }
  arb_clear(ref);
}

}  // namespace
}  // namespace uniparam
