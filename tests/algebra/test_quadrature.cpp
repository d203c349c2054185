// Tests of uniparam/algebra/quadrature.hpp against exact rational integrals
// and independent Arb values (arb_const_pi, arb_atan, arb_log, arb_sqrt).
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

namespace uniparam {
namespace {

using test_support::iterations;

Rational to_rational(const arf_t x) {
  Rational q;
  arf_get_fmpq(q.get(), x);
  return q;
}

/// rad <= 2^-bits * |mid|, decided exactly on rationals (independent of the
/// mag arithmetic used by the implementation).
bool meets_rel(const Ball& r, long bits) {
  if (!r.is_finite()) return false;
  arf_t rad;
  arf_init(rad);
  arf_set_mag(rad, arb_radref(r.get()));
  Rational rr = to_rational(rad);
  arf_clear(rad);
  Rational mid = to_rational(arb_midref(r.get()));
  if (mid.sign() < 0) mid = -mid;
  Integer p;
  fmpz_one(p.get());
  fmpz_mul_2exp(p.get(), p.get(), static_cast<ulong>(bits));
  return rr * Rational(p) <= mid;
}

bool meets_abs(const Ball& r, long bits) {
  return r.is_finite() && mag_cmp_2exp_si(arb_radref(r.get()), -bits) <= 0;
}

/// The balls share a point: the only way a correct enclosure and a correct
/// reference value can relate.
bool overlaps(const Ball& r, const arb_t ref) { return arb_overlaps(r.get(), ref); }

/// p(t) = sum c[k] t^k by Horner; entire, so the ball evaluation certifies
/// holomorphy by itself.
Integrand poly_integrand(const std::vector<long>& c) {
  return [c](acb_t out, const acb_t z, bool, long prec) {
    acb_zero(out);
    for (auto it = c.rbegin(); it != c.rend(); ++it) {
      acb_mul(out, out, z, prec);
      acb_add_si(out, out, *it, prec);
    }
  };
}

Rational power(const Rational& x, long e) {
  Rational r(1);
  for (long i = 0; i < e; ++i) r = r * x;
  return r;
}

Rational exact_poly_integral(const std::vector<long>& c, const Rational& a, const Rational& b) {
  Rational s(0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    const long e = static_cast<long>(k) + 1;
    s = s + Rational(c[k]) * (power(b, e) - power(a, e)) / Rational(e);
  }
  return s;
}

/// 1/(1+t^2): a rational function; inversion of a ball containing 0 gives a
/// non-finite result, so poles are detected by the evaluation itself.
void one_over_one_plus_square(acb_t out, const acb_t z, bool, long prec) {
  acb_mul(out, z, z, prec);
  acb_add_ui(out, out, 1, prec);
  acb_inv(out, out, prec);
}

std::string str(const std::vector<long>& c) {
  std::string s = "[";
  for (long x : c) s += std::to_string(x) + " ";
  return s + "]";
}

// ---------------------------------------------------------------------------

TEST(Quadrature, PolynomialsAtRationalEndsContainExactIntegral) {
  const char* seed_env = std::getenv("UNIPARAM_TEST_SEED");
  const unsigned seed = seed_env ? static_cast<unsigned>(std::strtoul(seed_env, nullptr, 10)) : 20240611u;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<long> coef(-9, 9), num(-30, 30), den(1, 12), deg(0, 7);
  const long n = iterations(30);
  for (long it = 0; it < n; ++it) {
    std::vector<long> c(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : c) x = coef(rng);
    Rational a(num(rng), den(rng)), b(num(rng), den(rng));
    if (b < a) std::swap(a, b);
    if (a == b) continue;
    const Rational exact = exact_poly_integral(c, a, b);
    QuadratureOptions opt;
    opt.rel_goal_bits = (it % 2 == 0) ? 53 : 200;
    if (exact.is_zero()) opt.abs_goal_bits = opt.rel_goal_bits;
    SCOPED_TRACE("seed " + std::to_string(seed) + " iteration " + std::to_string(it) + " poly " + str(c) +
                 " on [" + a.str() + ", " + b.str() + "] exact " + exact.str());
    const Ball r = integrate(poly_integrand(c), a, b, opt);
    EXPECT_TRUE(r.contains(exact)) << r.str(30);
    if (exact.is_zero())
      EXPECT_TRUE(meets_abs(r, opt.abs_goal_bits)) << r.str(30);
    else
      EXPECT_TRUE(meets_rel(r, opt.rel_goal_bits)) << r.str(30);
  }
}

TEST(Quadrature, NonDyadicRationalEnds) {
  // f = 1 on [1/3, 2/3]: both ends have a radius, the integral is 1/3.
  {
    QuadratureOptions opt;
    const Ball r = integrate(poly_integrand({1}), Rational(1, 3), Rational(2, 3), opt);
    EXPECT_TRUE(r.contains(Rational(1, 3))) << r.str(30);
    EXPECT_TRUE(meets_rel(r, opt.rel_goal_bits));
  }
  // 1/t on [1/3, 3] = 2 log 3, checked against arb_log.
  for (long bits : {53L, 200L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    Integrand inv = [](acb_t out, const acb_t z, bool, long prec) { acb_inv(out, z, prec); };
    const Ball r = integrate(inv, Rational(1, 3), Rational(3), opt);
    arb_t ref;
    arb_init(ref);
    arb_set_ui(ref, 9);
    arb_log(ref, ref, 4 * bits);
    EXPECT_TRUE(overlaps(r, ref)) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits)) << r.str(70);
    arb_clear(ref);
  }
}

TEST(Quadrature, ArctanIntegralContainsQuarterPi) {
  for (long bits : {53L, 200L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    long analytic_calls = 0, plain_calls = 0;
    Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
      (analytic ? analytic_calls : plain_calls)++;
      one_over_one_plus_square(out, z, analytic, prec);
    };
    const Ball r = integrate(f, Rational(0), Rational(1), opt);
    arb_t pi4;
    arb_init(pi4);
    arb_const_pi(pi4, 4 * bits);
    arb_mul_2exp_si(pi4, pi4, -2);
    EXPECT_TRUE(overlaps(r, pi4)) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits)) << r.str(70);
    arb_clear(pi4);
    // Arb's order 1 (Gauss-Legendre error bounds) and order 0 (direct
    // evaluation) both reach the Integrand, as analytic = true / false.
    EXPECT_GT(analytic_calls, 0);
    EXPECT_GT(plain_calls, 0);
  }
}

