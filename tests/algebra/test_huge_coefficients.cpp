// Polynomials with coefficients of thousands of bits: the certified bound
// on how close to 0 their nonzero roots come (root_depth_bits, from the
// Newton polygon: algebra/newton_polygon.hpp), checked against all complex
// roots found by Arb; and LocalPoly's power basis at a working precision far
// below the coefficients' size (coefficients rounded once to the working
// precision), whose enclosures must hold the exact values and be as tight as
// those of the exact coefficients.
#include <acb_poly.h>
#include <arb_fmpz_poly.h>
#include <arb_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "algebra/local_poly_support.hpp"
#include "support/balls.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/algebra/newton_polygon.hpp"

namespace uniparam {
namespace {

using local_poly_test::random_ball;
using test_support::expect_encloses_at_points;
using test_support::iterations;
using test_support::test_seed;

// A random integer of about `bits` bits (either sign, never 0).
Integer random_big(std::mt19937_64& rng, long bits) {
  Integer x(0);
  for (long b = 0; b < bits; b += 32) x = x * Integer(1L << 32) + Integer(static_cast<long>(rng() & 0xffffffffu));
  if (x.sign() == 0) x = Integer(1);
  return (rng() & 1) ? Integer(0) - x : x;
}

// A random polynomial of degree deg whose coefficient k has about bits[k]
// bits (0: the coefficient is 0).
Poly random_poly_bits(std::mt19937_64& rng, const std::vector<long>& bits) {
  std::vector<Integer> c;
  for (long b : bits) c.push_back(b > 0 ? random_big(rng, b) : Integer(0));
  return Poly(c);
}

// min |r| over p's nonzero complex roots as an enclosure's lower bound,
// in log2 (+infinity when there is none), from Arb's certified roots.
double log2_min_root_modulus(const Poly& p) {
  // drop the roots at 0
  long v = 0;
  while (v <= p.degree() && p.coeff(v).sign() == 0) ++v;
  std::vector<Integer> c;
  for (long k = v; k <= p.degree(); ++k) c.push_back(p.coeff(k));
  const Poly q(c);
  const long n = q.degree();
  if (n < 1) return HUGE_VAL;
  acb_ptr roots = _acb_vec_init(n);
  arb_fmpz_poly_complex_roots(roots, q.get(), 0, 256);
  double lo = HUGE_VAL;
  arb_t m;
  arb_init(m);
  for (long i = 0; i < n; ++i) {
    acb_abs(m, roots + i, 256);
    arf_t l;
    arf_init(l);
    arb_get_lbound_arf(l, m, 64);
    if (arf_sgn(l) > 0) {
      lo = std::min(lo, std::log2(arf_get_d(l, ARF_RND_DOWN)));
    } else {
      lo = -HUGE_VAL;  // not certified away from 0: the test below fails
    }
    arf_clear(l);
  }
  arb_clear(m);
  _acb_vec_clear(roots, n);
  return lo;
}

}  // namespace

// Must show: every nonzero root r of random polynomials (coefficients of
// mixed sizes up to 600 bits, zero coefficients, roots at 0, roots planted
// at 2^-k) has |r| >= 2^-root_depth_bits, and the bound is at most
// log2(4 deg) + 2 bits below the true smallest modulus (Fujiwara's bound is
// within a factor 2 deg of it).
TEST(NewtonPolygon, RootDepthBoundsTheNearestNonzeroRoot) {
  std::mt19937_64 rng(test_seed(8101));
  std::uniform_int_distribution<long> deg(1, 8), size(0, 600), plant(1, 400);
  for (long it = 0; it < iterations(200); ++it) {
    const long n = deg(rng);
    std::vector<long> bits;
    for (long k = 0; k <= n; ++k) bits.push_back(rng() % 4 == 0 ? 0 : size(rng) + 1);
    bits.back() = std::max(bits.back(), 1L);
    Poly p = random_poly_bits(rng, bits);
    if (it % 3 == 0) {  // a planted root 1 / 2^k: (2^k t - 1) p
      Integer two_k(1);
      for (long j = plant(rng); j > 0; --j) two_k = two_k * Integer(2);
      p = p * Poly(std::vector<Integer>{Integer(-1), two_k});
    }
    if (it % 5 == 0) p = p * Poly(std::vector<Integer>{Integer(0), Integer(0), Integer(1)});  // t^2 p
    const long d = root_depth_bits(p);
    const double truth = log2_min_root_modulus(p);
    SCOPED_TRACE(p.str().substr(0, 300));
    ASSERT_GE(d, 0);
    if (truth == HUGE_VAL) continue;  // no nonzero root
    EXPECT_GE(truth, -static_cast<double>(d)) << "bound 2^-" << d << " above the root's modulus 2^" << truth;
    EXPECT_LE(static_cast<double>(d), std::max(0.0, -truth) + std::log2(4.0 * static_cast<double>(p.degree())) + 4)
        << "bound 2^-" << d << " far below the root's modulus 2^" << truth;
  }
}

// end_root_depth_bits bounds the roots next to 1 as root_depth_bits those
// next to 0: with a root planted at 1 - 2^-k (and one at 2^-j), the bound
// is at least k (and j), and no root other than 0 and 1 comes nearer to
// an end than it says (Arb's certified roots of p and of p(1 + t)).
TEST(NewtonPolygon, EndRootDepthBoundsTheRootsNextToBothEnds) {
  std::mt19937_64 rng(test_seed(8103));
  std::uniform_int_distribution<long> deg(1, 6), size(0, 200), plant(1, 300);
  for (long it = 0; it < iterations(100); ++it) {
    std::vector<long> bits;
    for (long k = 0, n = deg(rng); k <= n; ++k) bits.push_back(rng() % 4 == 0 ? 0 : size(rng) + 1);
    bits.back() = std::max(bits.back(), 1L);
    // p(0) != 0: a repeated root at 0 would be one at -1 in p(1 + t), which
    // Arb's root finder (squarefree input only) would never isolate.
    bits.front() = std::max(bits.front(), 1L);
    Poly p = random_poly_bits(rng, bits);
    const long k = plant(rng), j = it % 2 ? plant(rng) : 0;
    Integer two_k(1), two_j(1);
    for (long i = 0; i < k; ++i) two_k = two_k * Integer(2);
    for (long i = 0; i < j; ++i) two_j = two_j * Integer(2);
    p = p * Poly(std::vector<Integer>{two_k - Integer(1), Integer(0) - two_k});  // root 1 - 2^-k
    if (j > 0) p = p * Poly(std::vector<Integer>{Integer(-1), two_j});  // root 2^-j
    SCOPED_TRACE(p.str().substr(0, 300));
    const long d = end_root_depth_bits(p);
    EXPECT_GE(d, std::max(k, j));
    Poly at1;
    fmpz_poly_taylor_shift(at1.get(), p.get(), Integer(1).get());
    for (const Poly* q : {static_cast<const Poly*>(&p), static_cast<const Poly*>(&at1)}) {
      const double truth = log2_min_root_modulus(*q);
      if (truth != HUGE_VAL) EXPECT_GE(truth, -static_cast<double>(d)) << "a root nearer than 2^-" << d;
    }
  }
}

// Must show: the tropical polynomial T(x) = max_i (log2 |c_i| - i x) read
// from the hull equals the maximum over all coefficients, at increasing x.
TEST(NewtonPolygon, TropicalValueIsTheMaximumOverTheCoefficients) {
  std::mt19937_64 rng(test_seed(8102));
  std::uniform_int_distribution<long> deg(0, 12), size(0, 300);
  for (long it = 0; it < iterations(200); ++it) {
    std::vector<long> bits;
    const long n = deg(rng);
    for (long k = 0; k <= n; ++k) bits.push_back(rng() % 3 == 0 ? 0 : size(rng) + 1);
    bits.back() = std::max(bits.back(), 1L);
    const Poly p = random_poly_bits(rng, bits);
    NewtonPolygon T(p);
    for (double x = 0; x < 400; x += 7.25) {
      double want = -HUGE_VAL;
      for (long k = 0; k <= p.degree(); ++k) {
        if (p.coeff(k).sign() == 0) continue;
        slong e = 0;
        const double m = fmpz_get_d_2exp(&e, p.coeff(k).get());
        want = std::max(want, std::log2(std::fabs(m)) + static_cast<double>(e) - static_cast<double>(k) * x);
      }
      EXPECT_NEAR(T(x), want, 1e-9 * std::max(1.0, std::fabs(want))) << p.str().substr(0, 200) << " at " << x;
    }
  }
}

// Must show: LocalPoly on polynomials of degree 1 to 6 whose coefficients
// have 2000 to 6000 bits, at working precisions 64 to 256: the enclosures
// of p, p', p'' hold the exact values at the points of random balls, and
// where the power basis evaluates (degree <= 2) a narrow ball's radius is
// within a factor 4 (plus 2^-prec of the sum of |c_k| |z|^k) of the exact
// coefficients' Horner evaluation at the same precision: rounding the
// coefficients to the working precision loses nothing the evaluation keeps.
TEST(HugeCoefficients, LocalPolyEnclosesAtLowPrecision) {
  std::mt19937_64 rng(test_seed(8103));
  std::uniform_int_distribution<long> deg(1, 6), size(2000, 6000);
  const long precs[] = {64, 128, 256};
  for (long it = 0; it < iterations(60); ++it) {
    const long n = deg(rng);
    std::vector<long> bits;
    for (long k = 0; k <= n; ++k) bits.push_back(size(rng));
    const Poly p = random_poly_bits(rng, bits);
    const LocalPoly lp(p);
    arb_poly_t exact;
    arb_poly_init(exact);
    arb_poly_set_fmpz_poly(exact, p.get(), ARF_PREC_EXACT);
    for (int b = 0; b < 4; ++b) {
      const long prec = precs[rng() % 3];
      acb_t z, v, d1, d2, ref;
      acb_init(z);
      acb_init(v);
      acb_init(d1);
      acb_init(d2);
      acb_init(ref);
      random_ball(z, rng);
      lp.eval(v, d1, d2, z, prec);
      const acb_struct* const outs[3] = {v, d1, d2};
      expect_encloses_at_points(p, outs, z, rng, "prec " + std::to_string(prec), 20000);
      if (n <= 2 && !is_wide_ball(z)) {  // the power basis (longer ones take the cells)
        arb_poly_evaluate_acb(ref, exact, z, prec);
        mag_t lim, r;
        mag_init(lim);
        mag_init(r);
        mag_hypot(lim, arb_radref(acb_realref(ref)), arb_radref(acb_imagref(ref)));
        mag_mul_ui(lim, lim, 4);
        // plus 2^-prec sum |c_k| |z|^k: the rounding a Horner step commits
        arb_t s, az;
        arb_init(s);
        arb_init(az);
        acb_abs(az, z, 64);
        arb_add_error_mag(az, arb_radref(az));
        for (long k = p.degree(); k >= 0; --k) {
          arb_mul(s, s, az, 64);
          arb_t c;
          arb_init(c);
          arb_set_round_fmpz(c, p.coeff(k).get(), 64);
          arb_abs(c, c);
          arb_add(s, s, c, 64);
          arb_clear(c);
        }
        mag_t extra;
        mag_init(extra);
        arb_get_mag(extra, s);
        mag_mul_2exp_si(extra, extra, -prec + 4);
        mag_add(lim, lim, extra);
        mag_hypot(r, arb_radref(acb_realref(v)), arb_radref(acb_imagref(v)));
        EXPECT_LE(mag_cmp(r, lim), 0) << "prec " << prec << ": radius 2^" << fmpz_get_si(MAG_EXPREF(r))
                                      << " against 2^" << fmpz_get_si(MAG_EXPREF(lim)) << " (exact coefficients 2^"
                                      << fmpz_get_si(MAG_EXPREF(arb_radref(acb_realref(ref)))) << ")";
        mag_clear(extra);
        arb_clear(s);
        arb_clear(az);
        mag_clear(lim);
        mag_clear(r);
      }
      acb_clear(z);
      acb_clear(v);
      acb_clear(d1);
      acb_clear(d2);
      acb_clear(ref);
    }
    arb_poly_clear(exact);
  }
}

}  // namespace uniparam
