// Tests of the high-degree path of isolate_real_roots (the certified ball
// subdivision, RootIsolationMethod::Subdivision) against exactly known roots
// and against the exact VCA path (RootIsolationMethod::Exact) on the same
// inputs. The hard inputs are Bernstein polynomials: huge power-basis
// coefficients (binomials), moderate values on [0, 1], complex roots close
// to it.
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
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::check_isolation;
using test_support::iterations;
using test_support::Known;

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }
Poly lin(const Integer& d, const Integer& n) { return Poly(std::vector<Integer>{Integer(0) - n, d}); }  // d t - n

/// sum b_i C(n, i) t^i (1 - t)^(n - i) in the power basis.
Poly bernstein(const std::vector<Integer>& b) {
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

RootIsolationOptions with(RootIsolationMethod m) {
  RootIsolationOptions o;
  o.method = m;
  return o;
}

/// Bernstein coefficients in [1, top]: the polynomial is positive on [0, 1]
/// (convex hull), so its only roots there are the known factors' roots; small
/// coefficients next to large ones put complex roots close to [0, 1].
std::vector<Integer> positive_bernstein(std::mt19937_64& rng, long n, long top) {
  std::vector<Integer> b;
  for (long i = 0; i <= n; ++i) b.emplace_back(static_cast<long>(1 + rng() % static_cast<unsigned long>(top)));
  return b;
}

/// High degree: a positive Bernstein polynomial of degree 200..500 times
/// factors with known roots in [0, 1] (rational, irrational, double, at the
/// ends), by both methods, against the exact roots.
TEST(RealRootsFast, BernsteinTimesKnownFactors) {
  std::mt19937_64 rng(2024);
  for (long it = 0; it < iterations(3); ++it) {
    const long n = 200 + static_cast<long>(rng() % 201);
    const Poly B = bernstein(positive_bernstein(rng, n, it % 2 ? 1000 : 1000000));
    std::vector<Known> all;
    Poly p = B;
    // rational roots c/d, one double
    for (int j = 0; j < 3; ++j) {
      const long d = 2 + static_cast<long>(rng() % 97);
      const long c = 1 + static_cast<long>(rng() % static_cast<unsigned long>(d - 1));
      const Rational q(c, d);
      bool dup = false;
      for (const Known& k : all) dup = dup || (k.rational && k.q == q);
      if (dup) continue;
      const int m = j == 0 ? 2 : 1;
      all.push_back({true, q, 0, m});
      p = p * lin(q.den(), q.num()).pow(static_cast<unsigned long>(m));
    }
    // irrational roots sqrt(c/d) in (0, 1): d t^2 - c
    for (long c : {2L, 3L}) {
      const long d = c + 1 + static_cast<long>(rng() % 50);
      const Rational q(c, d);
      all.push_back({false, q, 1, 1});
      p = p * Poly(std::vector<Integer>{Integer(-c), Integer(0), Integer(d)});
    }
    // a root at the end 0
    all.push_back({true, Rational(0), 0, 1});
    p = p * Poly::t();
    SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", iteration " + std::to_string(it));
    for (RootIsolationMethod m : {RootIsolationMethod::Subdivision, RootIsolationMethod::Exact}) {
      const auto got = isolate_real_roots(p, Rational(0), Rational(1), with(m));
      check_isolation(p, Rational(0), Rational(1), all, got);
    }
    // a sub-interval with non-dyadic ends
    const Rational a(1, 7), b(5, 6);
    check_isolation(p, a, b, all, isolate_real_roots(p, a, b, with(RootIsolationMethod::Subdivision)));
  }
}

/// Exactly one interior root next to roots at the ends of [0, 1] (Descartes'
/// count of the open interval is then 1 while the ends are roots): every
/// root must be found, by every method.
TEST(RealRootsFast, OneInteriorRootAndRootsAtTheEnds) {
  std::mt19937_64 rng(4242);
  for (long it = 0; it < iterations(3); ++it) {
    const long n = 300 + static_cast<long>(rng() % 100);
    // (t + 2)^n: no root near [0, 1], so Descartes' count on (0, 1) is 1.
    const Poly B = Poly(std::vector<long>{2, 1}).pow(static_cast<unsigned long>(n));
    const long d = 3 + static_cast<long>(rng() % 50);
    const Rational q(1, d);
    std::vector<Known> all{{true, q, 0, 1}};
    Poly p = B * lin(q.den(), q.num());
    if (it != 1) {
      all.push_back({true, Rational(0), 0, 1});
      p = p * Poly::t();
    }
    if (it != 0) {
      all.push_back({true, Rational(1), 0, 1});
      p = p * lin(Integer(1), Integer(1));
    }
    for (RootIsolationMethod m : {RootIsolationMethod::Subdivision, RootIsolationMethod::Auto, RootIsolationMethod::Exact})
      check_isolation(p, Rational(0), Rational(1), all, isolate_real_roots(p, Rational(0), Rational(1), with(m)));
  }
}