// An integral's ball depends on the integrand, the ends and the goal only,
// not on what the thread computed before: the Gauss-Legendre nodes are
// cached per thread, at a precision that depends on the precision asked
// alone. A fresh thread and one that integrated at 1200, 2 b and b + 20
// bits first give the same ball at b = 53 and 150 bits (fails when the cache
// hands out the nodes it holds at a higher precision).
TEST(Quadrature, BallsDoNotDependOnWhatTheThreadComputedBefore) {
  for (long bits : {53L, 150L}) {
    SCOPED_TRACE("bits " + std::to_string(bits));
    QuadratureOptions opt, high;
    opt.rel_goal_bits = bits;
    high.rel_goal_bits = 1200;
    Ball fresh, warm, warm_high;
    std::thread a([&] {
      fresh = integrate(one_over_one_plus_square, Rational(0), Rational(1), opt);
      flint_cleanup();
    });
    a.join();
    std::thread b([&] {
      for (long more : {1200L, 2 * bits, bits + 20}) {
        high.rel_goal_bits = more;
        warm_high = integrate(one_over_one_plus_square, Rational(0), Rational(1), high);
        EXPECT_TRUE(meets_rel(warm_high, more));
      }
      warm = integrate(one_over_one_plus_square, Rational(0), Rational(1), opt);
      flint_cleanup();
    });
    b.join();
    EXPECT_TRUE(arb_equal(fresh.get(), warm.get())) << fresh.str(40) << " vs " << warm.str(40);
  }
}

TEST(Quadrature, NearbyComplexPole) {
  // 10^6 / (10^6 t^2 + 1) has poles at +-i/1000; its integral over [0, 1] is
  // 1000 atan(1000).
  Integrand f = [](acb_t out, const acb_t z, bool, long prec) {
    acb_mul(out, z, z, prec);
    acb_mul_ui(out, out, 1000000, prec);
    acb_add_ui(out, out, 1, prec);
    acb_inv(out, out, prec);
    acb_mul_ui(out, out, 1000000, prec);
  };
  for (long bits : {53L, 200L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    const Ball r = integrate(f, Rational(0), Rational(1), opt);
    arb_t ref;
    arb_init(ref);
    arb_set_ui(ref, 1000);
    arb_atan(ref, ref, 4 * bits);
    arb_mul_ui(ref, ref, 1000, 4 * bits);
    EXPECT_TRUE(overlaps(r, ref)) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits)) << r.str(70);
    arb_clear(ref);
  }
}

TEST(Quadrature, IntegrableEndSingularityConverges) {
  // sqrt(t) is not holomorphic at 0, so no Gauss-Legendre rule is certified
  // on a subinterval [0, h]: those are accepted with their direct enclosure
  // h sqrt([0, h]) once it is below the tolerance (deep in the subdivision).
  // int_0^1 sqrt(t) dt = 2/3; int_0^{1/4} = 1/12.
  Integrand f = [](acb_t out, const acb_t z, bool analytic, long prec) {
    acb_sqrt_analytic(out, z, analytic ? 1 : 0, prec);
  };
  for (long bits : {20L, 53L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    const Ball r = integrate(f, Rational(0), Rational(1), opt);
    EXPECT_TRUE(r.contains(Rational(2, 3))) << r.str(30);
    EXPECT_TRUE(meets_rel(r, bits)) << r.str(30);
    const Ball q = integrate(f, Rational(0), Rational(1, 4), opt);
    EXPECT_TRUE(q.contains(Rational(1, 12))) << q.str(30);
    EXPECT_TRUE(meets_rel(q, bits)) << q.str(30);
  }
}

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

TEST(Quadrature, AlgebraicEnds) {
  const RealAlgebraic half_sqrt2(Poly(std::vector<long>{-1, 0, 2}), Rational(0), Rational(1));  // sqrt(2)/2
  const RealAlgebraic cbrt2(Poly(std::vector<long>{-2, 0, 0, 1}), Rational(1), Rational(2));    // 2^(1/3)
  for (long bits : {53L, 200L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    // int_0^{sqrt(2)/2} t dt = 1/4
    Ball r = integrate(poly_integrand({0, 1}), Rational(0), half_sqrt2, opt);
    EXPECT_TRUE(r.contains(Rational(1, 4))) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits));
    // int_1^{2^(1/3)} 3 t^2 dt = 2 - 1 = 1
    r = integrate(poly_integrand({0, 0, 3}), Rational(1), cbrt2, opt);
    EXPECT_TRUE(r.contains(Rational(1))) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits));
    // int_{sqrt(2)/2}^{2^(1/3)} 1 dt = 2^(1/3) - sqrt(2)/2, against arb_root_ui/arb_sqrt
    r = integrate(poly_integrand({1}), half_sqrt2, cbrt2, opt);
    arb_t ref, s;
    arb_init(ref);
    arb_init(s);
    arb_set_ui(ref, 2);
    arb_root_ui(ref, ref, 3, 4 * bits);
    arb_sqrt_ui(s, 2, 4 * bits);
    arb_mul_2exp_si(s, s, -1);
    arb_sub(ref, ref, s, 4 * bits);
    EXPECT_TRUE(overlaps(r, ref)) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits));
    // int_0^{sqrt(2)/2} t^2 dt = sqrt(2)/12
    r = integrate(poly_integrand({0, 0, 1}), Rational(0), half_sqrt2, opt);
    arb_sqrt_ui(ref, 2, 4 * bits);
    arb_div_ui(ref, ref, 12, 4 * bits);
    EXPECT_TRUE(overlaps(r, ref)) << r.str(70);
    EXPECT_TRUE(meets_rel(r, bits));
    arb_clear(ref);
    arb_clear(s);
  }
}

