// Tests of taylor_shift_pow2 (core/ball_poly.hpp): random ball polynomials
// against the exact shift of exact polynomials picked inside their balls.
#include <gtest/gtest.h>

#include <arb_poly.h>
#include <flint/fmpq.h>

#include <random>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

// The exact midpoint and radius of a ball as rationals.
Rational mid_q(const arb_t x) { return mid_rational(Ball(x)); }
Rational rad_q(const arb_t x) { return rad_rational(Ball(x)); }

bool contains(const arb_t x, const Rational& q) { return arb_contains_fmpq(x, q.get()); }

// out_j = sum_{k >= j} C(k, j) a_k d^(k - j), exactly.
std::vector<Rational> exact_shift(const std::vector<Rational>& a, const Rational& d) {
  const std::size_t n = a.size();
  std::vector<Rational> out(n, Rational(0));
  for (std::size_t j = 0; j < n; ++j) {
    Rational dk(1);  // d^(k - j)
    Integer binom(1);  // C(k, j)
    for (std::size_t k = j; k < n; ++k) {
      if (k > j) {
        dk = dk * d;
        fmpz_mul_ui(binom.get(), binom.get(), static_cast<ulong>(k));
        fmpz_divexact_ui(binom.get(), binom.get(), static_cast<ulong>(k - j));
      }
      out[j] = out[j] + Rational(binom) * a[k] * dk;
    }
  }
  return out;
}

// A random ball polynomial: midpoints of random sizes (exponents spread
// over ~100 bits, some zero), radii zero or a little below the midpoints'
// last bits.
void random_ball_poly(arb_poly_t p, std::mt19937_64& rng, long n, long bits) {
  std::uniform_int_distribution<long> expo(-60, 40), coin(0, 3);
  std::uniform_int_distribution<ulong> mant(0, ~0ULL);
  arb_poly_fit_length(p, n);
  for (long k = 0; k < n; ++k) {
    arb_ptr c = p->coeffs + k;
    if (coin(rng) == 0) {
      arb_zero(c);
    } else {
      fmpz_t m;
      fmpz_init(m);
      fmpz_set_ui(m, mant(rng));
      for (long b = 64; b < bits; b += 64) {
        fmpz_mul_2exp(m, m, 64);
        fmpz_add_ui(m, m, mant(rng));
      }
      if (coin(rng) < 2) fmpz_neg(m, m);
      arb_set_fmpz(c, m);
      arb_mul_2exp_si(c, c, expo(rng) - bits);
      fmpz_clear(m);
    }
    if (coin(rng) != 0) {
      mag_set_ui_2exp_si(arb_radref(c), static_cast<ulong>(coin(rng) + 1), expo(rng) - bits);
    }
  }
  _arb_poly_set_length(p, n);
  _arb_poly_normalise(p);
}

TEST(TaylorShiftPow2, EnclosesTheExactShiftOfEveryPolynomialInTheBalls) {
  std::mt19937_64 rng(20261122);
  std::uniform_int_distribution<long> len(1, 40), ex(-12, 3), pick(-4, 4);
  std::uniform_int_distribution<int> sign(0, 1);
  const long precs[] = {53, 64, 128, 300};
  for (long it = 0; it < iterations(60); ++it) {
    const long n = len(rng), e = ex(rng), prec = precs[it % 4];
    const int s = sign(rng) ? 1 : -1;
    BallPoly p, q;
    random_ball_poly(p.get(), rng, n, prec + 20);
    taylor_shift_pow2(q.get(), p.get(), e, s, prec);
    // Polynomials inside p's balls: mid + t rad with t in {-1, -3/4, ..., 1},
    // the ends included (where a dropped radius shows).
    for (int trial = 0; trial < 3; ++trial) {
      std::vector<Rational> a;
      for (long k = 0; k < arb_poly_length(p.get()); ++k) {
        const arb_struct* c = p.get()->coeffs + k;
        const long t = trial == 0 ? 4 : trial == 1 ? -4 : pick(rng);
        a.push_back(mid_q(c) + rad_q(c) * Rational(t, 4));
      }
      const std::vector<Rational> want = exact_shift(a, Rational(s) * pow2(e));
      ASSERT_EQ(static_cast<long>(want.size()), arb_poly_length(p.get()));
      for (std::size_t j = 0; j < want.size(); ++j) {
        arb_t got;
        arb_init(got);
        arb_poly_get_coeff_arb(got, q.get(), static_cast<slong>(j));
        EXPECT_TRUE(contains(got, want[j])) << "n = " << n << ", e = " << e << ", s = " << s << ", coefficient " << j;
        arb_clear(got);
      }
    }
  }
}

