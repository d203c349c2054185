// Tests of the refinement of isolating intervals with a scaled evaluator
// (root_refine.hpp: interval Newton steps, Moore's existence test, the
// bisections across zeros of f'), the Descartes test in double against the
// exact shift, and the evaluator's end checks of RealAlgebraic.
#include <arb_fmpz_poly.h>
#include <arb_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "root_refine.hpp"  // private to the algebra layer: detail::prove_root_near
#include "support/iterations.hpp"
#include "support/known_roots.hpp"
#include "algebra/real_roots_support.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using real_roots_test::bernstein;
using real_roots_test::centred_product_evaluator;
using real_roots_test::expect_refined_like_exact;
using real_roots_test::five_real_roots_and_complex_pairs;
using real_roots_test::grid_cell_root;
using real_roots_test::positive_bernstein;
using test_support::iterations;

/// Refinement with a ScaledEvaluator (interval Newton steps, derivative from
/// the factors, no exact sign) against the exact refinement of the same
/// root: at every precision the interval is narrow enough, still brackets
/// the root (exact signs of p at its ends differ), and to_ball, canonical,
/// gives the same ball as the exact path. p has degree ~100 with Bernstein
/// factors (large power-basis coefficients), irrational roots, complex
/// pairs near [0, 1], and the evaluator a random rational factor c (of
/// either sign) that lambda must carry. Fails when lambda is ignored or its
/// sign is dropped, when the new lower end is moved inward, or when f is
/// evaluated at the Newton guess but N is formed at the midpoint. The
/// constructor's check of the ends (by the evaluator first) still refuses
/// intervals with no root or two; fails when one decided end is taken as
/// enough.
TEST(RealRootsFast, ScaledEvaluatorRefinesLikeTheExactPath) {
  std::mt19937_64 rng(4242);
  for (long it = 0; it < iterations(3); ++it) {
    std::vector<Poly> factors = five_real_roots_and_complex_pairs(rng, 5);
    // a positive Bernstein polynomial of degree 80: no root in [0, 1]
    factors.push_back(bernstein(positive_bernstein(rng, 80, 1000)));
    Poly p(1);
    for (const Poly& f : factors) p = p * f;
    const Rational c(static_cast<long>(rng() % 2 ? 1 : -1) * static_cast<long>(1 + rng() % 97),
                     static_cast<long>(1 + rng() % 89));
    long calls = 0;
    ScaledEvaluator sev;
    sev.ev = centred_product_evaluator(factors, c, &calls);
    const Poly f = p.primitive();
    sev.lambda = c * Rational(p.leading()) / Rational(f.leading());
    const auto shared = std::make_shared<const ScaledEvaluator>(sev);
    const std::vector<IsolatedRoot> roots = isolate_real_roots(p, Rational(0), Rational(1));
    ASSERT_EQ(roots.size(), 5u);
    int checked = 0;
    for (const IsolatedRoot& r0 : roots) {
      ASSERT_FALSE(r0.is_exact());
      // start from the grid interval of width 2^-12 around the root (the
      // isolator's intervals may already be far narrower)
      const std::optional<IsolatedRoot> cell = grid_cell_root(p, f, r0);
      if (!cell) continue;
      const IsolatedRoot& r = *cell;
      const RealAlgebraic fast(r, shared), exact(r);
      ++checked;
      for (long bits : {40L, 130L, 400L}) {
        SCOPED_TRACE("iteration " + std::to_string(it) + ", root in " + r.lo.str() + ".., bits " +
                     std::to_string(bits));
        const long before = calls;
        fast.refine(bits);
        // The evaluator's steps ran: each takes one call (the first
        // refinement, from 2^-12, may take only the double start's proof).
        EXPECT_GE(calls - before, 1);
        expect_refined_like_exact(p, r, fast, exact, bits);
      }
    }
    EXPECT_GE(checked, 3);  // a root sharing its 2^-12 cell is skipped: most must be checked
    // The constructor checks the ends with the evaluator first: an interval
    // with no root or with two (no sign change), ends far from the roots
    // (where the evaluator decides the signs), is still refused, and an
    // isolating one is accepted.
    std::vector<RealAlgebraic> xs;
    for (const IsolatedRoot& r0 : roots) {
      xs.emplace_back(r0);
      xs.back().refine(30);
    }
    auto between = [&](std::size_t k) {  // a rational a quarter of the way from root k to root k + 1
      return xs[k].hi() + (xs[k + 1].lo() - xs[k].hi()) * Rational(1, 4);
    };
    auto between_r = [&](std::size_t k) {  // three quarters of the way
      return xs[k].hi() + (xs[k + 1].lo() - xs[k].hi()) * Rational(3, 4);
    };
    for (std::size_t k = 0; k + 2 < xs.size(); ++k) {
      SCOPED_TRACE("after root " + std::to_string(k));
      ASSERT_EQ(count_real_roots(p, between(k), between_r(k)), 0);
      EXPECT_THROW(RealAlgebraic(IsolatedRoot{between(k), between_r(k), f, 1}, shared), InvalidArgument);
      if (k + 3 < xs.size()) {  // roots k + 1 and k + 2 inside
        ASSERT_EQ(count_real_roots(p, between(k), between(k + 2)), 2);
        EXPECT_THROW(RealAlgebraic(IsolatedRoot{between(k), between(k + 2), f, 1}, shared), InvalidArgument);
      }
      const RealAlgebraic good(IsolatedRoot{between_r(k), between(k + 1), f, 1}, shared);
      EXPECT_EQ(compare(good, xs[k + 1]), 0);
    }
  }
}

