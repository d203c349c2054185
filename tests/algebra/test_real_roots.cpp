// Tests of uniparam/algebra/real_roots.hpp: property tests against products
// of factors with exactly known roots, hard inputs from the literature
// (Wilkinson, Mignotte, clusters) and an independent oracle (Arb's complex
// root finder, used only here).
#include <acb.h>
#include <arb.h>
#include <arb_fmpz_poly.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "support/iterations.hpp"
#include "support/known_roots.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::check_isolation;
using test_support::iterations;
using test_support::Known;

Integer pow_int(long base, unsigned long e) {
  Integer r;
  fmpz_set_si(r.get(), base);
  fmpz_pow_ui(r.get(), r.get(), e);
  return r;
}

Poly lin(long d, long n) { return Poly(std::vector<long>{-n, d}); }  // d t - n
Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }

bool is_rational_square(const Rational& q) {
  return fmpz_is_square(fmpq_numref(q.get())) && fmpz_is_square(fmpq_denref(q.get()));
}

/// Random products of (d t - n)^m and irreducible quadratics (d t^2 - c,
/// irrational roots +-sqrt(c/d), or t^2 + c without real roots).
TEST(RealRoots, RandomProductsOfKnownFactors) {
  std::mt19937_64 rng(20240611);
  const long iters = iterations(150);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 20240611)");
    std::uniform_int_distribution<long> small(1, 12), num(-40, 40), mult(1, 3), count(0, 4);
    std::vector<Known> all;
    Poly p(static_cast<long>(std::uniform_int_distribution<long>(1, 5)(rng)) *
           (rng() % 2 ? 1 : -1));
    // Linear factors with distinct roots.
    const long nl = count(rng);
    for (long i = 0; i < nl; ++i) {
      const Rational q(num(rng), small(rng));
      bool dup = false;
      for (const Known& k : all) dup = dup || (k.rational && k.q == q);
      if (dup) continue;
      const int m = static_cast<int>(mult(rng));
      all.push_back({true, q, 0, m});
      p = p * (lin(1, 0) * constant(q.den()) - constant(q.num())).pow(static_cast<unsigned long>(m));
    }
    // Quadratics with irrational real roots, distinct.
    const long nq = count(rng) / 2 + 1;
    for (long i = 0; i < nq; ++i) {
      const long d = small(rng), c = small(rng) * 3 + 1;
      const Rational r(c, d);
      if (is_rational_square(r)) continue;
      bool dup = false;
      for (const Known& k : all) dup = dup || (!k.rational && k.q == r);
      if (dup) continue;
      const int m = static_cast<int>(mult(rng));
      all.push_back({false, r, 1, m});
      all.push_back({false, r, -1, m});
      p = p * Poly(std::vector<long>{-c, 0, d}).pow(static_cast<unsigned long>(m));
    }
    if (rng() % 2) p = p * Poly(std::vector<long>{small(rng), 0, 1});  // no real roots
    // Interval: random, sometimes with ends exactly at roots.
    Rational a(num(rng), small(rng)), b(num(rng), small(rng));
    if (b < a) std::swap(a, b);
    if (!all.empty() && rng() % 3 == 0) {
      for (const Known& k : all)
        if (k.rational) { if (rng() % 2) a = std::min(a, k.q); else b = std::max(b, k.q); }
      for (const Known& k : all)
        if (k.rational && rng() % 2) { if (k.q <= b) a = k.q; break; }
    }
    if (b < a) std::swap(a, b);
    SCOPED_TRACE("p = " + p.str() + " on [" + a.str() + ", " + b.str() + "]");
    std::vector<IsolatedRoot> got;
    ASSERT_NO_THROW(got = isolate_real_roots(p, a, b));
    check_isolation(p, a, b, all, got);
    if (HasFatalFailure()) return;
    if (a < b) {
      long expect = 0;
      for (const Known& k : all)
        if (cmp(k, a) > 0 && cmp(k, b) < 0) ++expect;
      EXPECT_EQ(count_real_roots(p, a, b), expect);
    }
  }
}

