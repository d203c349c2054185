// Helpers shared by the real-root tests (test_real_roots_fast.cpp,
// test_root_refine.cpp): Bernstein polynomials in the power basis,
// evaluators of products of known factors, and the checks against the exact
// path.
#pragma once

#include <arb.h>
#include <arb_fmpz_poly.h>
#include <arb_poly.h>
#include <flint/fmpz.h>
#include <gtest/gtest.h>

#include <optional>
#include <random>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::real_roots_test {

/// sum b_i C(n, i) t^i (1 - t)^(n - i) in the power basis.
inline Poly bernstein(const std::vector<Integer>& b) {
  const long n = static_cast<long>(b.size()) - 1;
  std::vector<Integer> a(static_cast<std::size_t>(n + 1));
  for (long i = 0; i <= n; ++i) {
    Integer cni;
    fmpz_bin_uiui(cni.get(), static_cast<ulong>(n), static_cast<ulong>(i));
    const Integer bi = b[static_cast<std::size_t>(i)] * cni;
    for (long k = i; k <= n; ++k) {  // C(n-i, k-i) (-1)^(k-i) t^k
      Integer c;
      fmpz_bin_uiui(c.get(), static_cast<ulong>(n - i), static_cast<ulong>(k - i));
      const Integer term = bi * c;
      Integer& ak = a[static_cast<std::size_t>(k)];
      if ((k - i) % 2 == 0) ak = ak + term;
      else ak = ak - term;
    }
  }
  return Poly(a);
}

/// Bernstein coefficients in [1, top]: the polynomial is positive on [0, 1]
/// (convex hull), so its only roots there are the known factors' roots; small
/// coefficients next to large ones put complex roots close to [0, 1].
inline std::vector<Integer> positive_bernstein(std::mt19937_64& rng, long n, long top) {
  std::vector<Integer> b;
  for (long i = 0; i <= n; ++i) b.emplace_back(static_cast<long>(1 + rng() % static_cast<unsigned long>(top)));
  return b;
}

/// p = prod f_i and p' from the factors' own values (product rule), each
/// low-degree factor by Horner: an evaluator that never expands p.
inline PolyEvaluator product_evaluator(const std::vector<Poly>& factors, long* calls) {
  return [factors, calls](arb_t v, arb_t d, const arb_t x, long prec) {
    ++*calls;
    arb_t f, df;
    arb_init(f);
    arb_init(df);
    arb_one(v);
    if (d) arb_zero(d);
    for (const Poly& q : factors) {
      arb_fmpz_poly_evaluate_arb(f, q.get(), x, prec);
      if (d) {
        arb_fmpz_poly_evaluate_arb(df, q.derivative().get(), x, prec);
        arb_mul(d, d, f, prec);  // (P f)' = P' f + P f'
        arb_addmul(d, v, df, prec);
      }
      arb_mul(v, v, f, prec);
    }
    arb_clear(f);
    arb_clear(df);
  };
}


/// c p and c p' for p = prod f_i from the factors' Taylor expansions at the
/// midpoint of x (a centred form: as tight on a wide ball as p's variation
/// there, like the speeds' local expansions), never expanding p.
inline PolyEvaluator centred_product_evaluator(const std::vector<Poly>& factors, const Rational& c, long* calls) {
  return [factors, c, calls](arb_t v, arb_t d, const arb_t x, long prec) {
    ++*calls;
    arb_t f, df, r, cb;
    arb_init(f);
    arb_init(df);
    arb_init(r);
    arb_init(cb);
    arb_zero(r);
    mag_set(arb_radref(r), arb_radref(x));  // [-rad x, rad x]
    arb_set_fmpq(cb, c.get(), prec);
    arb_set(v, cb);
    if (d) arb_zero(d);
    for (const Poly& q : factors) {
      const long wp = prec + q.max_bits() + 2 * q.degree() + 64;  // the shift loses ~max_bits + degree bits
      arb_poly_t a, a1;
      arb_poly_init(a);
      arb_poly_init(a1);
      arb_poly_set_fmpz_poly(a, q.get(), wp);
      arb_t m;
      arb_init(m);
      arb_set_arf(m, arb_midref(x));
      arb_poly_taylor_shift(a, a, m, wp);  // q(mid + w)
      arb_clear(m);
      arb_poly_evaluate(f, a, r, prec);
      if (d) {
        arb_poly_derivative(a1, a, wp);
        arb_poly_evaluate(df, a1, r, prec);
        arb_mul(d, d, f, prec);  // (P q)' = P' q + P q'
        arb_addmul(d, v, df, prec);
      }
      arb_mul(v, v, f, prec);
      arb_poly_clear(a);
      arb_poly_clear(a1);
    }
    arb_clear(f);
    arb_clear(df);
    arb_clear(r);
    arb_clear(cb);
  };
}

