// Tests of uniparam/algebra/local_poly.hpp: the enclosures of p, p', p'' and
// of p / (t - gamma) from local expansions contain the values at every
// sampled point of random balls (narrow and wide, inside and outside
// [0, 1]), checked against evaluations at 4000 bits at exact points; and
// narrow balls do not pay for the power basis' cancellation.
#include <acb_poly.h>
#include <arb_poly.h>
#include <flint/flint.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/balls.hpp"
#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "algebra/local_poly_support.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using local_poly_test::bernstein;
using local_poly_test::kRefPrec;
using local_poly_test::random_ball;
using local_poly_test::random_test_poly;
using local_poly_test::RefDerivatives;

using test_support::expect_encloses_at_points;
using test_support::iterations;
using test_support::offsets;
using test_support::point_of;
using test_support::random_poly;

TEST(LocalPoly, EnclosesValueAndDerivativesOnRandomBalls) {
  std::mt19937_64 rng(20261122);
  const long precs[] = {30, 64, 128, 200};
  for (long it = 0; it < iterations(60); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly lp(p);
    const RefDerivatives rd(p);
    const auto& ref = rd.r;
    for (int b = 0; b < 25; ++b) {
      acb_t z, v, d1, d2, t, exact;
      for (acb_ptr x : {z, v, d1, d2, t, exact}) acb_init(x);
      random_ball(z, rng);
      const long prec = precs[std::uniform_int_distribution<int>(0, 3)(rng)];
      lp.eval(v, d1, d2, z, prec);
      const acb_struct* outs[3] = {v, d1, d2};
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        ASSERT_TRUE(acb_contains(z, t));
        for (int j = 0; j < 3; ++j) {
          arb_poly_evaluate_acb(exact, ref[j], t, kRefPrec);
          ASSERT_TRUE(acb_contains(outs[j], exact))
              << "derivative " << j << " of a degree-" << p.degree() << " polynomial at prec " << prec;
        }
      }
      for (acb_ptr x : {z, v, d1, d2, t, exact}) acb_clear(x);
    }
  }
}

TEST(LocalPoly, DiscsHoldValueAndDerivativesOnRandomBalls) {
  // eval_disks: the centred form's discs (degree <= 64, any length) or
  // eval's enclosures as discs (higher degrees), on the same balls as above
  // plus short polynomials (lengths 1-3, which eval leaves to Arb).
  std::mt19937_64 rng(20261201);
  long centred = 0;
  for (long it = 0; it < iterations(60); ++it) {
    const Poly p = it % 3 == 0 ? random_poly(rng, it % 9 / 3, 20) : random_test_poly(rng);
    const LocalPoly lp(p);
    centred += lp.has_disk_form();
    const RefDerivatives rd(p);
    const auto& ref = rd.r;
    for (int b = 0; b < 25; ++b) {
      acb_t z, t, exact, w;
      for (acb_ptr x : {z, t, exact, w}) acb_init(x);
      random_ball(z, rng);
      CDisk o[4];
      lp.eval_disks(&o[0], &o[1], &o[2], z, 64);
      o[3] = lp.eval_disk(z, 64);  // the value alone (the centred form may serve it and not p'')
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        for (int j = 0; j < 4; ++j) {
          if (!cdisk_is_finite(o[j])) continue;
          arb_poly_evaluate_acb(exact, ref[j % 3], t, kRefPrec);
          // |exact - centre| <= rad
          acb_set_d_d(w, o[j].re, o[j].im);
          acb_sub(w, exact, w, kRefPrec);
          arb_t m, r;
          arb_init(m);
          arb_init(r);
          acb_abs(m, w, kRefPrec);
          arb_set_d(r, o[j].rad);
          ASSERT_TRUE(arb_le(m, r)) << "derivative " << j << " of a degree-" << p.degree() << " polynomial";
          arb_clear(m);
          arb_clear(r);
        }
      }
      for (acb_ptr x : {z, t, exact, w}) acb_clear(x);
    }
  }
  EXPECT_GT(centred, iterations(60) / 3);  // both paths ran
  EXPECT_LT(centred, iterations(60));
}

