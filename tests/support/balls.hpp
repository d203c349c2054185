// tests/support/balls.hpp -- exact points of complex balls, and the check
// that enclosures of a polynomial and its first two derivatives on a ball
// contain the exact values there.
#pragma once

#include <acb.h>
#include <arb_poly.h>
#include <flint/fmpz_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/poly.hpp"

namespace uniparam::test_support {

/// Offsets (a, b) in [-1, 1]^2 of exact points of a ball: its midpoint,
/// corners and four random points (see point_of).
inline std::vector<std::pair<double, double>> offsets(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<std::pair<double, double>> o{{0, 0}, {1, 1}, {-1, 1}, {1, -1}, {-1, -1}};
  for (int i = 0; i < 4; ++i) o.emplace_back(u(rng), u(rng));
  return o;
}

/// t = mid(z) + a rad(Re z) + i b rad(Im z), exactly, inside z (the
/// offsets are rounded towards zero).
inline void point_of(acb_t t, const acb_t z, double a, double b) {
  acb_zero(t);
  arb_set_arf(acb_realref(t), arb_midref(acb_realref(z)));
  arb_set_arf(acb_imagref(t), arb_midref(acb_imagref(z)));
  arf_t d, f;
  arf_init(d);
  arf_init(f);
  arf_set_mag(d, arb_radref(acb_realref(z)));
  arf_set_d(f, a);
  arf_mul(d, d, f, 53, ARF_RND_DOWN);  // |d| <= rad: rounding toward zero
  arb_add_arf(acb_realref(t), acb_realref(t), d, ARF_PREC_EXACT);
  arf_set_mag(d, arb_radref(acb_imagref(z)));
  arf_set_d(f, b);
  arf_mul(d, d, f, 53, ARF_RND_DOWN);
  arb_add_arf(acb_imagref(t), acb_imagref(t), d, ARF_PREC_EXACT);
  arf_clear(d);
  arf_clear(f);
}

/// Checks that outs[j] contains p^(j) (j = 0, 1, 2) at the exact points of
/// z given by offsets(rng), against evaluations at ref_prec bits.
inline void expect_encloses_at_points(const Poly& p, const acb_struct* const outs[3], const acb_t z,
                                      std::mt19937_64& rng, const std::string& what, long ref_prec = 4000) {
  arb_poly_t ref[3];
  for (auto& r : ref) arb_poly_init(r);
  arb_poly_set_fmpz_poly(ref[0], p.get(), ARF_PREC_EXACT);
  arb_poly_derivative(ref[1], ref[0], ARF_PREC_EXACT);
  arb_poly_derivative(ref[2], ref[1], ARF_PREC_EXACT);
  acb_t t, exact;
  acb_init(t);
  acb_init(exact);
  for (const auto& [a, c] : offsets(rng)) {
    point_of(t, z, a, c);
    for (int j = 0; j < 3; ++j) {
      arb_poly_evaluate_acb(exact, ref[j], t, ref_prec);
      EXPECT_TRUE(acb_contains(outs[j], exact)) << "derivative " << j << " at offset (" << a << ", " << c << ") " << what;
    }
  }
  acb_clear(t);
  acb_clear(exact);
  for (auto& r : ref) arb_poly_clear(r);
}

/// K (2^b t - a)^n: on a ball centred at m = a 2^-b all its variation is
/// the top term of its expansion there, |p^(j)(t)| = n!/(n-j)! K 2^(bn)
/// |t - m|^(n-j), so the centred form at m is exact up to rounding, while
/// its value at m is 0 after heavy cancellation in the power basis.
inline Poly pure_power(long K, long a, long b, long n) {
  fmpz_poly_t lin, q;
  fmpz_poly_init(lin);
  fmpz_poly_init(q);
  fmpz_poly_set_coeff_si(lin, 0, -a);
  fmpz_poly_set_coeff_si(lin, 1, 1L << b);
  fmpz_poly_pow(q, lin, static_cast<ulong>(n));
  fmpz_poly_scalar_mul_si(q, q, K);
  Poly p;
  fmpz_poly_set(p.get(), q);
  fmpz_poly_clear(lin);
  fmpz_poly_clear(q);
  return p;
}

/// The tight radius of the centred form of pure_power(K, a, b, n) on a
/// disc of radius r around a 2^-b, for derivative j: n!/(n-j)! K 2^(bn)
/// r^(n-j) (1 + 2^-25: a mag_t holds 30 bits), plus 2^-40 times its
/// majorant n!/(n-j)! K 2^(bj) (2a + 2^b r)^(n-j) (the rounding part:
/// about 2n 2^-53 of the Taylor coefficients of |p| at the centre).
inline double pure_power_radius(long K, long a, long b, long n, int j, double r) {
  double fall = 1;
  for (int i = 0; i < j; ++i) fall *= static_cast<double>(n - i);
  const double rb = std::ldexp(r, static_cast<int>(b));
  const double var = fall * static_cast<double>(K) * std::ldexp(std::pow(rb, static_cast<double>(n - j)), static_cast<int>(b * j));
  const double majorant = fall * static_cast<double>(K) *
                          std::ldexp(std::pow(2.0 * static_cast<double>(a) + rb, static_cast<double>(n - j)), static_cast<int>(b * j));
  return var * (1 + 0x1p-25) + 0x1p-40 * majorant;
}

/// A random pure_power(K, a, b, n): n in [3, 8], b in [1, 8], K in
/// [1, 1000], 0 < a < 2^b; its zero m = a 2^-b.
struct PurePower {
  long n, b, K, a;
  double m;
  Poly p;
};
inline PurePower random_pure_power(std::mt19937_64& rng) {
  PurePower c{};
  c.n = std::uniform_int_distribution<long>(3, 8)(rng);
  c.b = std::uniform_int_distribution<long>(1, 8)(rng);
  c.K = std::uniform_int_distribution<long>(1, 1000)(rng);
  c.a = std::uniform_int_distribution<long>(1, (1L << c.b) - 1)(rng);
  c.m = std::ldexp(static_cast<double>(c.a), static_cast<int>(-c.b));
  c.p = pure_power(c.K, c.a, c.b, c.n);
  return c;
}

/// Checks enclosures of a pure power's p, p', p'' on a ball z centred at its
/// zero: they contain the exact values at z's points (expect_encloses_at_points)
/// and their radii are within pure_power_radius (the exact centred form up
/// to rounding).
inline void expect_pure_power_bounds(const PurePower& c, const acb_struct* const outs[3], const acb_t z,
                                     std::mt19937_64& rng, const std::string& what) {
  expect_encloses_at_points(c.p, outs, z, rng, what);
  const double r = std::hypot(mag_get_d(arb_radref(acb_realref(z))), mag_get_d(arb_radref(acb_imagref(z))));
  for (int j = 0; j <= 2; ++j) {
    const double rad = std::max(mag_get_d(arb_radref(acb_realref(outs[j]))), mag_get_d(arb_radref(acb_imagref(outs[j]))));
    EXPECT_LE(rad, pure_power_radius(c.K, c.a, c.b, c.n, j, r)) << "derivative " << j << " " << what;
  }
}

}  // namespace uniparam::test_support
