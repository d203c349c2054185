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
#include "algebra/real_roots_support.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::check_isolation;
using test_support::iterations;
using test_support::Known;
using real_roots_test::bernstein;
using real_roots_test::positive_bernstein;
using real_roots_test::product_evaluator;

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }
Poly lin(const Integer& d, const Integer& n) { return Poly(std::vector<Integer>{Integer(0) - n, d}); }  // d t - n

RootIsolationOptions with(RootIsolationMethod m) {
  RootIsolationOptions o;
  o.method = m;
  return o;
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

}  // namespace
}  // namespace uniparam