TEST(RealRoots, RootsExactlyAtTheEnds) {
  // (3t - 1)^2 (t - 2) (t^2 - 2) on [1/3, 2]: both ends are roots.
  const Poly p = lin(3, 1).pow(2) * lin(1, 2) * Poly(std::vector<long>{-2, 0, 1});
  const std::vector<Known> all = {{true, Rational(1, 3), 0, 2}, {true, Rational(2), 0, 1},
                                  {false, Rational(2), 1, 1}, {false, Rational(2), -1, 1}};
  check_isolation(p, Rational(1, 3), Rational(2), all, isolate_real_roots(p, Rational(1, 3), Rational(2)));
  // Degenerate interval [a, a].
  auto at = isolate_real_roots(p, Rational(1, 3), Rational(1, 3));
  ASSERT_EQ(at.size(), 1u);
  EXPECT_TRUE(at[0].is_exact());
  EXPECT_EQ(at[0].multiplicity, 2);
  EXPECT_TRUE(isolate_real_roots(p, Rational(1, 2), Rational(1, 2)).empty());
  // Open-interval count excludes the ends.
  EXPECT_EQ(count_real_roots(p, Rational(1, 3), Rational(2)), 1);
  // A dyadic root met as a bisection midpoint, and its neighbours.
  const Poly q = lin(2, 1) * lin(4, 1) * lin(4, 3) * Poly(std::vector<long>{-1, 0, 2});  // 1/2, 1/4, 3/4, 1/sqrt2
  const std::vector<Known> allq = {{true, Rational(1, 2), 0, 1}, {true, Rational(1, 4), 0, 1},
                                   {true, Rational(3, 4), 0, 1}, {false, Rational(1, 2), 1, 1},
                                   {false, Rational(1, 2), -1, 1}};
  check_isolation(q, Rational(0), Rational(1), allq, isolate_real_roots(q, Rational(0), Rational(1)));
}

TEST(RealRoots, InvalidInputs) {
  EXPECT_THROW(isolate_real_roots(Poly(), Rational(0), Rational(1)), InvalidArgument);
  EXPECT_THROW(isolate_real_roots(Poly::t(), Rational(1), Rational(0)), InvalidArgument);
  EXPECT_THROW(count_real_roots(Poly::t(), Rational(0), Rational(0)), InvalidArgument);
  RootIsolationOptions opt;
  opt.max_degree = 3;
  EXPECT_THROW(isolate_real_roots(Poly::t().pow(4) - Poly(2), Rational(0), Rational(2), opt), BudgetExceeded);
  EXPECT_TRUE(isolate_real_roots(Poly(7), Rational(0), Rational(1)).empty());
}

/// prod_{k=1}^{n} (n t - k): the Wilkinson polynomial scaled into [0, 1].
Poly scaled_wilkinson(long n) {
  Poly w(1);
  for (long k = 1; k <= n; ++k) w = w * lin(n, k);
  return w;
}

TEST(RealRoots, WilkinsonScaled) {
  for (long n : {20L, 100L}) {
    SCOPED_TRACE("W_" + std::to_string(n));
    const Poly w = scaled_wilkinson(n);
    std::vector<Known> all;
    for (long k = 1; k <= n; ++k) all.push_back({true, Rational(k, n), 0, 1});
    check_isolation(w, Rational(0), Rational(1), all, isolate_real_roots(w, Rational(0), Rational(1)));
  }
  // Unscaled W_20 on [0, 21] and half of it on [21/2, 20].
  Poly w20(1);
  for (long k = 1; k <= 20; ++k) w20 = w20 * lin(1, k);
  std::vector<Known> all;
  for (long k = 1; k <= 20; ++k) all.push_back({true, Rational(k), 0, 1});
  check_isolation(w20, Rational(0), Rational(21), all, isolate_real_roots(w20, Rational(0), Rational(21)));
  check_isolation(w20, Rational(21, 2), Rational(20), all, isolate_real_roots(w20, Rational(21, 2), Rational(20)));
}

/// Real roots of a squarefree p from Arb's complex root finder (the
/// independent oracle), as balls, ascending.
std::vector<Ball> arb_real_roots(const Poly& p) {
  const slong n = p.degree();
  acb_ptr roots = _acb_vec_init(n);
  arb_fmpz_poly_complex_roots(roots, p.get(), 0, 128);
  std::vector<Ball> out;
  for (slong i = 0; i < n; ++i)
    if (acb_is_real(roots + i)) out.emplace_back(acb_realref(roots + i));
  _acb_vec_clear(roots, n);
  return out;
}