/// Roots 1e-30 apart (rational and irrational) inside a high-degree
/// polynomial: the subdivision cannot separate them at its precision and
/// must hand the cell to the exact VCA.
TEST(RealRootsFast, ClustersInsideHighDegree) {
  std::mt19937_64 rng(77);
  const Poly B = bernstein(positive_bernstein(rng, 150, 1000));
  Integer e30;
  fmpz_set_ui(e30.get(), 10);
  fmpz_pow_ui(e30.get(), e30.get(), 30);
  std::vector<Known> all;
  Poly p = B;
  // 1/3 and 1/3 + 10^-30
  all.push_back({true, Rational(1, 3), 0, 1});
  p = p * lin(Integer(3), Integer(1));
  const Rational q2 = Rational(1, 3) + Rational(Integer(1), e30);
  all.push_back({true, q2, 0, 1});
  p = p * lin(q2.den(), q2.num());
  // sqrt(1/2) and a rational within 1e-30 of it: floor(10^31 / sqrt 2) / 10^31
  Integer ten31 = e30 * Integer(10), s;
  fmpz_mul(s.get(), ten31.get(), ten31.get());
  fmpz_fdiv_q_2exp(s.get(), s.get(), 1);
  fmpz_sqrt(s.get(), s.get());  // floor(10^31 / sqrt(2))
  const Rational r(s, ten31);
  all.push_back({false, Rational(1, 2), 1, 1});
  p = p * Poly(std::vector<long>{-1, 0, 2});
  all.push_back({true, r, 0, 1});
  p = p * lin(r.den(), r.num());
  for (RootIsolationMethod m : {RootIsolationMethod::Subdivision}) {
    const auto got = isolate_real_roots(p, Rational(0), Rational(1), with(m));
    check_isolation(p, Rational(0), Rational(1), all, got);
  }
}

/// Bernstein polynomials with sign changes (unknown real roots) of degree
/// 200..400, with binomial-size power-basis coefficients: both methods must
/// find the same roots: same count, equal exact roots, and each pair of
/// intervals overlapping (each holds exactly one root, and both lists are
/// sorted, so the i-th intervals hold the same root); the signs of the
/// factor at the ends differ.
TEST(RealRootsFast, SubdivisionAgreesWithExactVca) {
  std::mt19937_64 rng(31337);
  for (long it = 0; it < iterations(4); ++it) {
    const long n = 200 + static_cast<long>(rng() % 201);
    std::vector<Integer> b;
    for (long i = 0; i <= n; ++i) {
      // a slowly varying sign pattern plus noise: a handful of real roots
      const double phase = 6.283185307179586 * static_cast<double>(i) / static_cast<double>(n) * (2.0 + it);
      const long base = static_cast<long>(1000.0 * std::sin(phase));
      b.emplace_back(base + static_cast<long>(rng() % 201) - 100);
    }
    const Poly p = bernstein(b);
    if (p.is_zero()) continue;
    for (const auto& ab : {std::pair<Rational, Rational>(Rational(0), Rational(1)),
                           std::pair<Rational, Rational>(Rational(-1, 5), Rational(9, 10))}) {
      const Rational &lo = ab.first, &hi = ab.second;
      SCOPED_TRACE("degree " + std::to_string(n) + " on [" + lo.str() + ", " + hi.str() + "]");
      const auto fast = isolate_real_roots(p, lo, hi, with(RootIsolationMethod::Subdivision));
      const auto exact = isolate_real_roots(p, lo, hi, with(RootIsolationMethod::Exact));
      ASSERT_EQ(fast.size(), exact.size());
      EXPECT_GE(fast.size(), 2u);  // the sign pattern changes sign at least twice in [0, 1]
      for (std::size_t i = 0; i < fast.size(); ++i) {
        const IsolatedRoot &f = fast[i], &e = exact[i];
        EXPECT_EQ(f.multiplicity, e.multiplicity);
        EXPECT_EQ(f.is_exact(), e.is_exact());
        EXPECT_TRUE(f.lo <= e.hi && e.lo <= f.hi) << "intervals " << i << " do not overlap";
        if (f.is_exact()) {
          EXPECT_EQ(f.lo, e.lo);
        } else {
          EXPECT_EQ(f.factor, e.factor);
          EXPECT_EQ(f.factor.sign_at(f.lo) * f.factor.sign_at(f.hi), -1);
        }
        if (i + 1 < fast.size()) EXPECT_TRUE(f.hi < fast[i + 1].lo);
      }
    }
  }
}

}  // namespace
}  // namespace uniparam