TEST(LocalPoly, DeflatedEnclosesQuotientNearAndFarFromTheRoot) {
  std::mt19937_64 rng(7);
  // p = q (2t^2 - 1): gamma = 1/sqrt(2), p / (t - gamma) = 2 q (t + gamma).
  const Poly f(std::vector<long>{-1, 0, 2});
  const RealAlgebraic gamma(f, Rational(1, 2), Rational(1));
  for (long it = 0; it < iterations(40); ++it) {
    const Poly q = random_test_poly(rng);
    const LocalPoly lp(q * f);
    arb_poly_t qb;
    arb_poly_init(qb);
    arb_poly_set_fmpz_poly(qb, q.get(), ARF_PREC_EXACT);
    const Ball g = gamma.to_ball(kRefPrec);
    for (int b = 0; b < 25; ++b) {
      acb_t z, v, t, exact, s;
      for (acb_ptr x : {z, v, t, exact, s}) acb_init(x);
      random_ball(z, rng);
      if (b % 2 == 0) {  // centred on gamma (to 80 bits): the ball holds it or nearly
        arb_set_round(acb_realref(s), g.get(), 80);
        arf_set(arb_midref(acb_realref(z)), arb_midref(acb_realref(s)));
      }
      const long prec = b % 3 == 0 ? 64 : 128;
      lp.eval_deflated(v, z, gamma, prec);
      for (const auto& [a, c] : offsets(rng)) {
        point_of(t, z, a, c);
        arb_poly_evaluate_acb(exact, qb, t, kRefPrec);
        acb_add_arb(s, t, g.get(), kRefPrec);
        acb_mul(exact, exact, s, kRefPrec);
        acb_mul_2exp_si(exact, exact, 1);
        ASSERT_TRUE(acb_contains(v, exact)) << "degree " << q.degree() + 2 << ", prec " << prec;
      }
      for (acb_ptr x : {z, v, t, exact, s}) acb_clear(x);
    }
    arb_poly_clear(qb);
  }
}

TEST(LocalPoly, DeflatedRefusesANonRoot) {
  const LocalPoly lp(Poly(std::vector<long>{-1, 0, 2}) * Poly(std::vector<long>{1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1}));
  const RealAlgebraic not_root(Rational(1, 3));
  acb_t z, v;
  acb_init(z);
  acb_init(v);
  EXPECT_THROW(lp.eval_deflated(v, z, not_root, 64), DomainError);
  acb_clear(z);
  acb_clear(v);
}

// The point of the local bases: at a node in [0, 1], a Bezier polynomial of
// degree n (power-basis coefficients ~2^n times its values) evaluated at 80
// bits is accurate to about 80 bits of the size of its Bernstein
// coefficients, where Horner in the power basis would lose ~n bits. The
// nodes' cells (level 6) are ball shifts of their parents' expansions, whose
// discs reach where p is far larger: they must not lose those bits.
TEST(LocalPoly, NarrowBallsDoNotPayForPowerBasisCancellation) {
  std::mt19937_64 rng(99);
  std::uniform_int_distribution<long> c(-1000, 1000);
  for (long n : {150L, 300L}) {
    std::vector<long> b(static_cast<std::size_t>(n + 1));
    for (auto& x : b) x = c(rng);
    const LocalPoly lp(bernstein(b));
    std::uniform_int_distribution<long> num(0, 1L << 30);
    for (int i = 0; i < 300; ++i) {
      acb_t z, v;
      acb_init(z);
      acb_init(v);
      arb_set_si(acb_realref(z), num(rng));
      arb_mul_2exp_si(acb_realref(z), acb_realref(z), -30);
      lp.eval(v, z, 80);
      // |p| <= 1000 on [0, 1]; the radius must stay near 1000 * 2^-80.
      EXPECT_LT(mag_cmp_2exp_si(arb_radref(acb_realref(v)), 10 - 60), 0) << "degree " << n << ", node " << i;
      acb_clear(z);
      acb_clear(v);
    }
    EXPECT_GT(lp.cells(), 0u);
  }
}