TEST(Quadrature, KinkInsideIntervalNeverMissesTrueValue) {
  // |3t - 1| / 3 = |t - 1/3|: not holomorphic at 1/3; acb_real_abs with the
  // analytic flag answers indeterminate on balls containing 1/3.
  // int_0^1 |t - 1/3| dt = (1/3)^2/2 + (2/3)^2/2 = 5/18.
  Integrand f = [](acb_t out, const acb_t z, bool analytic, long prec) {
    acb_mul_ui(out, z, 3, prec);
    acb_sub_ui(out, out, 1, prec);
    acb_real_abs(out, out, analytic ? 1 : 0, prec);
    acb_div_ui(out, out, 3, prec);
  };
  // BudgetExceeded is allowed by the contract in general (a wrong ball never
  // is), but these integrals are well within max_prec: a throw would leave
  // the containment checks below unexercised, so it fails the test.
  for (long bits : {20L, 53L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    opt.max_prec = 1024;
    try {
      const Ball r = integrate(f, Rational(0), Rational(1), opt);
      EXPECT_TRUE(r.contains(Rational(5, 18))) << r.str(30);
      EXPECT_TRUE(meets_rel(r, bits)) << r.str(30);
    } catch (const BudgetExceeded& e) {
      ADD_FAILURE() << "bits " << bits << ": " << e.what();
    }
  }
  // Same with the kink at an algebraic end's neighbourhood: int_0^{sqrt(2)/2}.
  // = 1/18 + (sqrt(2)/2 - 1/3)^2 / 2, checked with arb_sqrt.
  const RealAlgebraic half_sqrt2(Poly(std::vector<long>{-1, 0, 2}), Rational(0), Rational(1));
  QuadratureOptions opt;
  opt.rel_goal_bits = 40;
  opt.max_prec = 1024;
  try {
    const Ball r = integrate(f, Rational(0), half_sqrt2, opt);
    arb_t ref, t;
    arb_init(ref);
    arb_init(t);
    arb_sqrt_ui(ref, 2, 256);
    arb_mul_2exp_si(ref, ref, -1);
    arb_set_ui(t, 1);
    arb_div_ui(t, t, 3, 256);
    arb_sub(ref, ref, t, 256);
    arb_mul(ref, ref, ref, 256);
    arb_mul_2exp_si(ref, ref, -1);
    arb_set_ui(t, 1);
    arb_div_ui(t, t, 18, 256);
    arb_add(ref, ref, t, 256);
    EXPECT_TRUE(overlaps(r, ref)) << r.str(30);
    EXPECT_TRUE(meets_rel(r, 40));
    arb_clear(ref);
    arb_clear(t);
  } catch (const BudgetExceeded& e) {
    ADD_FAILURE() << "algebraic end: " << e.what();
  }
}

TEST(Quadrature, AbsoluteGoalForZeroIntegral) {
  // int_{-1}^{1} t^3 dt = 0: only an absolute goal can be met.
  QuadratureOptions opt;
  opt.abs_goal_bits = 60;
  const Ball r = integrate(poly_integrand({0, 0, 0, 1}), Rational(-1), Rational(1), opt);
  EXPECT_TRUE(r.contains(Rational(0))) << r.str(30);
  EXPECT_TRUE(meets_abs(r, 60)) << r.str(30);
}

TEST(Quadrature, BudgetExceededWhenMaxPrecIsTiny) {
  std::set<long> precs;
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    precs.insert(prec);
    one_over_one_plus_square(out, z, analytic, prec);
  };
  QuadratureOptions opt;
  opt.rel_goal_bits = 53;
  opt.max_prec = 24;
  opt.what = "test arc length";
  try {
    integrate(f, Rational(0), Rational(1), opt);
    FAIL() << "53 bits certified with 24 bits of working precision";
  } catch (const BudgetExceeded& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test arc length"), std::string::npos) << msg;
    EXPECT_NE(msg.find("53 bits"), std::string::npos) << msg;
    EXPECT_NE(msg.find("24 bits"), std::string::npos) << msg;
    EXPECT_NE(msg.find("--max-prec"), std::string::npos) << msg;
  }
  ASSERT_FALSE(precs.empty());
  EXPECT_LE(*precs.rbegin(), 24);

  // The precision doubles from initial_prec and the last attempt is made at
  // exactly max_prec, never above.
  precs.clear();
  opt.rel_goal_bits = 100000;  // unreachable
  opt.initial_prec = 40;
  opt.max_prec = 200;
  EXPECT_THROW(integrate(f, Rational(0), Rational(1), opt), BudgetExceeded);
  EXPECT_EQ(*precs.begin(), 40);
  EXPECT_EQ(*precs.rbegin(), 200);
  EXPECT_TRUE(precs.count(80) && precs.count(160));
}

TEST(Quadrature, EvalLimitTooSmallIsBudgetNotWrongAnswer) {
  Integrand f = [](acb_t out, const acb_t z, bool, long prec) {
    acb_mul(out, z, z, prec);
    acb_mul_ui(out, out, 1000000, prec);
    acb_add_ui(out, out, 1, prec);
    acb_inv(out, out, prec);
    acb_mul_ui(out, out, 1000000, prec);
  };
  QuadratureOptions opt;
  opt.eval_limit = 3;
  opt.max_prec = 256;
  EXPECT_THROW(integrate(f, Rational(0), Rational(1), opt), BudgetExceeded);
}