/// Wilkinson's perturbed polynomial 2^23 W_20(t) - t^19: irrational roots,
/// several of them complex; compared with Arb's root finder.
TEST(RealRoots, WilkinsonPerturbedAgainstArb) {
  Poly w20(1);
  for (long k = 1; k <= 20; ++k) w20 = w20 * lin(1, k);
  const Poly p = w20 * Poly(1L << 23) - Poly::t().pow(19);
  const auto got = isolate_real_roots(p, Rational(0), Rational(30));
  const auto ref = arb_real_roots(p);
  ASSERT_EQ(got.size(), ref.size());
  for (std::size_t i = 0; i < got.size(); ++i) {
    EXPECT_FALSE(got[i].is_exact());
    Ball iv;
    Ball lo(got[i].lo, 256), hi(got[i].hi, 256);
    arb_union(iv.get(), lo.get(), hi.get(), 256);
    EXPECT_TRUE(arb_overlaps(iv.get(), ref[i].get())) << i;
  }
}

/// Mignotte: t^n - 2 (a t - 1)^2 has two real roots within ~2 a^(-(n+2)/2) of 1/a.
TEST(RealRoots, MignotteClosePair) {
  for (long n : {20L, 41L}) {
    const long a = 100;
    const Poly p = Poly::t().pow(static_cast<unsigned long>(n)) - Poly(2) * lin(a, 1).pow(2);
    SCOPED_TRACE(p.str());
    const auto got = isolate_real_roots(p, Rational(0), Rational(1));
    // h = a^(-(n+2)/2) bounds the distance of both roots to 1/a, roughly.
    const Rational h = Rational(Integer(1), pow_int(a, static_cast<unsigned long>(n / 2 + 1))) * Rational(4);
    std::vector<const IsolatedRoot*> near;
    for (const auto& r : got)
      if (Rational(1, a) - h < r.lo && r.hi < Rational(1, a) + h) near.push_back(&r);
    ASSERT_EQ(near.size(), 2u);
    EXPECT_TRUE(near[0]->hi < near[1]->lo);
    for (const auto* r : near) EXPECT_EQ(p.sign_at(r->lo) * p.sign_at(r->hi), -1);
    const auto ref = arb_real_roots(p);
    long in01 = 0;
    for (const Ball& b : ref)
      if (arb_is_positive(b.get()) && arb_lt(b.get(), Ball(1).get())) ++in01;
    EXPECT_EQ(static_cast<long>(got.size()), in01);
  }
}

TEST(RealRoots, ClustersTenToTheMinus30) {
  const Integer e30 = pow_int(10, 30);
  // sqrt2 and sqrt2 + 10^-30: (t^2 - 2)((10^30 t - 1)^2 - 2 10^60).
  const Poly f1 = Poly(std::vector<long>{-2, 0, 1});
  const Poly f2 = (Poly::t() * constant(e30) - Poly(1)).pow(2) - constant(pow_int(10, 60) * Integer(2));
  const auto got = isolate_real_roots(f1 * f2, Rational(0), Rational(2));
  ASSERT_EQ(got.size(), 2u);
  EXPECT_TRUE(got[0].hi < got[1].lo);
  const Rational eps(Integer(1), e30);
  // sqrt2 in (lo0, hi0): lo^2 < 2 < hi^2.
  EXPECT_TRUE(got[0].lo * got[0].lo < Rational(2) && Rational(2) < got[0].hi * got[0].hi);
  const Rational l1 = got[1].lo - eps, h1 = got[1].hi - eps;
  EXPECT_TRUE(l1 * l1 < Rational(2) && Rational(2) < h1 * h1);
  // Rational roots 10^-30 apart come back exact.
  const Poly g = lin(3, 1) * (Poly::t() * constant(e30 * Integer(3)) - constant(e30 + Integer(3)));
  const auto gr = isolate_real_roots(g * f1, Rational(0), Rational(1));
  ASSERT_EQ(gr.size(), 2u);
  EXPECT_TRUE(gr[0].is_exact() && gr[1].is_exact());
  EXPECT_EQ(gr[0].lo, Rational(1, 3));
  EXPECT_EQ(gr[1].lo, Rational(1, 3) + eps);
}