/// Descartes' test (root_refine.hpp), double first, against the exact shift
/// on polynomials whose shifted coefficients cancel by 100-400 bits: P =
/// reverse(S(x - 1)) for S = prod (1000 x + a_i) (a_i in 1..5: no sign
/// change), times (1000 x - b) for one, reverse((x - 1)^m +- c x^j) (exact
/// doubles whose shift x^m +- c (x + 1)^j comes from partial sums ~2^50
/// times larger), and random dense ones (mixed magnitudes up to 2^300).
/// Fails when signs are taken as known without an error bound, or when a
/// count with unknown signs is taken as final. (Either half of the bound,
/// the inputs' rounding or the additions', covers the other's size on all
/// of these: no test here tells them apart.)
TEST(RealRootsFast, DescartesTestInDoubleAgreesWithTheExactShift) {
  std::mt19937_64 rng(90210);
  auto exact = [](const Poly& P, int& s1) {
    Poly R, S;
    fmpz_poly_reverse(R.get(), P.get(), P.degree() + 1);
    fmpz_poly_taylor_shift(S.get(), R.get(), Integer(1).get());
    s1 = fmpz_sgn(S.get()->coeffs);
    int var = 0, last = 0;
    for (slong i = 0; i < S.get()->length; ++i) {
      const int sg = fmpz_sgn(S.get()->coeffs + i);
      if (sg == 0) continue;
      if (last != 0 && sg != last && ++var >= 2) return 2;
      last = sg;
    }
    return var;
  };
  long low = 0;
  for (long it = 0; it < iterations(300); ++it) {
    Poly P;
    const int kind = static_cast<int>(it % 4);
    if (kind == 3) {
      // R = (x - 1)^m + delta x^j, coefficients exact in double, so that
      // S = R(x + 1) = x^m + delta (x + 1)^j: small integers the shift
      // computes from partial sums of up to ~2^(m+20), by cancellation
      const long m = 30 + static_cast<long>(rng() % 21), j = static_cast<long>(rng() % 20);
      const long delta = (rng() % 2 ? 1 : -1) * (1 + static_cast<long>(rng() % 3));
      Poly R = Poly(std::vector<long>{-1, 1}).pow(m) + Poly(delta) * Poly::t().pow(j);
      fmpz_poly_reverse(P.get(), R.get(), R.degree() + 1);
    } else if (kind < 2) {
      const long m = 2 + static_cast<long>(rng() % 40);
      Poly S(1);
      for (long i = 0; i < m; ++i) S = S * Poly(std::vector<long>{1 + static_cast<long>(rng() % 5), 1000});
      if (kind == 1) S = S * Poly(std::vector<long>{-(1 + static_cast<long>(rng() % 999)), 1000});
      Poly R;
      fmpz_poly_taylor_shift(R.get(), S.get(), Integer(-1).get());
      fmpz_poly_reverse(P.get(), R.get(), R.degree() + 1);
    } else {
      const long n = 1 + static_cast<long>(rng() % 300);
      std::vector<Integer> c;
      for (long k = 0; k <= n; ++k) {
        Integer v(static_cast<long>(rng() % 2001) - 1000);
        fmpz_mul_2exp(v.get(), v.get(), rng() % 300);
        c.push_back(v);
      }
      if (c.back().sign() == 0) c.back() = Integer(1);
      P = Poly(c);
    }
    SCOPED_TRACE("iteration " + std::to_string(it) + ", kind " + std::to_string(kind) + ", degree " +
                 std::to_string(P.degree()));
    int s_fast = 9, s_exact = 9;
    const int v_fast = detail::descartes_test(P, s_fast), v_exact = exact(P, s_exact);
    EXPECT_EQ(v_fast, v_exact);
    if (v_exact <= 1) {
      EXPECT_EQ(s_fast, s_exact);
      ++low;
    }
  }
  EXPECT_GT(low, iterations(300) / 3);  // the products and the last kind: 0 or 1 sign change
}