TEST(Quadrature, PoleOnTheSegmentIsBudgetNotAFiniteBall) {
  // 1/(2t - 1) has a pole at 1/2 in [0, 1]: no enclosure can be finite.
  Integrand f = [](acb_t out, const acb_t z, bool, long prec) {
    acb_mul_2exp_si(out, z, 1);
    acb_sub_ui(out, out, 1, prec);
    acb_inv(out, out, prec);
  };
  QuadratureOptions opt;
  opt.max_prec = 200;
  EXPECT_THROW(integrate(f, Rational(0), Rational(1), opt), BudgetExceeded);
}

TEST(Quadrature, DegenerateAndReversedSegments) {
  long calls = 0;
  Integrand f = [&](acb_t out, const acb_t, bool, long) {
    ++calls;
    acb_indeterminate(out);
  };
  const Ball z = integrate(f, Rational(1, 3), Rational(1, 3));
  EXPECT_TRUE(z.certainly_zero());
  EXPECT_TRUE(z.is_exact());
  // The same algebraic number from two isolating intervals: still exactly 0.
  const RealAlgebraic x(Poly(std::vector<long>{-1, 0, 2}), Rational(0), Rational(1));
  const RealAlgebraic y(Poly(std::vector<long>{-1, 0, 2}), Rational(1, 2), Rational(3, 4));
  const Ball w = integrate(f, x, y);
  EXPECT_TRUE(w.certainly_zero());
  EXPECT_TRUE(w.is_exact());
  EXPECT_EQ(calls, 0);
  EXPECT_THROW(integrate(f, Rational(1), Rational(0)), InvalidArgument);
  EXPECT_THROW(integrate(f, x, Rational(0)), InvalidArgument);
}

TEST(Quadrature, InvalidArguments) {
  EXPECT_THROW(integrate(Integrand(), Rational(0), Rational(1)), InvalidArgument);
  QuadratureOptions opt;
  opt.max_prec = 1;
  EXPECT_THROW(integrate(poly_integrand({1}), Rational(0), Rational(1), opt), InvalidArgument);
  opt = QuadratureOptions();
  opt.rel_goal_bits = -1;
  EXPECT_THROW(integrate(poly_integrand({1}), Rational(0), Rational(1), opt), InvalidArgument);
}

TEST(Quadrature, IntegrandExceptionsCrossTheCCallback) {
  long calls = 0, calls_after_throw = 0;
  bool thrown = false;
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    if (thrown) ++calls_after_throw;
    if (++calls == 5) {
      thrown = true;
      throw DomainError("pole of the test integrand");
    }
    one_over_one_plus_square(out, z, analytic, prec);
  };
  try {
    integrate(f, Rational(0), Rational(1));
    FAIL() << "exception swallowed";
  } catch (const DomainError& e) {
    EXPECT_STREQ(e.what(), "pole of the test integrand");
  }
  EXPECT_EQ(calls_after_throw, 0);

  // An exception from the end-point bound (non-dyadic end) propagates too.
  // g throws only on small real balls around 1/3: the end-point enclosure
  // (or the wider ball the bound tries first).
  Integrand g = [](acb_t out, const acb_t z, bool analytic, long prec) {
    const Rational third(1, 3);
    if (!analytic && arb_is_zero(acb_imagref(z)) && arb_contains_fmpq(acb_realref(z), third.get()) &&
        mag_cmp_2exp_si(arb_radref(acb_realref(z)), -8) < 0)
      throw InvalidArgument("end point evaluation");
    one_over_one_plus_square(out, z, analytic, prec);
  };
  EXPECT_THROW(integrate(g, Rational(0), Rational(1, 3)), InvalidArgument);
}

// The end error of a non-dyadic end (an algebraic end's enclosure) is
// bounded on a small ball around the end first, where the integrand is
// cheap to bound, and on the end's own enclosure only where that bound is
// not finite: here 1/(t - c) with its pole c at 2^-(k+1) below the end 1/3
// for k = 20, 14, 8 (the ball of radius 2^-12 holds the pole for k >= 11).
// Every result holds log((b - c)/(a - c)); the narrow end evaluations
// happen exactly where the small ball holds the pole.
TEST(Quadrature, EndErrorsAreBoundedOnASmallBallAroundTheEndFirst) {
  for (long k : {20L, 14L, 8L}) {
    const Rational a(1, 3), b(1, 2);
    arb_t c;
    arb_init(c);
    arb_set_d(c, std::ldexp(1.0, static_cast<int>(-k - 1)));
    arb_t third;
    arb_init(third);
    arb_set_fmpq(third, a.get(), 300);
    arb_sub(c, third, c, 300);  // c = 1/3 - 2^-(k+1), at 300 bits
    long narrow_end_calls = 0;
    Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
      if (!analytic && acb_is_real(z) && mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) < 0 &&
          arb_contains_fmpq(acb_realref(z), a.get()))
        ++narrow_end_calls;
      acb_sub_arb(out, z, c, prec + 30);
      acb_inv(out, out, prec);
    };
    const Ball r = integrate(f, RealAlgebraic(a), RealAlgebraic(b), QuadratureOptions{});  // 1/3: not dyadic
    arb_t exact, den;
    arb_init(exact);
    arb_init(den);
    arb_set_fmpq(exact, b.get(), 300);
    arb_sub(exact, exact, c, 300);
    arb_sub(den, third, c, 300);
    arb_div(exact, exact, den, 300);
    arb_log(exact, exact, 300);
    EXPECT_TRUE(arb_overlaps(r.get(), exact)) << "k = " << k << ": " << r.str(30);
    EXPECT_TRUE(r.is_finite()) << "k = " << k;
    EXPECT_GT(arb_rel_accuracy_bits(r.get()), 50) << "k = " << k;
    if (k >= 11) EXPECT_GT(narrow_end_calls, 0) << "k = " << k;
    else EXPECT_EQ(narrow_end_calls, 0) << "k = " << k;
    for (arb_ptr x : {c, third, exact, den}) arb_clear(x);
  }
}

