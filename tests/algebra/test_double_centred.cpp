// Tests of uniparam/algebra/double_centred.hpp: the centred form in double
// contains the exact values of p, p', p'' at exact points of wide balls
// (checked at 4000 bits), is as tight as the exact centred form up to its
// documented rounding part, keeps its rounding bound where the rounding
// dominates (near a zero of p after cancellation), gives real enclosures on
// real balls, and refuses what its contract excludes.
#include <acb.h>
#include <acb_poly.h>
#include <arb_poly.h>
#include <flint/fmpz_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support/balls.hpp"
#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/double_centred.hpp"

namespace uniparam {
namespace {

using test_support::expect_encloses_at_points;

// |c| rounded to a double (an estimate, for tightness bounds only).
double acb_get_d_abs_for_test(const acb_t c) {
  return std::hypot(arf_get_d(arb_midref(acb_realref(c)), ARF_RND_NEAR), arf_get_d(arb_midref(acb_imagref(c)), ARF_RND_NEAR));
}
using test_support::iterations;
using test_support::pure_power;

struct Balls {
  acb_t z, v, d1, d2;
  Balls() {
    for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
  }
  ~Balls() {
    for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
  }
  Balls(const Balls&) = delete;
  Balls& operator=(const Balls&) = delete;
  void set(double mid, double rx, double ry, double mid_im = 0) {
    acb_zero(z);
    arb_set_d(acb_realref(z), mid);
    arb_set_d(acb_imagref(z), mid_im);
    mag_set_d(arb_radref(acb_realref(z)), rx);
    mag_set_d(arb_radref(acb_imagref(z)), ry);
  }
};

// On K (2^b t - a)^n around a 2^-b the bound is the exact centred form up to
// its rounding part (pure_power_radius), and holds at the corners, where it
// is attained: a looser form, a missing hypot of the radii or a wrong
// derivative factor fails.
TEST(DoubleCentredForm, IsTheExactCentredFormUpToRoundingOnPurePowers) {
  std::mt19937_64 rng(112326);
  std::uniform_real_distribution<double> unit(0, 1);
  for (long it = 0; it < iterations(200); ++it) {
    const test_support::PurePower c = test_support::random_pure_power(rng);
    const DoubleCentredForm form(c.p);
    ASSERT_TRUE(form.usable());
    Balls x;
    const double rx = c.m * (0.25 + 1.75 * unit(rng));
    x.set(c.m, rx, it % 3 == 0 ? 0 : rx * unit(rng));
    ASSERT_TRUE(form.eval(x.v, x.d1, x.d2, x.z, HUGE_VAL));
    const acb_struct* outs[3] = {x.v, x.d1, x.d2};
    const std::string what = "of K (2^b t - a)^n, n = " + std::to_string(c.n);
    test_support::expect_pure_power_bounds(c, outs, x.z, rng, what);
    if (it % 3 == 0)
      for (const acb_struct* o : outs) EXPECT_TRUE(acb_is_real(o)) << "a real ball " << what;
  }
}

// Near the zero a 2^-b of K (2^b t - a)^n, with radii 2^-24 .. 2^-20, the
// value 0 comes out of heavy cancellation: the rounding part must cover it
// (forced with max_error = infinity). Without it, or with a wrong bound of
// the Taylor coefficients of |p|, the midpoint's value escapes. With
// max_error = 2^-10 such bounds are refused.
TEST(DoubleCentredForm, TheRoundingBoundCoversCancellationNearAZero) {
  std::mt19937_64 rng(2311);
  std::uniform_int_distribution<long> deg(3, 12), bits(2, 20), scale(1, 1000);
  long refused = 0, total = 0;
  for (long it = 0; it < iterations(300); ++it) {
    const long n = deg(rng), b = bits(rng), K = scale(rng);
    const long a = std::uniform_int_distribution<long>(1, (1L << b) - 1)(rng) | 1;
    const Poly p = pure_power(K, a, b, n);
    const DoubleCentredForm form(p);
    ASSERT_TRUE(form.usable());
    Balls x;
    x.set(std::ldexp(static_cast<double>(a), static_cast<int>(-b)),
          std::ldexp(1.0, -std::uniform_int_distribution<int>(20, 24)(rng)),
          it % 2 ? 0 : std::ldexp(1.0, -std::uniform_int_distribution<int>(20, 30)(rng)));
    ASSERT_TRUE(form.eval(x.v, x.d1, x.d2, x.z, HUGE_VAL));
    const acb_struct* outs[3] = {x.v, x.d1, x.d2};
    expect_encloses_at_points(p, outs, x.z, rng, "near the zero of K (2^b t - a)^n, n = " + std::to_string(n));
    refused += !form.eval(x.v, x.d1, x.d2, x.z, 0x1p-10);
    ++total;
  }
  EXPECT_EQ(refused, total) << "the rounding dominates every one of these enclosures";
}

// Dense polynomials up to degree 64, coefficients up to 2^780, real and
// complex balls of radius 2^-24 .. 256 around points of [-0.25, 1.25]:
// every enclosure given holds at the exact points and is finite; the large
// radii overflow and are refused.
TEST(DoubleCentredForm, EnclosesDensePolynomialsAndRefusesOverflow) {
  std::mt19937_64 rng(6402);
  std::uniform_real_distribution<double> unit(0, 1);
  long refused = 0;
  for (long it = 0; it < iterations(40); ++it) {
    Poly p = test_support::random_poly(rng, std::uniform_int_distribution<long>(3, 64)(rng), 1000);
    if (it % 4 == 0) fmpz_poly_scalar_mul_2exp(p.get(), p.get(), 780);
    const DoubleCentredForm form(p);
    ASSERT_TRUE(form.usable());
    for (int k = 0; k < 10; ++k) {
      Balls x;
      const double rx = std::ldexp(1.0 + unit(rng), -std::uniform_int_distribution<int>(-7, 23)(rng));
      x.set(-0.25 + 1.5 * unit(rng), rx, k % 2 ? rx * unit(rng) : 0);
      if (!form.eval(x.v, x.d1, x.d2, x.z, HUGE_VAL)) {
        ++refused;
        continue;
      }
      const acb_struct* outs[3] = {x.v, x.d1, x.d2};
      expect_encloses_at_points(p, outs, x.z, rng, "of a dense polynomial of degree " + std::to_string(p.degree()));
      for (acb_srcptr o : {x.v, x.d1, x.d2}) {
        EXPECT_TRUE(acb_is_finite(o));
        if (k % 2 == 0) EXPECT_TRUE(acb_is_real(o)) << "a real ball";
      }
    }
  }
  EXPECT_GT(refused, 0) << "some radii must overflow";
}

// Boxes above the real axis (the quadrature's upper-half boxes): complex
// midpoints x + i y, x in [-0.25, 1.25], y in [0, 1], radii 2^-24 .. 2, of
// dense polynomials up to degree 64 (coefficients up to 1000, or times
// 2^780). Every enclosure given holds at the exact points; and it is about
// as tight as the exact centred form there: at most twice the majorant
// sum_{k>=1} |d_k| r^k of p - p(m) (d_k the exact Taylor coefficients at
// the double midpoint m, r the hypot of the radii) plus 2^-30 of
// sum |a_j| (|m| + r)^j, which bounds the rounding part many times over.
// An imaginary part left out of the synthetic division, or a real |m| for
// the bound, fails the first; a much looser bound the second.
TEST(DoubleCentredForm, EnclosesPolynomialsOnBallsWithComplexMidpoints) {
  std::mt19937_64 rng(240611);
  std::uniform_real_distribution<double> unit(0, 1);
  long checked = 0;
  acb_poly_t exact;
  acb_poly_init(exact);
  acb_t m, c;
  acb_init(m);
  acb_init(c);
  for (long it = 0; it < iterations(60); ++it) {
    Poly p = test_support::random_poly(rng, std::uniform_int_distribution<long>(3, 64)(rng), 1000);
    if (it % 4 == 0) fmpz_poly_scalar_mul_2exp(p.get(), p.get(), 780);
    const DoubleCentredForm form(p);
    ASSERT_TRUE(form.usable());
    for (int k = 0; k < 6; ++k) {
      Balls x;
      const double rx = std::ldexp(1.0 + unit(rng), -std::uniform_int_distribution<int>(1, 24)(rng));
      const double re = -0.25 + 1.5 * unit(rng), im = unit(rng);
      x.set(re, rx, rx * (0.25 + unit(rng)), im);
      if (!form.eval(x.v, x.d1, x.d2, x.z, HUGE_VAL)) continue;
      ++checked;
      const acb_struct* outs[3] = {x.v, x.d1, x.d2};
      expect_encloses_at_points(p, outs, x.z, rng, "of a polynomial of degree " + std::to_string(p.degree()) +
                                                        " on a ball around " + std::to_string(re) + " + " +
                                                        std::to_string(im) + "i");
      for (acb_srcptr o : {x.v, x.d1, x.d2}) EXPECT_TRUE(acb_is_finite(o));
      // tightness of the value's enclosure
      acb_set_d_d(m, re, im);
      acb_poly_set_fmpz_poly(exact, p.get(), 4000);
      acb_poly_taylor_shift(exact, exact, m, 4000);
      const double r = std::hypot(mag_get_d(arb_radref(acb_realref(x.z))), mag_get_d(arb_radref(acb_imagref(x.z))));
      double var = 0, scale = 0;
      const double am = std::hypot(re, im);
      for (long j = p.degree(); j >= 0; --j) {
        acb_poly_get_coeff_acb(c, exact, j);
        const double cj = j >= 1 ? acb_get_d_abs_for_test(c) : 0.0;
        var = var * r + cj;
        scale = scale * (am + r) + std::fabs(fmpz_get_d(p.get()->coeffs + j));
      }
      const double rad = std::max(mag_get_d(arb_radref(acb_realref(x.v))), mag_get_d(arb_radref(acb_imagref(x.v))));
      EXPECT_LE(rad, 2 * var + 0x1p-30 * scale) << "degree " << p.degree() << " at " << re << " + " << im << "i, r " << r;
    }
  }
  EXPECT_GT(checked, iterations(60) * 3);
  acb_poly_clear(exact);
  acb_clear(m);
  acb_clear(c);
}

// p = (2t^2 - 1) q with gamma = 1/sqrt(2) known only to [mid +- rad] (mid
// off by up to 2^-25): the quotient's enclosure on wide balls around gamma
// holds p(t) / (t - gamma) = 2 (t + gamma) q(t) at the exact points, against
// gamma at 4000 bits. Without the bound of gamma's uncertainty or of p's
// coefficients' errors, points escape (the division's own rounding is
// smaller than the latter and not seen separately).
TEST(DoubleCentredForm, DeflatedEnclosesTheQuotientForARootKnownToAnyAccuracy) {
  std::mt19937_64 rng(5151);
  std::uniform_real_distribution<double> unit(0, 1);
  arb_t g;
  arb_init(g);
  arb_set_ui(g, 2);
  arb_rsqrt(g, g, 4000);  // gamma = 1/sqrt(2)
  const double g_double = arf_get_d(arb_midref(g), ARF_RND_NEAR);
  acb_t t, exact, qv;
  acb_init(t);
  acb_init(exact);
  acb_init(qv);
  long escaped_points = 0, checked = 0;
  for (long it = 0; it < iterations(150); ++it) {
    const Poly q = test_support::random_poly(rng, std::uniform_int_distribution<long>(1, 20)(rng), 50);
    const Poly p = Poly(std::vector<long>{-1, 0, 2}) * q;
    const DoubleCentredForm form(p);
    ASSERT_TRUE(form.usable());
    const int off = static_cast<int>(it % 3);  // gamma's midpoint: nearest, or off by ~2^-40 or ~2^-25
    const double delta = off == 0 ? 0 : std::ldexp(unit(rng) - 0.5, off == 1 ? -40 : -25);
    const double g_mid = g_double + delta, g_rad = std::fabs(delta) + 0x1p-50;
    Balls x;
    const double rx = std::ldexp(1.0 + unit(rng), -std::uniform_int_distribution<int>(3, 24)(rng));
    const double mid = std::ldexp(std::round(std::ldexp(g_double + rx * (unit(rng) - 0.5), 30)), -30);
    // real balls, complex balls about the real axis, and (it % 4 == 3)
    // boxes above it, with a complex midpoint
    x.set(mid, rx, it % 2 ? rx * unit(rng) : 0, it % 4 == 3 ? rx * unit(rng) : 0);
    if (!form.eval_deflated(x.v, x.z, g_mid, g_rad, HUGE_VAL)) continue;
    ++checked;
    arb_poly_t qp;
    arb_poly_init(qp);
    arb_poly_set_fmpz_poly(qp, q.get(), ARF_PREC_EXACT);
    for (const auto& [a, c] : test_support::offsets(rng)) {
      test_support::point_of(t, x.z, a, c);
      arb_poly_evaluate_acb(qv, qp, t, 4000);
      acb_add_arb(exact, t, g, 4000);
      acb_mul(exact, exact, qv, 4000);
      acb_mul_2exp_si(exact, exact, 1);
      if (!acb_contains(x.v, exact)) ++escaped_points;
    }
    if (it % 2 == 0) EXPECT_TRUE(acb_is_real(x.v));
    arb_poly_clear(qp);
  }
  EXPECT_EQ(escaped_points, 0);
  EXPECT_GT(checked, iterations(150) / 2);
  for (acb_ptr y : {t, exact, qv}) acb_clear(y);
  arb_clear(g);
}

// What the contract excludes is refused: |m| > 2 (real or complex m),
// r > 2^8; for the quotient, a constant p, |gamma_mid| > 4 or
// gamma_rad > 1; and polynomials of degree > 64 or coefficients of 800 bits
// are not usable.
// The rounding part of each output j is the documented majorant
// 1.01 L u |p|^(j)(|m| + r), |p| = sum |a_i| t^i (L = 2n + 3 for a real
// midpoint, 4n + 3 for a complex one; the underflow slack is negligible
// here): measured through max_error, whose refusal compares it with
// |centre| + variation (both from the exact Taylor shift at 4000 bits).
// Just below the majorant's ratio the output is refused, just above it is
// given: a rounding part without the radius in |m| + r, or with |p| for
// |p|' or |p|'', fails.
TEST(DoubleCentredForm, TheRoundingPartIsTheMajorantOfTheAbsoluteCoefficients) {
  std::mt19937_64 rng(90125);
  std::uniform_real_distribution<double> unit(0, 1);
  acb_poly_t exact;
  acb_poly_init(exact);
  acb_t m, c;
  acb_init(m);
  acb_init(c);
  long checked = 0;
  for (long it = 0; it < iterations(80); ++it) {
    const Poly p = test_support::random_poly(rng, std::uniform_int_distribution<long>(3, 64)(rng), 1000);
    const DoubleCentredForm form(p);
    ASSERT_TRUE(form.usable());
    const long n = p.degree();
    Balls x;
    const double re = -0.25 + 1.5 * unit(rng), im = it % 2 ? 0.5 * unit(rng) : 0;
    const double rx = std::ldexp(1.0 + unit(rng), -std::uniform_int_distribution<int>(1, 8)(rng));
    x.set(re, rx, it % 3 == 0 ? 0 : rx * unit(rng), im);
    const double r = std::hypot(mag_get_d(arb_radref(acb_realref(x.z))), mag_get_d(arb_radref(acb_imagref(x.z))));
    const double am = std::hypot(re, im), s = am + r;
    const double eps = 1.01 * static_cast<double>((im == 0 ? 2 : 4) * n + 3) * 0x1p-53;
    acb_set_d_d(m, re, im);
    acb_poly_set_fmpz_poly(exact, p.get(), 4000);
    acb_poly_taylor_shift(exact, exact, m, 4000);
    for (int j = 0; j <= 2; ++j) {
      // |p|^(j)(s) and j! |c_j| + sum_{k>j} k!/(k-j)! |c_k| r^(k-j)
      double major = 0, scale = 0;
      for (long k = n; k >= j; --k) {
        const double f = j == 0 ? 1.0 : j == 1 ? static_cast<double>(k) : static_cast<double>(k * (k - 1));
        major = major * s + f * std::fabs(fmpz_get_d(p.get()->coeffs + k));
        acb_poly_get_coeff_acb(c, exact, k);
        scale = scale * r + f * acb_get_d_abs_for_test(c);
      }
      const double ratio = eps * major / scale;
      acb_ptr out[3] = {nullptr, nullptr, nullptr};
      out[j] = j == 0 ? x.v : j == 1 ? x.d1 : x.d2;
      const std::string what = "output " + std::to_string(j) + ", degree " + std::to_string(n) + " at " +
                               std::to_string(re) + " + " + std::to_string(im) + "i, r " + std::to_string(r);
      if (!form.eval(out[0], out[1], out[2], x.z, HUGE_VAL)) continue;  // (overflow)
      ++checked;
      EXPECT_FALSE(form.eval(out[0], out[1], out[2], x.z, 0.999 * ratio))
          << "rounding part below the majorant, " << what;
      EXPECT_TRUE(form.eval(out[0], out[1], out[2], x.z, 1.001 * ratio))
          << "rounding part above the majorant, " << what;
    }
  }
  EXPECT_GT(checked, iterations(80) * 2);
  acb_poly_clear(exact);
  acb_clear(m);
  acb_clear(c);
}

TEST(DoubleCentredForm, RefusesWhatItsContractExcludes) {
  const Poly p = pure_power(3, 1, 2, 5);
  const DoubleCentredForm form(p);
  Balls x;
  x.set(0.5, 0.1, 0.1);
  EXPECT_TRUE(form.eval(x.v, nullptr, nullptr, x.z, HUGE_VAL));
  x.set(0.5, 0.1, 0.1, 0.25);
  EXPECT_TRUE(form.eval(x.v, nullptr, nullptr, x.z, HUGE_VAL)) << "a complex midpoint";
  EXPECT_FALSE(acb_is_real(x.v));
  x.set(1.5, 0.1, 0.1, 1.5);
  EXPECT_FALSE(form.eval(x.v, nullptr, nullptr, x.z, HUGE_VAL)) << "|m| = 2.12 > 2";
  EXPECT_FALSE(form.eval_deflated(x.v, x.z, 0.25, 0x1p-60, HUGE_VAL)) << "|m| = 2.12 > 2";
  x.set(2.5, 0.1, 0);
  EXPECT_FALSE(form.eval(x.v, nullptr, nullptr, x.z, HUGE_VAL)) << "|m| > 2";
  x.set(0.5, 300, 0);
  EXPECT_FALSE(form.eval(x.v, nullptr, nullptr, x.z, HUGE_VAL)) << "r > 2^8";
  EXPECT_FALSE(DoubleCentredForm(pure_power(1, 1, 1, 65)).usable());
  EXPECT_TRUE(DoubleCentredForm(pure_power(1, 1, 1, 64)).usable());
  for (long a : {1L, -1L}) {  // (2t -+ 1)^3 2^796: 800 bits (8 t^3), of either sign pattern
    Poly big = pure_power(1, a, 1, 3);
    fmpz_poly_scalar_mul_2exp(big.get(), big.get(), 796);
    EXPECT_FALSE(DoubleCentredForm(big).usable()) << a;
    fmpz_poly_scalar_fdiv_2exp(big.get(), big.get(), 1);
    EXPECT_TRUE(DoubleCentredForm(big).usable()) << a;
  }
  EXPECT_FALSE(DoubleCentredForm(Poly()).usable());
  // a constant has no quotient; gamma far away or too uncertain is refused
  EXPECT_FALSE(DoubleCentredForm(Poly(std::vector<long>{3})).eval_deflated(x.v, x.z, 0.5, 0x1p-60, HUGE_VAL));
  x.set(0.25, 0.1, 0);
  EXPECT_TRUE(form.eval_deflated(x.v, x.z, 0.25, 0x1p-60, HUGE_VAL));  // 1/4: the root of 3 (4t - 1)^5
  EXPECT_FALSE(form.eval_deflated(x.v, x.z, 4.5, 0x1p-60, HUGE_VAL));
  EXPECT_FALSE(form.eval_deflated(x.v, x.z, 0.25, 2, HUGE_VAL));
}

}  // namespace
}  // namespace uniparam