// The grid cell [k, k + 1] 2^-12 holding the root r0 of p, as a root of f
// (p's primitive part), when it isolates that root; nothing otherwise (a
// root sharing its cell).
inline std::optional<IsolatedRoot> grid_cell_root(const Poly& p, const Poly& f, const IsolatedRoot& r0) {
  const RealAlgebraic x0(r0);
  x0.refine(20);
  const double mid = std::ldexp(fmpq_get_d(x0.lo().get()) + fmpq_get_d(x0.hi().get()), 11);  // 2^12 x
  const Rational lo(static_cast<long>(std::floor(mid)), 4096), hi = lo + Rational(1, 4096);
  if (!(p.sign_at(lo) * p.sign_at(hi) < 0 && count_real_roots(p, lo, hi) == 1)) return std::nullopt;
  return IsolatedRoot{lo, hi, f, 1};
}

// After fast.refine(bits): fast still isolates p's root inside r, is at most
// 2^-bits wide, and its enclosure is the exact path's (to_ball depends on
// the number alone).
inline void expect_refined_like_exact(const Poly& p, const IsolatedRoot& r, const RealAlgebraic& fast,
                               const RealAlgebraic& exact, long bits) {
  ASSERT_TRUE(fast.lo() < fast.hi());
  Rational width(1);
  fmpq_div_2exp(width.get(), width.get(), static_cast<flint_bitcnt_t>(bits));  // 2^-bits
  EXPECT_TRUE(fast.hi() - fast.lo() <= width);
  EXPECT_EQ(p.sign_at(fast.lo()) * p.sign_at(fast.hi()), -1);
  EXPECT_TRUE(r.lo <= fast.lo() && fast.hi() <= r.hi);
  const Ball bf = fast.to_ball(bits), be = exact.to_ball(bits);
  EXPECT_TRUE(arb_equal(bf.get(), be.get())) << bf.str(20) << " vs " << be.str(20);
}

// Factors with five real roots in (0, 1) (sqrt(cc / dd) for cc = 2, 3, 5, 7
// and the cube root of 1/3) and `pairs` quadratics (D t - C)^2 + E^2 with
// complex roots C/D +- i E/D near [0, 1].
inline std::vector<Poly> five_real_roots_and_complex_pairs(std::mt19937_64& rng, int pairs) {
  std::vector<Poly> factors;
  for (long cc : {2L, 3L, 5L, 7L}) {
    const long dd = cc + 1 + static_cast<long>(rng() % 60);
    factors.push_back(Poly(std::vector<Integer>{Integer(-cc), Integer(0), Integer(dd)}));
  }
  factors.push_back(Poly(std::vector<long>{-1, 0, 0, 3}));  // 3 t^3 - 1
  for (int j = 0; j < pairs; ++j) {
    const long D = 1000, C = static_cast<long>(rng() % 1001), E = 1 + static_cast<long>(rng() % 5);
    factors.push_back(Poly(std::vector<Integer>{Integer(C * C + E * E), Integer(-2 * C * D), Integer(D * D)}));
  }
  return factors;
}

}  // namespace uniparam::real_roots_test
