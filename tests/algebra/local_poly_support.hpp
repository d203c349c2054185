// Helpers shared by the LocalPoly tests (test_local_poly.cpp,
// test_local_poly_double.cpp): Bezier and random test polynomials, random
// balls, exact reference derivatives.
#pragma once

#include <arb_poly.h>
#include <flint/fmpz_poly.h>

#include <random>
#include <vector>

#include "support/balls.hpp"
#include "support/curves.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::local_poly_test {

using test_support::random_poly;

constexpr long kRefPrec = 4000;

/// Power-basis coefficients of sum_k b_k C(n,k) t^k (1-t)^(n-k): a Bezier
/// polynomial, whose power-basis coefficients dwarf its values on [0, 1].
inline Poly bernstein(const std::vector<long>& b) {
  const long n = static_cast<long>(b.size()) - 1;
  fmpz_poly_t acc, term, lin, one_minus;
  fmpz_poly_init(acc);
  fmpz_poly_init(term);
  fmpz_poly_init(lin);
  fmpz_poly_init(one_minus);
  fmpz_poly_set_coeff_si(lin, 1, 1);
  fmpz_poly_set_coeff_si(one_minus, 0, 1);
  fmpz_poly_set_coeff_si(one_minus, 1, -1);
  fmpz_t binom;
  fmpz_init(binom);
  for (long k = 0; k <= n; ++k) {
    fmpz_poly_pow(term, lin, static_cast<ulong>(k));
    fmpz_poly_t r;
    fmpz_poly_init(r);
    fmpz_poly_pow(r, one_minus, static_cast<ulong>(n - k));
    fmpz_poly_mul(term, term, r);
    fmpz_poly_clear(r);
    fmpz_bin_uiui(binom, static_cast<ulong>(n), static_cast<ulong>(k));
    fmpz_mul_si(binom, binom, b[static_cast<std::size_t>(k)]);
    fmpz_poly_scalar_mul_fmpz(term, term, binom);
    fmpz_poly_add(acc, acc, term);
  }
  Poly p;
  fmpz_poly_set(p.get(), acc);
  fmpz_clear(binom);
  fmpz_poly_clear(acc);
  fmpz_poly_clear(term);
  fmpz_poly_clear(lin);
  fmpz_poly_clear(one_minus);
  return p;
}

/// A random test polynomial of degree >= 11 (the cells' range): dense small
/// coefficients, or a Bezier polynomial of degree up to 160.
inline Poly random_test_poly(std::mt19937_64& rng) {
  std::uniform_int_distribution<int> kind(0, 1);
  if (kind(rng) == 0) return random_poly(rng, std::uniform_int_distribution<long>(11, 90)(rng), 20);
  const long n = std::uniform_int_distribution<long>(11, 160)(rng);
  std::uniform_int_distribution<long> c(-1000, 1000);
  std::vector<long> b(static_cast<std::size_t>(n + 1));
  for (auto& x : b) x = c(rng);
  return bernstein(b);
}

/// A random complex ball: midpoint in [-0.2, 1.2] (+ a small imaginary part
/// sometimes), radius 0 (a point), tiny, or wide (2^-3 .. 2^-20).
inline void random_ball(acb_t z, std::mt19937_64& rng) {
  std::uniform_int_distribution<long> re(-209715, 1258291);  // [-0.2, 1.2] * 2^20
  std::uniform_int_distribution<long> num(-(1L << 20), 1L << 20);
  std::uniform_int_distribution<int> pick(0, 3);
  acb_zero(z);
  arb_set_si(acb_realref(z), re(rng));
  arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
  if (pick(rng) == 0) {
    arb_set_si(acb_imagref(z), num(rng));
    arb_mul_2exp_si(acb_imagref(z), acb_imagref(z), -27);
  }
  const int k = pick(rng);
  if (k == 0) return;  // a point
  const long e = k == 1 ? -std::uniform_int_distribution<long>(26, 60)(rng)
                        : -std::uniform_int_distribution<long>(3, 20)(rng);
  mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1 + std::uniform_int_distribution<ulong>(0, 7)(rng), e - 3);
  if (pick(rng) != 0) mag_set_ui_2exp_si(arb_radref(acb_imagref(z)), 1 + std::uniform_int_distribution<ulong>(0, 7)(rng), e - 3);
}

/// p, p', p'' as exact Arb polynomials (the reference evaluations).
struct RefDerivatives {
  arb_poly_t r[3];
  explicit RefDerivatives(const Poly& p) {
    for (auto& x : r) arb_poly_init(x);
    arb_poly_set_fmpz_poly(r[0], p.get(), ARF_PREC_EXACT);
    arb_poly_derivative(r[1], r[0], ARF_PREC_EXACT);
    arb_poly_derivative(r[2], r[1], ARF_PREC_EXACT);
  }
  ~RefDerivatives() {
    for (auto& x : r) arb_poly_clear(x);
  }
  RefDerivatives(const RefDerivatives&) = delete;
  RefDerivatives& operator=(const RefDerivatives&) = delete;
};

}  // namespace uniparam::local_poly_test