// Wide balls (the quadrature's ellipses and segments) use coarse cells, which
// keep p's expansion only to about 2^-24 of its size. Their enclosures must
// stay about as tight as p's variation on the ball: with c_j the exact Taylor
// coefficients of p at the ball's midpoint (4000 bits) and r the ball's
// radius, the enclosure's radius is at most twice the majorant
// sum_{j >= 1} |c_j| (8r)^j of p - p(mid), plus 2^-20 of the majorant of p
// there (the cell's centre c is within 2.9r of the midpoint m, and the
// enclosure sums the expansion at c on |t - c| <= |m - c| + 1.5r, which the
// expansion at m majorises on the radius 2|m - c| + 1.5r < 8r; the coarse
// tails are 2^-24 of p's size on the cell). Cells truncated far below 24
// bits break it (at 8 bits, 19 of the 180 balls fail).
TEST(LocalPoly, WideBallsAreAboutAsTightAsTheVariationOfP) {
  std::mt19937_64 rng(4242);
  std::uniform_int_distribution<long> c(-1000, 1000);
  std::uniform_int_distribution<long> num(0, 1L << 20);
  std::uniform_int_distribution<long> ex(3, 20);
  std::uniform_int_distribution<ulong> frac(0, 8);
  for (long n : {40L, 150L, 300L}) {
    std::vector<long> b(static_cast<std::size_t>(n + 1));
    for (auto& x : b) x = c(rng);
    const Poly p = bernstein(b);
    const LocalPoly lp(p);
    arb_poly_t exact, shifted;
    arb_poly_init(exact);
    arb_poly_init(shifted);
    arb_poly_set_fmpz_poly(exact, p.get(), kRefPrec);
    for (long i = 0; i < iterations(60); ++i) {
      acb_t z, v;
      acb_init(z);
      acb_init(v);
      // an ellipse-like box: real radius r = 2^-e, imaginary radius <= r
      const long e = ex(rng);
      arb_set_si(acb_realref(z), num(rng));
      arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
      mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -e);
      mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), frac(rng), -e - 3);
      lp.eval(v, z, 80);
      // majorants at radius 8r from the exact expansion at the midpoint
      arb_t m;
      arb_init(m);
      arb_set_arf(m, arb_midref(acb_realref(z)));
      arb_poly_taylor_shift(shifted, exact, m, kRefPrec);
      mag_t rho, term, var, all;
      mag_init(rho);
      mag_init(term);
      mag_init(var);
      mag_init(all);
      mag_set_ui_2exp_si(rho, 1, 3 - e);
      // all = sum_{j >= 0} |c_j| rho^j, var = sum_{j >= 1} |c_j| rho^j
      mag_one(term);
      for (slong j = 0; j < arb_poly_length(shifted); ++j) {
        mag_t cj;
        mag_init(cj);
        arb_get_mag(cj, shifted->coeffs + j);
        mag_mul(cj, cj, term);
        mag_add(all, all, cj);
        if (j >= 1) mag_add(var, var, cj);
        mag_clear(cj);
        mag_mul(term, term, rho);
      }
      mag_mul_2exp_si(var, var, 1);
      mag_mul_2exp_si(all, all, -20);
      mag_add(var, var, all);
      mag_t rad;
      mag_init(rad);
      mag_hypot(rad, arb_radref(acb_realref(v)), arb_radref(acb_imagref(v)));
      EXPECT_LE(mag_cmp(rad, var), 0) << "degree " << n << ", radius 2^-" << e << ", ball " << i;
      mag_clear(rad);
      mag_clear(rho);
      mag_clear(term);
      mag_clear(var);
      mag_clear(all);
      arb_clear(m);
      acb_clear(z);
      acb_clear(v);
    }
    arb_poly_clear(exact);
    arb_poly_clear(shifted);
  }
}