TEST(Quadrature, NonRealIntegrandIsDomainError) {
  Integrand f = [](acb_t out, const acb_t, bool, long) { acb_onei(out); };
  EXPECT_THROW(integrate(f, Rational(0), Rational(1)), DomainError);
}


// An integrand that loses ~200 bits to cancellation (the expanded (1 - 2z)^100
// by Horner, as a high-degree power-basis polynomial is evaluated): the first
// attempt starts above the loss, so the quadrature runs at one precision only,
// and the result still encloses 1/101 to the goal.
TEST(Quadrature, StartsAbovePrecisionLostToCancellation) {
  arb_poly_t p;
  arb_poly_init(p);
  {
    fmpz_poly_t e;
    fmpz_poly_init(e);
    fmpz_poly_set_coeff_si(e, 0, 1);
    fmpz_poly_set_coeff_si(e, 1, -2);
    fmpz_poly_pow(e, e, 100);
    arb_poly_set_fmpz_poly(p, e, ARF_PREC_EXACT);
    fmpz_poly_clear(e);
  }
  std::set<long> precs;
  Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    if (analytic) precs.insert(prec);
    arb_poly_evaluate_acb(out, p, z, prec);
  };
  QuadratureOptions o;
  o.rel_goal_bits = 64;
  const Ball r = integrate(f, Rational(0), Rational(1), o);
  EXPECT_TRUE(r.contains(Rational(1, 101))) << r.str(30);
  EXPECT_LE(mag_cmp_2exp_si(arb_radref(r.get()), -64 - 6), 0) << r.str(30);  // 2^-64 relative to 1/101
  EXPECT_EQ(precs.size(), 1u) << "precisions used: " << precs.size();
  arb_poly_clear(p);
}

// ---------------------------------------------------------------------------
// integrate_many: several integrals over one subdivision.

TEST(QuadratureMany, PolynomialsOfDifferentScalesEachContainTheirExactIntegral) {
  // count random polynomials, one scaled by 10^-12 and one by 10^9, on
  // random rational segments: each result contains its exact integral and
  // meets its own relative goal (a shared tolerance would miss the small one).
  const char* seed_env = std::getenv("UNIPARAM_TEST_SEED");
  const unsigned seed = seed_env ? static_cast<unsigned>(std::strtoul(seed_env, nullptr, 10)) : 20261123u;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<long> coef(-9, 9), num(-30, 30), den(1, 12), deg(0, 9), cnt(1, 4);
  const long n = iterations(30);
  for (long it = 0; it < n; ++it) {
    const std::size_t count = static_cast<std::size_t>(cnt(rng));
    std::vector<std::vector<long>> c(count);
    std::vector<Rational> scale(count, Rational(1));
    for (std::size_t k = 0; k < count; ++k) {
      c[k].resize(static_cast<std::size_t>(deg(rng)) + 1);
      for (long& x : c[k]) x = coef(rng);
      if (k == 1) scale[k] = Rational(1, 1000000000000L);
      if (k == 2) scale[k] = Rational(1000000000L);
    }
    Rational a(num(rng), den(rng)), b(num(rng), den(rng));
    if (b < a) std::swap(a, b);
    if (a == b) continue;
    std::vector<Rational> exact(count);
    bool any_zero = false;
    for (std::size_t k = 0; k < count; ++k) {
      exact[k] = scale[k] * exact_poly_integral(c[k], a, b);
      any_zero = any_zero || exact[k].is_zero();
    }
    if (any_zero) continue;  // a relative goal cannot be met by 0 (integrate's contract)
    std::vector<Integrand> fs;
    for (std::size_t k = 0; k < count; ++k) fs.push_back(poly_integrand(c[k]));
    Integrand f = [&](acb_ptr out, const acb_t z, bool analytic, long prec) {
      for (std::size_t k = 0; k < count; ++k) {
        fs[k](out + k, z, analytic, prec);
        arb_t s;
        arb_init(s);
        arb_set_fmpq(s, scale[k].get(), prec);
        acb_mul_arb(out + k, out + k, s, prec);
        arb_clear(s);
      }
    };
    QuadratureOptions opt;
    opt.rel_goal_bits = (it % 2 == 0) ? 53 : 200;
    SCOPED_TRACE("seed " + std::to_string(seed) + " iteration " + std::to_string(it) + " on [" + a.str() + ", " +
                 b.str() + "]");
    const std::vector<Ball> r = integrate_many(f, count, a, b, opt);
    ASSERT_EQ(r.size(), count);
    for (std::size_t k = 0; k < count; ++k) {
      EXPECT_TRUE(r[k].contains(exact[k])) << k << " " << str(c[k]) << " " << r[k].str(30);
      EXPECT_TRUE(meets_rel(r[k], opt.rel_goal_bits)) << k << " " << r[k].str(30);
    }
  }
}

