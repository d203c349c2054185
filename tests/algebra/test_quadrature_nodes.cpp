// Tests of QuadratureOptions::node_fast (uniparam/algebra/quadrature.hpp):
// the nodes in double-word balls hold the exact integrals, are asked first,
// and a wrong node path is caught by the exact integral.
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

}  // namespace
}  // namespace uniparam