// Narrow balls wider than a point (the error bounds of tiny subintervals,
// radius 2^-26 .. 2^-56) next to a near double root of p, where p' is far
// smaller than the absolute-value bound that Horner's rule or a cell's
// expansion multiplies the radius by: p = prod (C_i (t - c_i)^2 + 1), C_1 up
// to 2^40, the ball 2^-k from c_1. The enclosure's radius must stay within
// twice the majorant sum_{j >= 1} |c_j| (2r)^j of p - p(mid) (exact Taylor
// coefficients at the midpoint), plus the working precision's rounding
// relative to p's coefficients. Horner's wrapping alone exceeds that by 2^9
// or more.
TEST(LocalPoly, NarrowRegionsAreAboutAsTightAsTheVariationOfP) {
  std::mt19937_64 rng(20261204);
  std::uniform_int_distribution<long> cbits(24, 40), kdist(10, 30), edist(26, 56), cnum(1, 63);
  std::uniform_int_distribution<ulong> frac(0, 8);
  const long prec = 128;
  for (long it = 0; it < iterations(40); ++it) {
    const int factors = 1 + static_cast<int>(it % 3);  // degree 2 (power basis), 4 and 6 (cells)
    Poly p(1);
    Rational c1;
    for (int i = 0; i < factors; ++i) {
      const Rational c(cnum(rng), 64);
      if (i == 0) c1 = c;
      fmpz_t C;
      fmpz_init(C);
      fmpz_one(C);
      fmpz_mul_2exp(C, C, static_cast<ulong>(i == 0 ? cbits(rng) : 4));
      // C (t - c)^2 + 1 with c = a / 64: (C (64 t - a)^2 + 4096) / 4096, made integral
      fmpz_poly_t q;
      fmpz_poly_init(q);
      const long a = fmpz_get_si(c.num().get()) * (64 / fmpz_get_si(c.den().get()));
      fmpz_poly_set_coeff_si(q, 1, 64);
      fmpz_poly_set_coeff_si(q, 0, -a);
      fmpz_poly_mul(q, q, q);
      fmpz_poly_scalar_mul_fmpz(q, q, C);
      fmpz_poly_t one;
      fmpz_poly_init(one);
      fmpz_poly_set_si(one, 4096);
      fmpz_poly_add(q, q, one);
      Poly f;
      fmpz_poly_set(f.get(), q);
      p = p * f;
      fmpz_poly_clear(q);
      fmpz_poly_clear(one);
      fmpz_clear(C);
    }
    const LocalPoly lp(p);
    arb_poly_t exact, shifted;
    arb_poly_init(exact);
    arb_poly_init(shifted);
    arb_poly_set_fmpz_poly(exact, p.get(), kRefPrec);
    for (int b = 0; b < 10; ++b) {
      acb_t z, v, d1, d2;
      for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
      const long k = kdist(rng), e = edist(rng);
      arb_set_fmpq(acb_realref(z), c1.get(), 2 * prec);
      arb_t off;
      arb_init(off);
      arb_one(off);
      arb_mul_2exp_si(off, off, -k);
      if (b % 2) arb_neg(off, off);
      arb_add(acb_realref(z), acb_realref(z), off, 2 * prec);
      mag_zero(arb_radref(acb_realref(z)));
      mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -e);
      mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), frac(rng), -e - 3);
      lp.eval(v, d1, d2, z, prec);
      const acb_struct* outs[3] = {v, d1, d2};
      test_support::expect_encloses_at_points(p, outs, z, rng, "narrow region");
      arb_t m;
      arb_init(m);
      arb_set_arf(m, arb_midref(acb_realref(z)));
      arb_poly_taylor_shift(shifted, exact, m, kRefPrec);
      mag_t rho, term, var, coeffs, cj, rad;
      for (mag_ptr x : {rho, term, var, coeffs, cj, rad}) mag_init(x);
      mag_set_ui_2exp_si(rho, 1, 1 - e);
      mag_one(term);
      for (slong j = 0; j < arb_poly_length(shifted); ++j) {
        arb_get_mag(cj, shifted->coeffs + j);
        mag_mul(cj, cj, term);
        if (j >= 1) mag_add(var, var, cj);
        mag_mul(term, term, rho);
      }
      mag_mul_2exp_si(var, var, 1);
      for (slong j = 0; j <= p.degree(); ++j) {
        arb_get_mag(cj, exact->coeffs + j);
        mag_add(coeffs, coeffs, cj);
      }
      mag_mul_2exp_si(coeffs, coeffs, 30 - prec);
      mag_add(var, var, coeffs);
      mag_hypot(rad, arb_radref(acb_realref(v)), arb_radref(acb_imagref(v)));
      EXPECT_LE(mag_cmp(rad, var), 0) << "degree " << p.degree() << ", 2^-" << k << " from the near root, radius 2^-"
                                       << e << ": radius " << mag_get_d(rad) << " > " << mag_get_d(var);
      for (mag_ptr x : {rho, term, var, coeffs, cj, rad}) mag_clear(x);
      arb_clear(m);
      arb_clear(off);
      for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
    }
    arb_poly_clear(exact);
    arb_poly_clear(shifted);
  }
}