/// Random polynomials against Arb's complex root finder.
TEST(RealRoots, RandomPolynomialsAgainstArb) {
  std::mt19937_64 rng(77);
  const long iters = iterations(40);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 77)");
    const long n = std::uniform_int_distribution<long>(1, 30)(rng);
    std::vector<long> c(static_cast<std::size_t>(n + 1));
    for (long& x : c) x = std::uniform_int_distribution<long>(-1000, 1000)(rng);
    if (c.back() == 0) c.back() = 1;
    const Poly p = squarefree_part(Poly(c));
    if (p.degree() < 1) continue;
    const auto got = isolate_real_roots(p, Rational(-3), Rational(3));
    std::vector<Ball> ref;
    for (const Ball& b : arb_real_roots(p))
      if (arb_gt(b.get(), Ball(-3).get()) && arb_lt(b.get(), Ball(3).get())) ref.push_back(b);
    ASSERT_EQ(got.size(), ref.size()) << p.str();
    for (std::size_t i = 0; i < got.size(); ++i) {
      Ball iv;
      arb_union(iv.get(), Ball(got[i].lo, 256).get(), Ball(got[i].hi, 256).get(), 256);
      EXPECT_TRUE(arb_overlaps(iv.get(), ref[i].get())) << p.str() << " root " << i;
      if (i + 1 < got.size()) EXPECT_TRUE(got[i].hi < got[i + 1].lo);
    }
  }
}

/// Sign of p(x): Arb when the ball excludes 0, else exact (exact rational
/// Horner at a 700-bit point of a degree-600 polynomial is slow).
int fast_sign(const Poly& p, const Rational& x) {
  for (long prec = 128; prec <= 8192; prec *= 2) {
    Ball v;
    arb_fmpz_poly_evaluate_arb(v.get(), p.get(), Ball(x, prec).get(), prec);
    if (v.certainly_positive()) return 1;
    if (v.certainly_negative()) return -1;
  }
  return p.sign_at(x);
}

/// Degree 600, ~100-digit random coefficients: must run fast (no time
/// assertion; the duration is printed). Consistency: the roots on [a, b]
/// are the roots on [a, m] and [m, b] for a non-root m.
TEST(RealRoots, Degree600HundredDigitCoefficients) {
  std::mt19937_64 rng(600);
  std::vector<Integer> c;
  for (int i = 0; i <= 600; ++i) {
    std::string digits = (rng() % 2) ? "-" : "";
    digits += static_cast<char>('1' + rng() % 9);
    for (int k = 1; k < 100; ++k) digits += static_cast<char>('0' + rng() % 10);
    c.emplace_back(digits);
  }
  const Poly p(c);
  ASSERT_EQ(p.degree(), 600);
  for (const auto& ab : {std::pair<Rational, Rational>(Rational(-2), Rational(2)),
                         std::pair<Rational, Rational>(Rational(0), Rational(1)),
                         std::pair<Rational, Rational>(Rational(-1), Rational(1))}) {
    const Rational &a = ab.first, &b = ab.second;
    const auto t0 = std::chrono::steady_clock::now();
    const auto got = isolate_real_roots(p, a, b);
    const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("[ info ] degree 600 on [%s, %s]: %zu roots in %.3f s\n", a.str().c_str(), b.str().c_str(),
                got.size(), secs);
    for (std::size_t i = 0; i < got.size(); ++i) {
      EXPECT_FALSE(got[i].is_exact());
      EXPECT_EQ(fast_sign(got[i].factor, got[i].lo) * fast_sign(got[i].factor, got[i].hi), -1);
      if (i + 1 < got.size()) EXPECT_TRUE(got[i].hi < got[i + 1].lo);
    }
    // Split at a point that is not a root: the counts must add up.
    Rational m = (a + b) * Rational(1, 2) + Rational(1, 1000003);
    ASSERT_NE(p.sign_at(m), 0);
    EXPECT_EQ(isolate_real_roots(p, a, m).size() + isolate_real_roots(p, m, b).size(), got.size());
  }
}

}  // namespace
}  // namespace uniparam