/// Moore's existence test (root_refine.hpp), the proof the refinement's
/// double-precision start needs before it is used: on a degree-~100
/// product with five real roots in (0, 1), an interval around a random
/// centre is accepted only when it holds a root (exact signs at the new
/// ends differ, inside the old), and a narrow one around each root is
/// accepted and narrowed. Fails when an interval is accepted unproven.
TEST(RealRootsFast, ProveRootNearAcceptsOnlyIntervalsThatHoldARoot) {
  std::mt19937_64 rng(777);
  long accepted = 0, refused = 0, calls = 0;
  for (long it = 0; it < iterations(3); ++it) {
    std::vector<Poly> factors = five_real_roots_and_complex_pairs(rng, 5);
    factors.push_back(bernstein(positive_bernstein(rng, 80, 1000)));
    Poly p(1);
    for (const Poly& f : factors) p = p * f;
    ScaledEvaluator sev;
    sev.ev = centred_product_evaluator(factors, Rational(3), &calls);
    const Poly f = p.primitive();
    sev.lambda = Rational(3) * Rational(p.leading()) / Rational(f.leading());
    auto check = [&](const Rational& g, const Rational& d, bool must) {
      SCOPED_TRACE("iteration " + std::to_string(it) + ", g = " + g.str() + ", d = " + d.str());
      Rational lo(-7), hi(-7);
      const bool ok = detail::prove_root_near(f, sev, g, d, 120, lo, hi);
      if (must) EXPECT_TRUE(ok);
      if (!ok) {
        EXPECT_TRUE(lo == Rational(-7) && hi == Rational(-7));
        ++refused;
        return;
      }
      ++accepted;
      EXPECT_TRUE(g - d <= lo && lo < hi && hi <= g + d);
      EXPECT_EQ(f.sign_at(lo) * f.sign_at(hi), -1);
      if (must) EXPECT_TRUE((hi - lo) * Rational(1L << 20) <= d);  // a narrow start gains > 20 bits
    };
    for (int k = 0; k < 60; ++k) {  // random centres on the grid 2^-24, radii 2^-4 .. 2^-30
      const Rational g(static_cast<long>(rng() % (1L << 24)), 1L << 24);
      check(g, pow2(-4 - static_cast<long>(rng() % 27)), false);
    }
    for (const IsolatedRoot& r : isolate_real_roots(p, Rational(0), Rational(1))) {
      RealAlgebraic x(r);
      x.refine(70);
      check(x.lo(), pow2(-40), true);  // |x - lo| <= 2^-70
    }
  }
  EXPECT_GT(accepted, 0);
  EXPECT_GT(refused, 0);
}

TEST(RealRootsFast, ScaledEvaluatorRefinesAcrossZerosOfTheDerivative) {
  // f = (2 t^2 - 1) (10^6 (5 t - 3)^2 + 25) B(t), B a positive Bernstein
  // polynomial of degree 80: one root, 1/sqrt(2), in (1/2, 1), and f' has
  // two zeros there too (near 0.600004 and 0.83: the sharp dip of the
  // quadratic at 3/5). On such an interval the interval Newton step's f'
  // bound holds 0; refinement bisects by signs until it does not, then
  // continues with Newton steps. The result must be the exact path's.
  std::mt19937_64 rng(777);
  for (long it = 0; it < iterations(3); ++it) {
    const long big = 1000000 * (1 + it);
    std::vector<Poly> factors = {Poly(std::vector<long>{-1, 0, 2}),
                                 Poly(std::vector<long>{9 * big + 25, -30 * big, 25 * big}),
                                 bernstein(positive_bernstein(rng, 80, 1000))};
    Poly p(1);
    for (const Poly& g : factors) p = p * g;
    const Poly f = p.primitive();
    long calls = 0;
    ScaledEvaluator sev;
    const Rational c(1 + static_cast<long>(rng() % 50), 1 + static_cast<long>(rng() % 50));
    sev.ev = centred_product_evaluator(factors, c, &calls);
    sev.lambda = c * Rational(p.leading()) / Rational(f.leading());
    const auto shared = std::make_shared<const ScaledEvaluator>(sev);
    const IsolatedRoot r{Rational(1, 2), Rational(1), f, 1};
    ASSERT_EQ(count_real_roots(p, r.lo, r.hi), 1);
    const RealAlgebraic fast(r, shared), exact(r);
    for (long bits : {40L, 130L}) {
      SCOPED_TRACE("iteration " + std::to_string(it) + ", bits " + std::to_string(bits));
      const long before = calls;
      fast.refine(bits);
      EXPECT_GE(calls - before, 1);  // the Newton steps ran (with the evaluator's f')
      expect_refined_like_exact(p, r, fast, exact, bits);
    }
  }
}