// Next to a root of p at 0 (a feature a chart puts at u = 0, with
// coefficients of hundreds of bits), a narrow ball at |z| = 2^-k keeps
// about prec bits of p(z), p'(z), p''(z) themselves, not of p's size on a
// cell 2^-7 wide: p = t^m r(t) with random r (r(0) != 0, 300-bit
// coefficients), m = 1, 2, at the exact points 3 2^-k and -5 2^-k (20 <=
// k <= 400) and 64 bits. A level-6 cell's expansion about 2^-7 loses about
// (k - 7) m bits of p(z): everything from k ~ 70. The same for
// eval_deflated of p (2t - 1) by its root 1/2 (2 p).
TEST(LocalPoly, PointsNextToARootAtZeroKeepTheirRelativeAccuracy) {
  std::mt19937_64 rng(20261205);
  std::uniform_int_distribution<long> kdist(20, 400), ddist(3, 12);
  const long prec = 64;
  for (long it = 0; it < iterations(40); ++it) {
    const int m = 1 + static_cast<int>(it % 2);
    Poly r = random_poly(rng, ddist(rng), 1000);
    if (r.coeff(0).sign() == 0) r = r + Poly(1);
    Poly p = r;
    fmpz_poly_scalar_mul_2exp(p.get(), p.get(), 300);
    fmpz_poly_shift_left(p.get(), p.get(), m);
    const LocalPoly lp(p);
    // pd = p (2t - 1): eval_deflated by its root 1/2 gives back 2 p
    const Poly pd = p * Poly(std::vector<long>{-1, 2});
    const LocalPoly lpd(pd);
    const RealAlgebraic half(Rational(1, 2));
    arb_poly_t exact, e1, e2;
    arb_poly_init(exact);
    arb_poly_init(e1);
    arb_poly_init(e2);
    arb_poly_set_fmpz_poly(exact, p.get(), kRefPrec);
    arb_poly_derivative(e1, exact, kRefPrec);
    arb_poly_derivative(e2, e1, kRefPrec);
    for (int b = 0; b < 8; ++b) {
      const long k = kdist(rng);
      acb_t z, v, d1, d2;
      for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
      acb_set_si(z, b % 2 ? 3 : -5);
      acb_mul_2exp_si(z, z, -k);
      lp.eval(v, d1, d2, z, prec);
      const arb_poly_struct* refs[3] = {exact, e1, e2};
      const acb_struct* outs[3] = {v, d1, d2};
      for (int j = 0; j < 3; ++j) {
        arb_t ref;
        arb_init(ref);
        arb_poly_evaluate(ref, refs[j], acb_realref(z), kRefPrec);
        EXPECT_TRUE(arb_contains(acb_realref(outs[j]), ref) && arb_contains_zero(acb_imagref(outs[j]))) << "derivative " << j << " at 2^-" << k;
        // relative radius at most 2^-(prec - 16)
        mag_t lo, rad;
        mag_init(lo);
        mag_init(rad);
        arb_get_mag_lower(lo, ref);
        mag_mul_2exp_si(lo, lo, 16 - prec);
        mag_hypot(rad, arb_radref(acb_realref(outs[j])), arb_radref(acb_imagref(outs[j])));
        EXPECT_LE(mag_cmp(rad, lo), 0) << "t^" << m << " (" << r.str() << "), derivative " << j << " at 2^-" << k
                                       << ": radius " << mag_get_d(rad) << " > " << mag_get_d(lo);
        mag_clear(lo);
        mag_clear(rad);
        arb_clear(ref);
      }
      // p (2t - 1) / (t - 1/2) = 2 p
      lpd.eval_deflated(v, z, half, prec);
      {
        arb_t ref;
        arb_init(ref);
        arb_poly_evaluate(ref, exact, acb_realref(z), kRefPrec);
        arb_mul_2exp_si(ref, ref, 1);
        EXPECT_TRUE(arb_contains(acb_realref(v), ref) && arb_contains_zero(acb_imagref(v))) << "deflated at 2^-" << k;
        mag_t lo, rad;
        mag_init(lo);
        mag_init(rad);
        arb_get_mag_lower(lo, ref);
        mag_mul_2exp_si(lo, lo, 16 - prec);
        mag_hypot(rad, arb_radref(acb_realref(v)), arb_radref(acb_imagref(v)));
        EXPECT_LE(mag_cmp(rad, lo), 0) << "deflated, t^" << m << " (" << r.str() << ") at 2^-" << k
                                       << ": radius " << mag_get_d(rad) << " > " << mag_get_d(lo);
        mag_clear(lo);
        mag_clear(rad);
        arb_clear(ref);
      }
      for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
    }
    arb_poly_clear(exact);
    arb_poly_clear(e1);
    arb_poly_clear(e2);
  }
}

}  // namespace
}  // namespace uniparam

