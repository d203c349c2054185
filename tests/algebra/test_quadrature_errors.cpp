// Tests of uniparam/algebra/quadrature.hpp: what integrate() does when it
// cannot or must not answer (budgets, invalid arguments, the integrand's
// exceptions, non-real values, poles on the segment), and the error bound
// at a non-dyadic end.
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
  Integrand f = test_support::near_pole_integrand;
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

}  // namespace
}  // namespace uniparam