TEST(QuadratureMany, AgreesWithSeparateQuadraturesNearAPoleAndASingularEnd) {
  // f_0 = 1/(1 + 400 t^2) (poles at +-i/20: subdivision, the Gauss-Legendre
  // error bounds matter), f_1 = sqrt(t) (no rule certified next to 0: direct
  // enclosures deep in the subdivision), f_2 = 10^9 f_0 and
  // f_3 = 10^-12 f_0 (each integral's error bound and tolerance its own)
  // together: the shared subdivision must serve all four.
  Integrand f = [](acb_ptr out, const acb_t z, bool analytic, long prec) {
    acb_mul(out, z, z, prec);
    acb_mul_ui(out, out, 400, prec);
    acb_add_ui(out, out, 1, prec);
    acb_inv(out, out, prec);
    acb_sqrt_analytic(out + 1, z, analytic ? 1 : 0, prec);
    acb_mul_ui(out + 2, out, 1000000000, prec);
    acb_div_ui(out + 3, out, 1000000, prec);
    acb_div_ui(out + 3, out + 3, 1000000, prec);
  };
  for (long bits : {20L, 53L, 120L}) {
    QuadratureOptions opt;
    opt.rel_goal_bits = bits;
    const std::vector<Ball> r = integrate_many(f, 4, Rational(0), Rational(1), opt);
    arb_t ref;  // atan(20) / 20
    arb_init(ref);
    arb_set_ui(ref, 20);
    arb_atan(ref, ref, 4 * bits);
    arb_div_ui(ref, ref, 20, 4 * bits);
    EXPECT_TRUE(overlaps(r[0], ref)) << r[0].str(30);
    EXPECT_TRUE(meets_rel(r[0], bits)) << r[0].str(30);
    EXPECT_TRUE(r[1].contains(Rational(2, 3))) << r[1].str(30);
    EXPECT_TRUE(meets_rel(r[1], bits)) << r[1].str(30);
    arb_mul_ui(ref, ref, 1000000000, 4 * bits);
    EXPECT_TRUE(overlaps(r[2], ref)) << r[2].str(30);
    EXPECT_TRUE(meets_rel(r[2], bits)) << r[2].str(30);
    arb_div_ui(ref, ref, 1000000000, 4 * bits);
    arb_div_ui(ref, ref, 1000000, 4 * bits);
    arb_div_ui(ref, ref, 1000000, 4 * bits);
    EXPECT_TRUE(overlaps(r[3], ref)) << r[3].str(30);
    EXPECT_TRUE(meets_rel(r[3], bits)) << r[3].str(30);
    arb_clear(ref);
  }
}

TEST(QuadratureMany, TheDegreeServesTheHardestIntegral) {
  // f_0 = 1 is integrated exactly by one node, f_1 = (2t - 1)^40 needs 21:
  // each subinterval's rule must be chosen for both, or f_1's error bound
  // misses its goal (one attempt only: no retry at a higher precision).
  Integrand f = [](acb_ptr out, const acb_t z, bool, long prec) {
    acb_one(out);
    acb_mul_2exp_si(out + 1, z, 1);
    acb_sub_ui(out + 1, out + 1, 1, prec);
    acb_pow_ui(out + 1, out + 1, 40, prec);
  };
  QuadratureOptions opt;
  opt.rel_goal_bits = 100;
  opt.initial_prec = opt.max_prec = 132;
  const std::vector<Ball> r = integrate_many(f, 2, Rational(0), Rational(1), opt);
  EXPECT_TRUE(r[0].contains(Rational(1))) << r[0].str(30);
  EXPECT_TRUE(r[1].contains(Rational(1, 41))) << r[1].str(40);
  EXPECT_TRUE(meets_rel(r[1], opt.rel_goal_bits)) << r[1].str(40);
}

TEST(QuadratureMany, OneCallPerPointForAllIntegrals) {
  // The point of integrate_many: the same calls of f serve every integral.
  long calls_many = 0, calls_one = 0;
  Integrand g = [&](acb_ptr out, const acb_t z, bool analytic, long prec) {
    ++calls_many;
    one_over_one_plus_square(out, z, analytic, prec);
    acb_mul(out + 1, out, out, prec);
  };
  Integrand h = [&](acb_t out, const acb_t z, bool analytic, long prec) {
    ++calls_one;
    one_over_one_plus_square(out, z, analytic, prec);
  };
  QuadratureOptions opt;
  const std::vector<Ball> r = integrate_many(g, 2, Rational(0), Rational(1), opt);
  const Ball one = integrate(h, Rational(0), Rational(1), opt);
  EXPECT_TRUE(arb_overlaps(r[0].get(), one.get()));
  // int_0^1 (1 + t^2)^-2 dt = 1/4 + pi/8
  arb_t ref;
  arb_init(ref);
  arb_const_pi(ref, 256);
  arb_mul_2exp_si(ref, ref, -3);
  arb_t quarter;
  arb_init(quarter);
  arb_set_d(quarter, 0.25);  // exact
  arb_add(ref, ref, quarter, 256);
  arb_clear(quarter);
  EXPECT_TRUE(overlaps(r[1], ref)) << r[1].str(30);
  arb_clear(ref);
  // the second integrand needs at most a few more nodes than the first
  // alone; two separate quadratures would call f about twice as often
  EXPECT_LT(calls_many, 2 * calls_one) << calls_many << " vs " << calls_one;
}

TEST(QuadratureMany, InvalidArgumentsAndErrors) {
  Integrand f = [](acb_ptr out, const acb_t z, bool analytic, long prec) {
    one_over_one_plus_square(out, z, analytic, prec);
    acb_set(out + 1, out);
  };
  EXPECT_THROW(integrate_many(f, 0, Rational(0), Rational(1)), InvalidArgument);
  EXPECT_THROW(integrate_many(Integrand(), 2, Rational(0), Rational(1)), InvalidArgument);
  EXPECT_THROW(integrate_many(f, 2, Rational(1), Rational(0)), InvalidArgument);
  const std::vector<Ball> z = integrate_many(f, 2, Rational(1, 3), Rational(1, 3));
  ASSERT_EQ(z.size(), 2u);
  EXPECT_TRUE(z[0].is_exact() && z[0].contains(Rational(0)) && z[1].contains(Rational(0)));
  // a non-real second integral is a DomainError; an exception from f propagates
  Integrand cplx = [](acb_ptr out, const acb_t z, bool, long prec) {
    acb_set(out, z);
    acb_mul_onei(out + 1, z);
    acb_add_ui(out + 1, out + 1, 1, prec);
  };
  EXPECT_THROW(integrate_many(cplx, 2, Rational(0), Rational(1)), DomainError);
  Integrand thrower = [](acb_ptr, const acb_t, bool, long) { throw BudgetExceeded("from the integrand"); };
  EXPECT_THROW(integrate_many(thrower, 2, Rational(0), Rational(1)), BudgetExceeded);
}