TEST(RealRootsFast, LowDegreeNewtonStepsBoundTheDerivativeFromThePowerBasis) {
  // Up to degree 64 of f', an interval Newton step bounds f' on the interval
  // from the power basis, not from the evaluator: the refinement must give
  // the exact path's enclosures (to_ball depends on the number alone) and
  // still isolate the root, with the evaluator called for the ends' check
  // at construction only.
  std::mt19937_64 rng(4243);
  for (long it = 0; it < iterations(6); ++it) {
    std::vector<Poly> factors = five_real_roots_and_complex_pairs(rng, 3);
    Poly p(1);
    for (const Poly& f : factors) p = p * f;
    ASSERT_LE(p.degree() - 1, 64);
    long calls = 0;
    ScaledEvaluator sev;
    sev.ev = centred_product_evaluator(factors, Rational(1), &calls);
    const Poly f = p.primitive();
    sev.lambda = Rational(p.leading()) / Rational(f.leading());
    const auto shared = std::make_shared<const ScaledEvaluator>(sev);
    for (const IsolatedRoot& r0 : isolate_real_roots(p, Rational(0), Rational(1))) {
      // start from the grid interval of width 2^-12 around the root (the
      // isolator's intervals may already be far narrower)
      const std::optional<IsolatedRoot> cell = grid_cell_root(p, f, r0);
      if (!cell) continue;
      const IsolatedRoot& r = *cell;
      const RealAlgebraic fast(r, shared), exact(r);
      const long after_construction = calls;
      for (long bits : {40L, 130L, 400L}) {
        SCOPED_TRACE("iteration " + std::to_string(it) + ", root in " + r.lo.str() + ".., bits " +
                     std::to_string(bits));
        fast.refine(bits);
        expect_refined_like_exact(p, r, fast, exact, bits);
      }
      EXPECT_EQ(calls, after_construction);
    }
  }
}

// The ends' signs by the evaluator must hold for the exact end, even where
// its 64-bit ball is rounded by more than the evaluator's 2^-23 radius:
// lo = 2^50 + 2/3 rounds ~2^-14 below itself, and the only root of f lies
// 2^-40 below lo, so [lo, hi] isolates nothing (f > 0 at both ends). A ball
// centred on the rounded lo with radius 2^-23 lies left of the root and
// would show f < 0 there, accepting the interval.
TEST(RealRootsFast, EvaluatorEndChecksHoldForFarEnds) {
  const Rational lo = Rational(1L << 50) + Rational(2, 3), hi = lo + Rational(1, 2);
  Rational eps(1);
  fmpq_div_2exp(eps.get(), eps.get(), 40);
  const Rational r = lo - eps;
  // f = den(r) t - num(r), exact; its evaluator is Arb's at the ball
  const Poly f(std::vector<Integer>{Integer(0) - Integer(fmpq_numref(r.get())), Integer(fmpq_denref(r.get()))});
  ScaledEvaluator sev;
  sev.lambda = Rational(1);
  sev.ev = [f](arb_t v, arb_t d, const arb_t x, long) {
    arb_fmpz_poly_evaluate_arb(v, f.get(), x, 512);  // tight: f's 2^90 coefficients cancel
    if (d) arb_set_fmpz(d, f.get()->coeffs + 1);
  };
  IsolatedRoot bad{lo, hi, f, 1};
  EXPECT_THROW(RealAlgebraic(bad, std::make_shared<const ScaledEvaluator>(sev)), InvalidArgument);
  // the same check without the evaluator (exact signs) refuses it too
  EXPECT_THROW(RealAlgebraic{bad}, InvalidArgument);
}

}  // namespace
}  // namespace uniparam
