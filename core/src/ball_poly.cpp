#include "uniparam/core/ball_poly.hpp"

#include <flint/fmpz_poly.h>
#include <flint/fmpz_vec.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

// c(x + s) in ball arithmetic: Horner's n - 1 passes of additions. The
// fallback for non-finite balls or extreme exponents.
void shift_by_one_balls(arb_ptr c, slong n, int s, long prec) {
  for (slong i = n - 2; i >= 0; --i)
    for (slong j = i; j < n - 1; ++j) {
      if (s > 0) arb_add(c + j, c + j, c + j + 1, prec);
      else arb_sub(c + j, c + j, c + j + 1, prec);
    }
}

// Exponents beyond this take the ball fallback (slong arithmetic below).
constexpr slong kMaxExp = slong(1) << 40;
// Integers of more bits than this (plus 16 prec) take the fallback too.
constexpr slong kMaxSpan = 1 << 16;

// Radii longer than this take mag additions in shift_radii: their sums grow
// by up to 2^n, which doubles hold below 2^1023.
constexpr slong kMaxDoubleShift = 900;

// r_j <- upper bounds of sum_{k >= j} C(k, j) r_k: the radii's shift by one
// (the same sums for either sign of the shift). In doubles on one scale 2^R
// (R the largest exponent of a radius): Horner's n - 1 passes add
// non-negative doubles rounded to nearest, each with a relative error of at
// most u = 2^-53, and every result is at most n - 1 additions deep, so it is
// at least (1 - u)^(n - 1) of the true sum; the results are raised by
// 1 + 4 n u and converted upward. Radii below 2^(R - 1000) are raised to it
// (no subnormals), zero radii stay zero. Long inputs or extreme exponents
// take mag additions (the same bounds, ~30x the instructions).
void shift_radii(std::vector<mag_struct>& r) {
  const slong n = static_cast<slong>(r.size());
  slong R = 0;
  bool any = false, doubles = n <= kMaxDoubleShift;
  for (const mag_struct& x : r) {
    if (mag_is_zero(&x)) continue;
    if (!mag_is_finite(&x) || !fmpz_fits_si(MAG_EXPREF(&x))) {
      any = true;
      doubles = false;
      break;
    }
    const slong ex = fmpz_get_si(MAG_EXPREF(&x));
    if (ex > kMaxExp || ex < -kMaxExp) doubles = false;
    if (!any || ex > R) R = ex;
    any = true;
  }
  if (!any) return;  // all zero
  if (!doubles) {
    for (slong i = n - 2; i >= 0; --i)
      for (slong j = i; j < n - 1; ++j)
        mag_add(&r[static_cast<std::size_t>(j)], &r[static_cast<std::size_t>(j)], &r[static_cast<std::size_t>(j + 1)]);
    return;
  }
  std::vector<double> d(static_cast<std::size_t>(n), 0.0);
  mag_t t;
  mag_init(t);
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (mag_is_zero(&r[k])) continue;
    if (fmpz_get_si(MAG_EXPREF(&r[k])) - R < -1000) {
      d[k] = std::ldexp(1.0, -1000);
    } else {
      mag_mul_2exp_si(t, &r[k], -R);
      d[k] = mag_get_d(t);  // an upper bound, <= 1
    }
  }
  mag_clear(t);
  for (slong i = n - 2; i >= 0; --i)
    for (slong j = i; j < n - 1; ++j) d[static_cast<std::size_t>(j)] += d[static_cast<std::size_t>(j + 1)];
  const double raise = 1 + 4 * static_cast<double>(n) * std::ldexp(1.0, -53);
  for (std::size_t k = 0; k < r.size(); ++k) {
    if (d[k] == 0) {
      mag_zero(&r[k]);
      continue;
    }
    mag_set_d(&r[k], d[k] * raise);  // an upper bound of the product, itself above the sum
    mag_mul_2exp_si(&r[k], &r[k], R);
  }
}

// c(x + s) by midpoints and radii apart: the midpoints as exact integers on
// one grid 2^E, shifted exactly by FLINT (fmpz additions), rounded once to
// prec; the radii shifted by mag additions (upper bounds of
// sum_k C(k, j) r_k). Several times cheaper than n^2 / 2 arb_add. False (c
// untouched) when a ball is not finite or the exponents are extreme.
bool shift_by_one_fixed(arb_ptr c, slong n, int s, long prec) {
  slong top = 0, low = 0;
  bool any = false;
  for (slong k = 0; k < n; ++k) {
    if (!arb_is_finite(c + k)) return false;
    const arf_struct* m = arb_midref(c + k);
    if (arf_is_zero(m)) continue;
    const fmpz* ex = ARF_EXPREF(m);
    if (!fmpz_fits_si(ex)) return false;
    const slong x = fmpz_get_si(ex);
    if (x > kMaxExp || x < -kMaxExp) return false;
    const slong lb = x - static_cast<slong>(arf_bits(m));  // value of the lowest bit: 2^lb
    if (!any || x > top) top = x;
    if (!any || lb < low) low = lb;
    any = true;
  }
  // the grid: the lowest bit of any midpoint, so the integers are exact
  // (a grid relative to the largest coefficient would lose the small ones,
  // which alone make the high coefficients of the result). Spans beyond
  // kMaxSpan bits take the ball fallback.
  if (any && top - low > kMaxSpan + 16 * static_cast<slong>(prec)) return false;
  std::vector<mag_struct> r(static_cast<std::size_t>(n));
  for (auto& x : r) mag_init(&x);
  fmpz* m = _fmpz_vec_init(n);
  const slong E = any ? low : 0;
  for (slong k = 0; k < n; ++k) {
    mag_struct* rk = &r[static_cast<std::size_t>(k)];
    mag_set(rk, arb_radref(c + k));
    arf_get_fmpz_fixed_si(m + k, arb_midref(c + k), E);  // exact: E is at or below every lowest bit
  }
  fmpz_t one;
  fmpz_init_set_si(one, s);
  _fmpz_poly_taylor_shift(m, one, n);
  fmpz_clear(one);
  shift_radii(r);
  fmpz_t ef;
  fmpz_init_set_si(ef, E);
  for (slong k = 0; k < n; ++k) {
    arb_set_round_fmpz_2exp(c + k, m + k, ef, prec);
    mag_add(arb_radref(c + k), arb_radref(c + k), &r[static_cast<std::size_t>(k)]);
  }
  fmpz_clear(ef);
  _fmpz_vec_clear(m, n);
  for (auto& x : r) mag_clear(&x);
  return true;
}

}  // namespace

void taylor_shift_pow2(arb_poly_t out, const arb_poly_t in, long e, int s, long prec) {
  if (s != 1 && s != -1) throw InvalidArgument("taylor_shift_pow2: the sign must be +1 or -1");
  arb_poly_set(out, in);
  const slong n = arb_poly_length(out);
  if (n <= 1) return;
  arb_ptr c = out->coeffs;
  // c_k 2^(e k): the shift by s 2^e becomes a shift by s (exact scalings)
  for (slong k = 1; k < n; ++k) arb_mul_2exp_si(c + k, c + k, e * k);
  if (!shift_by_one_fixed(c, n, s, prec)) shift_by_one_balls(c, n, s, prec);
  for (slong k = 1; k < n; ++k) arb_mul_2exp_si(c + k, c + k, -e * k);
}

}  // namespace uniparam