// ---------------------------------------------------------------------------
// QuadratureOptions::node_fast (double-word nodes) and singularity_hints

/// p and its node path: DDPoly (Horner in double-word balls) on the nodes,
/// counting the nodes it answers; refuse_every > 0 refuses every such call.
NodeIntegrand poly_nodes(const std::vector<long>& c, long* answered, long refuse_every = 0) {
  auto dp = std::make_shared<DDPoly>(Poly(c));
  auto calls = std::make_shared<long>(0);
  return [dp, answered, refuse_every, calls](DDBall* out, const DDBall& t, long prec) {
    if (refuse_every > 0 && (*calls)++ % refuse_every == 0) return false;
    if (!dp->eval(out, nullptr, nullptr, t)) return false;
    if (!(dd_rel_rad(out[0]) <= std::ldexp(1.0, -static_cast<int>(prec - kNodeFastSlackBits)))) return false;
    ++*answered;
    return true;
  };
}

TEST(QuadratureNodes, DoubleWordNodesContainTheExactIntegral) {
  // Random polynomials, several integrals at once (p, 3p, p with refusals):
  // the weighted double-word sums must hold the exact integrals and meet
  // the goal, with the Integrand left only the error bounds (or the
  // refused nodes).
  std::mt19937 rng(20261123u);
  std::uniform_int_distribution<long> coef(-9, 9), num(-30, 30), den(1, 12), deg(0, 9);
  const long n = iterations(30);
  for (long it = 0; it < n; ++it) {
    std::vector<long> c(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : c) x = coef(rng);
    c.back() = c.back() == 0 ? 1 : c.back();
    Rational a(num(rng), den(rng)), b(num(rng), den(rng));
    if (b < a) std::swap(a, b);
    if (a == b) continue;
    const Rational exact = exact_poly_integral(c, a, b);
    if (exact.is_zero()) continue;
    for (long refuse : {0L, 3L}) {
      SCOPED_TRACE("iteration " + std::to_string(it) + " poly " + str(c) + " on [" + a.str() + ", " + b.str() +
                   "] refusing every " + std::to_string(refuse));
      long answered = 0, narrow_calls = 0;
      const Integrand arb_f = poly_integrand(c);
      // A point: a narrow real ball, or the small ball around an end that
      // the end's bound tries first (radius <= 2^-10; the quadrature's own
      // segments are far wider here).
      auto is_point = [&](const acb_t z, bool analytic) {
        if (analytic || !acb_is_real(z)) return false;
        const mag_struct* rad = arb_radref(acb_realref(z));
        return mag_cmp_2exp_si(rad, -30) < 0 ||
               (mag_cmp_2exp_si(rad, -10) <= 0 &&
                (arb_contains_fmpq(acb_realref(z), a.get()) || arb_contains_fmpq(acb_realref(z), b.get())));
      };
      Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
        if (is_point(z, analytic)) ++narrow_calls;
        arb_f(out, z, analytic, prec);
      };
      QuadratureOptions opt;
      opt.rel_goal_bits = 53;
      opt.node_fast = poly_nodes(c, &answered, refuse);
      const Ball r = integrate(f, a, b, opt);
      EXPECT_TRUE(r.contains(exact)) << r.str(30) << " exact " << exact.str();
      EXPECT_TRUE(meets_rel(r, 53)) << r.str(30);
      EXPECT_GT(answered, 0);
      // Each node goes to one path: the Integrand sees as many narrow balls
      // as without the node path, less the nodes it answered.
      long plain_calls = 0;
      Integrand g = [&](acb_t out, const acb_t z, bool analytic, long prec) {
        if (is_point(z, analytic)) ++plain_calls;
        arb_f(out, z, analytic, prec);
      };
      QuadratureOptions plain_opt;
      plain_opt.rel_goal_bits = 53;
      const Ball plain = integrate(g, a, b, plain_opt);
      EXPECT_TRUE(plain.contains(exact));
      EXPECT_EQ(narrow_calls + answered, plain_calls);
      if (refuse > 0) EXPECT_GT(narrow_calls, plain_calls / 4);
    }
  }
}

TEST(QuadratureNodes, TheProbeAndTheEndsAskTheNodePathFirst) {
  // Every narrow real point (nodes, the start-precision probe's points, the
  // enclosures of non-dyadic ends) goes to node_fast first. Here it answers
  // all of them, at the contract's limit of accuracy (relative radius
  // 2^-(prec - 21)): the Integrand must get no narrow ball, and the probe
  // must not read that radius as cancellation (it would raise the start
  // precision above rel_goal_bits + 32).
  std::mt19937 rng(20261124u);
  std::uniform_int_distribution<long> coef(-9, 9), num(0, 12), deg(0, 7);
  const long n = iterations(20);
  for (long it = 0; it < n; ++it) {
    std::vector<long> c(static_cast<std::size_t>(deg(rng)) + 1);
    long sum = 0;
    for (long& x : c) sum += std::labs(x = coef(rng));
    c[0] = sum + 1;  // p >= 1 on [0, 1]: every point can meet the contract
    Rational a(num(rng), 13), b(num(rng), 13);
    if (b < a) std::swap(a, b);
    if (a == b) continue;
    SCOPED_TRACE("iteration " + std::to_string(it) + " poly " + str(c) + " on [" + a.str() + ", " + b.str() + "]");
    long answered = 0, narrow_calls = 0, lowest = 1L << 30, highest = 0;
    const Integrand arb_f = poly_integrand(c);
    Integrand f = [&](acb_t out, const acb_t z, bool analytic, long prec) {
      if (!analytic && acb_is_real(z) && mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) < 0) ++narrow_calls;
      arb_f(out, z, analytic, prec);
    };
    NodeIntegrand exact_nodes = poly_nodes(c, &answered);
    QuadratureOptions opt;
    opt.rel_goal_bits = 53;
    opt.node_fast = [&](DDBall* out, const DDBall& t, long prec) {
      if (!exact_nodes(out, t, prec)) return false;
      lowest = std::min(lowest, prec);
      highest = std::max(highest, prec);
      out[0].rad = std::max(out[0].rad, std::fabs(out[0].hi) * std::ldexp(1.0, -static_cast<int>(prec - 21)));
      return true;
    };
    const Ball r = integrate(f, a, b, opt);
    const Rational exact = exact_poly_integral(c, a, b);
    EXPECT_TRUE(r.contains(exact)) << r.str(30) << " exact " << exact.str();
    EXPECT_TRUE(meets_rel(r, 53)) << r.str(30);
    EXPECT_GT(answered, 0);
    EXPECT_EQ(narrow_calls, 0);
    EXPECT_EQ(lowest, 53 + 32);
    EXPECT_EQ(highest, 53 + 32);
  }
}