namespace uniparam {
namespace {

using test_support::check_isolation;
using test_support::iterations;
using test_support::Known;

/// p = prod f_i and p' from the factors' own values (product rule), each
/// low-degree factor by Horner: an evaluator that never expands p.
PolyEvaluator product_evaluator(const std::vector<Poly>& factors, long* calls) {
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

/// The evaluator-driven subdivision (isolate_real_roots with a
/// PolyEvaluator) against exactly known roots: rational ones (two of them
/// 2^-40 apart: a cell it must hand to the exact isolation), irrational
/// ones, roots at the ends, complex pairs close to [0, 1] (the enclosures
/// there hold 0 without a real root), on [0, 1] and on a sub-interval with
/// non-dyadic ends. A non-squarefree p goes to the exact path without one
/// evaluation.
TEST(RealRootsFast, EvaluatorSubdivisionFindsTheKnownRoots) {
  std::mt19937_64 rng(31337);
  RootIsolationOptions sub;
  sub.method = RootIsolationMethod::Subdivision;
  for (long it = 0; it < iterations(4); ++it) {
    std::vector<Poly> factors;
    std::vector<Known> all;
    auto add_rational = [&](const Rational& q) {
      for (const Known& k : all)
        if (k.rational && k.q == q) return;
      all.push_back({true, q, 0, 1});
      factors.push_back(Poly(std::vector<Integer>{Integer(0) - q.num(), q.den()}));
    };
    for (int j = 0; j < 12; ++j) {
      const long d = 2 + static_cast<long>(rng() % 997);
      add_rational(Rational(1 + static_cast<long>(rng() % static_cast<unsigned long>(d - 1)), d));
    }
    const Rational c(static_cast<long>(1 + rng() % 1000), 1001);  // a close pair: c and c + 2^-40
    add_rational(c);
    add_rational(c + Rational(1, 1L << 40));
    for (long cc : {2L, 3L, 5L}) {  // sqrt(cc / dd) in (0, 1)
      const long dd = cc + 1 + static_cast<long>(rng() % 40);
      all.push_back({false, Rational(cc, dd), 1, 1});
      factors.push_back(Poly(std::vector<Integer>{Integer(-cc), Integer(0), Integer(dd)}));
    }
    for (int j = 0; j < 6; ++j) {  // (D t - C)^2 + E^2: complex roots C/D +- i E/D
      const long D = 1000, C = static_cast<long>(rng() % 1001), E = 1 + static_cast<long>(rng() % 5);
      factors.push_back(Poly(std::vector<Integer>{Integer(C * C + E * E), Integer(-2 * C * D), Integer(D * D)}));
    }
    if (it % 2 == 0) {
      all.push_back({true, Rational(0), 0, 1});
      factors.push_back(Poly::t());
    }
    if (it % 3 == 0) {
      all.push_back({true, Rational(1), 0, 1});
      factors.push_back(Poly(std::vector<long>{-1, 1}));
    }
    Poly p(1);
    for (const Poly& f : factors) p = p * f;
    SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", iteration " + std::to_string(it));
    long calls = 0;
    const PolyEvaluator ev = product_evaluator(factors, &calls);
    check_isolation(p, Rational(0), Rational(1), all, isolate_real_roots(p, ev, Rational(0), Rational(1), sub));
    EXPECT_GT(calls, 0);
    const Rational a(1, 7), b(5, 6);
    check_isolation(p, a, b, all, isolate_real_roots(p, ev, a, b, sub));
    // A double factor: not squarefree, so the exact path and no evaluation.
    std::vector<Known> doubled = all;
    doubled.front().mult = 2;
    std::vector<Poly> f2 = factors;
    f2.push_back(factors.front());
    long calls2 = 0;
    const Poly p2 = p * factors.front();
    check_isolation(p2, Rational(0), Rational(1), doubled,
                    isolate_real_roots(p2, product_evaluator(f2, &calls2), Rational(0), Rational(1), sub));
    EXPECT_EQ(calls2, 0);
  }
}

/// c p and c p' for p = prod f_i from the factors' Taylor expansions at the
/// midpoint of x (a centred form: as tight on a wide ball as p's variation
/// there, like the speeds' local expansions), never expanding p.
PolyEvaluator centred_product_evaluator(const std::vector<Poly>& factors, const Rational& c, long* calls) {
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
std::optional<IsolatedRoot> grid_cell_root(const Poly& p, const Poly& f, const IsolatedRoot& r0) {
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
void expect_refined_like_exact(const Poly& p, const IsolatedRoot& r, const RealAlgebraic& fast,
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
std::vector<Poly> five_real_roots_and_complex_pairs(std::mt19937_64& rng, int pairs) {
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
      check(g, detail::pow2(-4 - static_cast<long>(rng() % 27)), false);
    }
    for (const IsolatedRoot& r : isolate_real_roots(p, Rational(0), Rational(1))) {
      RealAlgebraic x(r);
      x.refine(70);
      check(x.lo(), detail::pow2(-40), true);  // |x - lo| <= 2^-70
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