namespace uniparam {
namespace {

// Copies share one cache, and evaluations from several threads at once give
// exactly the enclosures a fresh LocalPoly gives on one thread (a cell
// depends only on its key, never on who built it or when).
TEST(LocalPoly, CopiesShareCellsAndThreadsGetTheSameEnclosures) {
  std::mt19937_64 rng(7121);
  for (long it = 0; it < iterations(4); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly shared(p);
    const LocalPoly copy = shared;  // NOLINT: the copy is the point
    constexpr int kBalls = 200;
    std::vector<acb_struct> balls(kBalls);
    for (auto& z : balls) {
      acb_init(&z);
      random_ball(&z, rng);
    }
    // the reference: a fresh LocalPoly, one thread, in order
    std::vector<acb_struct> ref(3 * kBalls);
    for (auto& v : ref) acb_init(&v);
    {
      const LocalPoly fresh(p);
      for (int b = 0; b < kBalls; ++b) fresh.eval(&ref[3 * b], &ref[3 * b + 1], &ref[3 * b + 2], &balls[b], 96);
    }
    // two threads on the shared cache (one through the copy), in opposite orders
    std::vector<acb_struct> got(6 * kBalls);
    for (auto& v : got) acb_init(&v);
    // thread t writes outputs t; `forward` is its order
    auto run_in = [&](const LocalPoly& lp, int t, bool forward) {
      for (int k = 0; k < kBalls; ++k) {
        const int b = forward ? k : kBalls - 1 - k;
        acb_ptr o = &got[static_cast<std::size_t>(3 * (t * kBalls + b))];
        lp.eval(o, o + 1, o + 2, &balls[b], 96);
      }
      flint_cleanup();  // this thread's FLINT caches (as parallel_for's workers do)
    };
    auto run = [&](const LocalPoly& lp, int t) { run_in(lp, t, t == 0); };
    std::thread a(run, std::cref(shared), 0), c(run, std::cref(copy), 1);
    a.join();
    c.join();
    EXPECT_GT(shared.cells(), 0u);
    EXPECT_EQ(shared.cells(), copy.cells());  // one cache
    const LocalPoly late = shared;             // NOLINT: a copy made after the work
    EXPECT_EQ(late.cells(), shared.cells());
    for (int t = 0; t < 2; ++t)
      for (int b = 0; b < 3 * kBalls; ++b)
        ASSERT_TRUE(acb_equal(&got[static_cast<std::size_t>(3 * t * kBalls + b)], &ref[static_cast<std::size_t>(b)]))
            << "thread " << t << ", output " << b % 3 << " of ball " << b / 3 << ", degree " << p.degree();
    EXPECT_EQ(shared.builds(), shared.cells());  // far below the cache's limit: nothing emptied
    // Two threads in the same order ask for the same cells at about the same
    // time: each is still built once (the second waits for the first).
    {
      const LocalPoly fresh(p);
      const LocalPoly fresh_copy = fresh;  // NOLINT: the copy is the point
      std::thread x(run_in, std::cref(fresh), 0, true), y(run_in, std::cref(fresh_copy), 1, true);
      x.join();
      y.join();
      EXPECT_EQ(fresh.builds(), fresh.cells()) << "degree " << p.degree();
      for (int t = 0; t < 2; ++t)
        for (int b = 0; b < 3 * kBalls; ++b)
          ASSERT_TRUE(acb_equal(&got[static_cast<std::size_t>(3 * t * kBalls + b)], &ref[static_cast<std::size_t>(b)]));
    }
    for (auto& v : got) acb_clear(&v);
    for (auto& v : ref) acb_clear(&v);
    for (auto& z : balls) acb_clear(&z);
  }
}

// A thread keeps the powers of the last w = z - c (the factors of a speed
// are evaluated at the same z, often on cells with the same centre): every
// evaluation must give what it gives alone on a fresh thread, whatever was
// evaluated before on its own thread (other polynomials, other balls,
// other precisions, fewer or more terms).
TEST(LocalPoly, SharedPowersGiveTheEnclosuresOfALoneEvaluation) {
  std::mt19937_64 rng(2311);
  for (long it = 0; it < iterations(3); ++it) {
    // p and q of the same degree share cell centres; r of another degree
    // has more or fewer terms on the same cells
    const long n = std::uniform_int_distribution<long>(20, 120)(rng);
    const LocalPoly p(random_poly(rng, n, 20)), q(random_poly(rng, n, 20)),
        r(random_poly(rng, std::uniform_int_distribution<long>(11, 160)(rng), 20));
    const LocalPoly* polys[3] = {&p, &q, &r};
    constexpr int kBalls = 40;
    const long precs[2] = {64, 200};
    // calls: (poly, ball, prec), in an order that reuses and invalidates the powers
    std::vector<std::array<int, 3>> calls;
    for (int b = 0; b < kBalls; ++b)
      for (int k : {0, 1, 2, 1})
        calls.push_back({k, b, static_cast<int>(std::uniform_int_distribution<int>(0, 1)(rng))});
    std::vector<acb_struct> balls(kBalls), got(3 * calls.size()), alone(3 * calls.size());
    for (auto& z : balls) {
      acb_init(&z);
      random_ball(&z, rng);
    }
    for (auto& v : got) acb_init(&v);
    for (auto& v : alone) acb_init(&v);
    auto call = [&](std::size_t i, acb_ptr o) {
      const auto& c = calls[i];
      polys[c[0]]->eval(o, o + 1, o + 2, &balls[static_cast<std::size_t>(c[1])], precs[c[2]]);
    };
    std::thread seq([&] {
      for (std::size_t i = 0; i < calls.size(); ++i) call(i, &got[3 * i]);
      flint_cleanup();
    });
    seq.join();
    for (std::size_t i = 0; i < calls.size(); ++i) {
      std::thread lone([&] {
        call(i, &alone[3 * i]);
        flint_cleanup();
      });
      lone.join();
      for (int j = 0; j < 3; ++j)
        ASSERT_TRUE(acb_equal(&got[3 * i + static_cast<std::size_t>(j)], &alone[3 * i + static_cast<std::size_t>(j)]))
            << "call " << i << " (polynomial " << calls[i][0] << ", ball " << calls[i][1] << ", precision "
            << precs[calls[i][2]] << "), output " << j;
    }
    for (auto& v : got) acb_clear(&v);
    for (auto& v : alone) acb_clear(&v);
    for (auto& z : balls) acb_clear(&z);
  }
}

// p has real coefficients: on a real ball its enclosures are real (an
// imaginary radius would make a square root of a positive quantity look as
// if it could cross its branch cut).
TEST(LocalPoly, RealBallsGiveRealEnclosures) {
  std::mt19937_64 rng(5);
  for (long it = 0; it < iterations(20); ++it) {
    const LocalPoly lp(random_test_poly(rng));
    for (int b = 0; b < 40; ++b) {
      acb_t z, v, d1, d2;
      for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
      random_ball(z, rng);
      arb_zero(acb_imagref(z));
      lp.eval(v, d1, d2, z, 80);
      for (acb_srcptr x : {v, d1, d2}) ASSERT_TRUE(acb_is_real(x)) << "ball " << b << " of polynomial " << it;
      for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
    }
  }
}

}  // namespace
}  // namespace uniparam