TEST(QuadratureNodes, AWrongNodePathIsCaughtByTheExactIntegral) {
  // DoubleWordNodesContainTheExactIntegral can fail: a node path that
  // answers p + 2^-40 (a ball that misses p(t)) gives an enclosure that
  // misses the exact integral.
  const std::vector<long> c = {1, -3, 0, 5};  // integral 3/4 on [0, 1]
  long answered = 0;
  NodeIntegrand good = poly_nodes(c, &answered);
  QuadratureOptions opt;
  opt.rel_goal_bits = 60;  // working precision 92 <= kNodeFastMaxPrec
  opt.node_fast = [&good](DDBall* out, const DDBall& t, long prec) {
    if (!good(out, t, prec)) return false;
    out[0] = dd_add(out[0], dd_from_double(0x1p-40));
    return true;
  };
  const Rational exact = exact_poly_integral(c, Rational(0), Rational(1));
  const Ball r = integrate(poly_integrand(c), Rational(0), Rational(1), opt);
  EXPECT_GT(answered, 0);
  EXPECT_FALSE(r.contains(exact)) << r.str(30);
}

/// 1 / ((t - 1/2)^2 + a^2): poles at 1/2 +- a i; counts the error bounds
/// (analytic calls) and those that were not finite.
struct PolePair {
  Rational a2;  // a^2
  long ellipses = 0, failed = 0, points = 0;  // points: the calls off the ellipses
  Integrand f() {
    return [this](acb_t out, const acb_t z, bool analytic, long prec) {
      acb_t h;
      acb_init(h);
      acb_set_d(h, 0.5);
      acb_sub(out, z, h, prec);
      acb_mul(out, out, out, prec);
      arb_set_fmpq(acb_realref(h), a2.get(), prec);
      arb_zero(acb_imagref(h));
      acb_add(out, out, h, prec);
      acb_inv(out, out, prec);
      acb_clear(h);
      if (analytic) {
        ++ellipses;
        if (!acb_is_finite(out)) ++failed;
      } else {
        ++points;
      }
    };
  }
};

void pole_pair_reference(arb_t ref, const Rational& a2) {  // (2 / a) atan(1 / (2 a)) on [0, 1]
  arb_t a;
  arb_init(a);
  arb_set_fmpq(a, a2.get(), 256);
  arb_sqrt(a, a, 256);
  arb_mul_2exp_si(ref, a, 1);
  arb_inv(ref, ref, 256);
  arb_atan(ref, ref, 256);
  arb_mul_2exp_si(ref, ref, 1);
  arb_div(ref, ref, a, 256);
  arb_clear(a);
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

TEST(QuadratureMany, EachIntegralGetsItsOwnErrorBound) {
  // integrate_many bounds each integral's Gauss-Legendre error with its own
  // bound M_k on the ellipse. Next to a tiny constant (M_0 ~ 2^-200), an
  // integrand with poles near [0, 1] bounded with M_0 would get a radius far
  // below its true error, and its ball would miss the true value. The
  // working precision is set far above the goal, so that the nodes' own
  // radii (2^-prec) cannot cover that error either.
  for (long inv_a : {4L, 8L, 20L}) {
    for (long goal : {20L, 40L, 53L}) {
      const Rational a2(1, inv_a * inv_a);
      PolePair p{a2};
      const Integrand pole = p.f();
      Integrand f = [&pole](acb_ptr out, const acb_t z, bool analytic, long prec) {
        acb_one(out);
        acb_mul_2exp_si(out, out, -200);
        pole(out + 1, z, analytic, prec);
      };
      QuadratureOptions opt;
      opt.rel_goal_bits = goal;
      opt.initial_prec = 256;
      const std::vector<Ball> r = integrate_many(f, 2, RealAlgebraic(0), RealAlgebraic(1), opt);
      arb_t ref, tiny;
      arb_init(ref);
      arb_init(tiny);
      pole_pair_reference(ref, a2);
      arb_one(tiny);
      arb_mul_2exp_si(tiny, tiny, -200);
      SCOPED_TRACE("a = 1/" + std::to_string(inv_a) + ", goal " + std::to_string(goal) + " bits");
      EXPECT_TRUE(overlaps(r[0], tiny)) << r[0].str(30);
      EXPECT_TRUE(overlaps(r[1], ref)) << r[1].str(30);
      EXPECT_TRUE(meets_rel(r[1], goal)) << r[1].str(30);
      arb_clear(ref);
      arb_clear(tiny);
    }
  }
}

}  // namespace
}  // namespace uniparam
