// tests/support/bezier_point.hpp -- an independent exact evaluator of
// (rational) Bezier curves, the oracle of the path readers' tests.
#pragma once

#include <flint/fmpz.h>

#include <cstddef>
#include <vector>

#include "uniparam/core/number.hpp"
#include "uniparam/reparam/bezier.hpp"

namespace uniparam::test_support {

/// The exact point of b at the rational t, by the Bernstein sum
/// sum_i w_i P_i B_i^n(t) / sum_i w_i B_i^n(t) (weights 1 for an integral
/// curve). \pre the denominator is not 0 at t (positive weights, t in [0, 1]).
inline std::vector<Rational> bezier_point(const BezierCurve& b, const Rational& t) {
  const auto& p = b.points();
  const auto w = b.weights();
  const long n = b.degree();
  std::vector<Rational> num(b.dimension(), Rational(0));
  Rational den(0);
  for (long i = 0; i <= n; ++i) {
    Integer binom;
    fmpz_bin_uiui(binom.get(), static_cast<unsigned long>(n), static_cast<unsigned long>(i));
    Rational basis(binom);
    for (long k = 0; k < i; ++k) basis = basis * t;
    for (long k = 0; k < n - i; ++k) basis = basis * (Rational(1) - t);
    basis = basis * w[static_cast<std::size_t>(i)];
    den = den + basis;
    for (std::size_t c = 0; c < num.size(); ++c) num[c] = num[c] + basis * p[static_cast<std::size_t>(i)][c];
  }
  for (auto& x : num) x = x / den;
  return num;
}

}  // namespace uniparam::test_support
