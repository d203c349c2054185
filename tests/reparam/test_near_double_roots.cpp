// A speed whose factors come close to a double root inside (0, 1): the
// arc length of the bump ((1 + t^2) / (1 + C (t - c)^2), t). Its speed
// sqrt(x'^2 + 1) has branch points at distance about 1/(2C) from the real
// axis next to c, so the quadrature runs down to subintervals of that width;
// there the power basis of 1 + C (t - c)^2 (and the cells' expansions about
// centres farther away than the subinterval) multiply the subinterval's
// radius by about C instead of by the factor's small derivative, and the
// error bounds fail on every subinterval of a whole neighbourhood of c.
#include <acb_calc.h>
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "support/iterations.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

struct Bump {
  arb_t C, c;
};

// sigma(z) = sqrt(x'(z)^2 + 1), x' = (2 z Q - (1 + z^2) 2 C (z - c)) / Q^2,
// Q = 1 + C (z - c)^2, written in z - c (no power basis); analytic where
// asked (the branch points off the real axis).
int bump_speed(acb_ptr out, const acb_t z, void* param, slong order, slong prec) {
  const Bump& b = *static_cast<const Bump*>(param);
  acb_t d, q, n, x;
  acb_init(d);
  acb_init(q);
  acb_init(n);
  acb_init(x);
  acb_sub_arb(d, z, b.c, prec);
  acb_sqr(q, d, prec);
  acb_mul_arb(q, q, b.C, prec);
  acb_add_ui(q, q, 1, prec);  // Q
  acb_mul(x, z, q, prec);
  acb_mul_2exp_si(x, x, 1);  // 2 z Q
  acb_sqr(n, z, prec);
  acb_add_ui(n, n, 1, prec);
  acb_mul(n, n, d, prec);
  acb_mul_arb(n, n, b.C, prec);
  acb_mul_2exp_si(n, n, 1);  // (1 + z^2) 2 C (z - c)
  acb_sub(x, x, n, prec);
  acb_sqr(q, q, prec);
  acb_div(x, x, q, prec);  // x'
  acb_sqr(x, x, prec);
  acb_add_ui(x, x, 1, prec);
  acb_sqrt_analytic(out, x, order != 0, prec);
  acb_clear(d);
  acb_clear(q);
  acb_clear(n);
  acb_clear(x);
  return 0;
}

}  // namespace

// For random C of 9 to 20 digits and random rational c, the certified arc
// length finishes (within a TimeBudget: on an engine whose narrow balls wrap,
// it bisects until the budget runs out from C of about 10^9.5) and overlaps
// Arb's own quadrature of the integrand above.
TEST(NearDoubleRoot, ArcLengthOfARationalBumpMatchesAnIndependentQuadrature) {
  TimeBudget budget(60);
  std::mt19937 rng(20261204);
  for (int trial = 0; trial < 6; ++trial) {
    const std::string C = test_support::random_positive_digits(rng, 9 + static_cast<int>(rng() % 12));
    const Rational c = test_support::random_inner_rational(rng);
    const Curve p = Curve::parse("((1 + t^2)/(1 + " + C + "*(t - " + c.str() + ")^2), t)");
    SCOPED_TRACE(p.str());
    Options opt;
    opt.digits = 15;
    const UniformityResult r = uniformity(p, SpeedKind::Parametric, opt);
    EXPECT_TRUE(r.mu.meets_digits(15)) << r.mu.str(25);

    Bump b;
    arb_init(b.C);
    arb_init(b.c);
    arb_set_str(b.C, C.c_str(), 256);
    arb_set_fmpq(b.c, c.get(), 256);
    acb_t want, lo, hi;
    acb_init(want);
    acb_init(lo);
    acb_init(hi);
    acb_one(hi);
    mag_t tol;
    mag_init(tol);
    mag_set_ui_2exp_si(tol, 1, -70);
    acb_calc_integrate_opt_t o;
    acb_calc_integrate_opt_init(o);
    o->depth_limit = 400;
    o->eval_limit = 10000000;
    const int status = acb_calc_integrate(want, bump_speed, &b, lo, hi, 70, tol, o, 128);
    ASSERT_EQ(status, ARB_CALC_SUCCESS);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), acb_realref(want)));
    mag_clear(tol);
    acb_clear(want);
    acb_clear(lo);
    acb_clear(hi);
    arb_clear(b.C);
    arb_clear(b.c);
  }
}
