// Tests of integrate_many (uniparam/algebra/quadrature.hpp): several
// integrals over one subdivision, each holding its exact or reference value
// with its own error bound, one integrand call per point for all of them.
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

TEST(QuadratureMany, PolynomialsOfDifferentScalesEachContainTheirExactIntegral) {
  // count random polynomials, one scaled by 10^-12 and one by 10^9, on
  // random rational segments: each result contains its exact integral and
  // meets its own relative goal (a shared tolerance would miss the small one).
  const unsigned seed = test_seed(20261123u);
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