// Radii alone (zero midpoints): the output radius of coefficient j must be
// at least sum_{k >= j} C(k, j) r_k 2^(e (k - j)) (the shift of the radii,
// for either sign), and, where a radius within 2^-200 of the largest enters
// that sum (radii far below may be raised to 2^-1000 of it), within 2^-20 of it (the
// double path, n <= 900) or n 2^-28 (the mag path: each of up to n mag
// additions rounds up by 2^-30). Lengths up to 953 reach both paths.
TEST(TaylorShiftPow2, RadiiAreShiftedUpwardAndTightly) {
  std::mt19937_64 rng(2311);
  std::uniform_int_distribution<int> kind(0, 3), sign(0, 1);
  std::uniform_int_distribution<long> near(-200, 0), far(-1150, -1050), ex(-8, 0), top(-3000, 3000);
  std::uniform_int_distribution<ulong> mant(1, (1UL << 30) - 1);
  for (long it = 0; it < iterations(24); ++it) {
    const long n = it % 6 == 5 ? 950 + static_cast<long>(kind(rng)) : 2 + static_cast<long>(rng() % 160);
    const long e = ex(rng), R = top(rng);
    BallPoly p, q;
    arb_poly_fit_length(p.get(), n);
    std::vector<Rational> r(static_cast<std::size_t>(n), Rational(0));
    std::vector<bool> is_near(static_cast<std::size_t>(n), false);  // within 2^-200 of the largest
    for (long k = 0; k < n; ++k) {
      arb_ptr c = p.get()->coeffs + k;
      arb_zero(c);
      const int kd = k == 0 ? 3 : kind(rng);  // r_0 sets the scale
      if (kd == 0) continue;
      const long x = R + (kd == 1 ? far(rng) : near(rng));
      is_near[static_cast<std::size_t>(k)] = kd != 1;
      mag_set_ui_2exp_si(arb_radref(c), mant(rng), x - 30);
      r[static_cast<std::size_t>(k)] = rad_q(c);
    }
    _arb_poly_set_length(p.get(), n);  // zero midpoints: length set by hand
    taylor_shift_pow2(q.get(), p.get(), e, sign(rng) ? 1 : -1, 64);
    const long step = n > 200 ? n / 7 : 1;
    for (long j = 0; j < n; j += step) {
      Rational want(0);
      Integer binom(1);  // C(k, j)
      bool any_near = false;
      for (long k = j; k < n; ++k) {
        any_near = any_near || is_near[static_cast<std::size_t>(k)];
        if (k > j) {
          fmpz_mul_ui(binom.get(), binom.get(), static_cast<ulong>(k));
          fmpz_divexact_ui(binom.get(), binom.get(), static_cast<ulong>(k - j));
        }
        if (r[static_cast<std::size_t>(k)].sign() != 0)
          want = want + Rational(binom) * r[static_cast<std::size_t>(k)] * pow2(e * (k - j));
      }
      const arb_struct* c = j < arb_poly_length(q.get()) ? q.get()->coeffs + j : nullptr;
      const Rational got = c ? rad_q(c) : Rational(0);
      ASSERT_TRUE(c == nullptr || arf_is_zero(arb_midref(c)));
      ASSERT_GE(got, want) << "n = " << n << ", coefficient " << j;
      const Rational slack = n <= 900 ? pow2(-20) : Rational(n) * pow2(-28);
      if (any_near) EXPECT_LE(got, want * (Rational(1) + slack)) << "n = " << n << ", coefficient " << j;
    }
  }
}

TEST(TaylorShiftPow2, AnExactInputIsRoundedOnceToPrec) {
  // Exact balls: every output is the exact shift rounded once, so its
  // radius is at most 2^-prec of its midpoint (Arb's arb_poly_taylor_shift
  // rounds at every step and may not be this tight; a shift that truncated
  // the inputs would not be).
  std::mt19937_64 rng(7);
  std::uniform_int_distribution<long> len(2, 60), ex(-10, 0);
  for (long it = 0; it < iterations(40); ++it) {
    const long n = len(rng), e = ex(rng), prec = 64 + 32 * (it % 5);
    BallPoly p, q;
    random_ball_poly(p.get(), rng, n, prec);
    for (long k = 0; k < arb_poly_length(p.get()); ++k) mag_zero(arb_radref(p.get()->coeffs + k));
    taylor_shift_pow2(q.get(), p.get(), e, it % 2 ? 1 : -1, prec);
    for (long k = 0; k < arb_poly_length(q.get()); ++k) {
      const arb_struct* c = q.get()->coeffs + k;
      if (arf_is_zero(arb_midref(c))) {
        EXPECT_TRUE(mag_is_zero(arb_radref(c)));
        continue;
      }
      mag_t m;
      mag_init(m);
      arf_get_mag(m, arb_midref(c));
      mag_mul_2exp_si(m, m, -prec + 1);
      EXPECT_LE(mag_cmp(arb_radref(c), m), 0) << "coefficient " << k << " of " << n;
      mag_clear(m);
    }
  }
}

TEST(TaylorShiftPow2, NonFiniteBallsAndAliasing) {
  BallPoly p;
  arb_poly_set_coeff_si(p.get(), 0, 1);
  arb_poly_set_coeff_si(p.get(), 1, 2);
  arb_poly_set_coeff_si(p.get(), 2, 3);  // 1 + 2w + 3w^2
  // in place, w -> w + 1/2: 1 + 1 + 3/4, 2 + 3, 3
  taylor_shift_pow2(p.get(), p.get(), -1, 1, 64);
  EXPECT_TRUE(contains(p.get()->coeffs + 0, Rational(11, 4)));
  EXPECT_TRUE(contains(p.get()->coeffs + 1, Rational(5)));
  EXPECT_TRUE(contains(p.get()->coeffs + 2, Rational(3)));
  // an infinite radius spreads to every coefficient it reaches, never lost
  mag_inf(arb_radref(p.get()->coeffs + 2));
  taylor_shift_pow2(p.get(), p.get(), -3, -1, 64);
  for (long k = 0; k < 3; ++k) EXPECT_FALSE(arb_is_finite(p.get()->coeffs + k)) << k;
  EXPECT_THROW(taylor_shift_pow2(p.get(), p.get(), 0, 0, 64), InvalidArgument);
  EXPECT_THROW(taylor_shift_pow2(p.get(), p.get(), 0, 2, 64), InvalidArgument);
}

}  // namespace
}  // namespace uniparam
