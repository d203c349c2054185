// approx_roots.cpp -- UNCERTIFIED complex root approximations
// (approx_roots.hpp): the Aberth-Ehrlich iteration in IEEE double.
#include "uniparam/algebra/approx_roots.hpp"

#include <flint/fmpz.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using C = std::complex<double>;

// A root is settled (no longer updated) once its correction is below this
// fraction of max(|z|, 1): hints need a few digits, not all 15.
constexpr double kSettled = 0x1p-30;

constexpr double kPi = 3.14159265358979323846;  // M_PI is POSIX, not C++

// Plain complex products and quotients: std::complex's operators call
// __muldc3 / __divdc3 (C99 Annex G's infinity and NaN recovery), several
// times slower, and this iteration discards non-finite steps anyway.
inline C mul(C a, C b) { return {a.real() * b.real() - a.imag() * b.imag(), a.real() * b.imag() + a.imag() * b.real()}; }
inline C inv(C a) {
  const double d = a.real() * a.real() + a.imag() * a.imag();
  return {a.real() / d, -a.imag() / d};
}
inline C div(C a, C b) { return mul(a, inv(b)); }

/// p(z) / p'(z) for the coefficients c (low to high, c.back() != 0):
/// Horner's rule on p for |z| <= 1; beyond, on the reversal r(y) = y^n
/// p(1 / y) at y = 1 / z, where p / p' = z r / (n r - y r').
C newton_ratio(const std::vector<double>& c, C z) {
  const std::size_t n = c.size() - 1;
  if (std::abs(z) <= 1) {
    C b = c[n], d = 0;
    for (std::size_t k = n; k-- > 0;) {
      d = mul(d, z) + b;
      b = mul(b, z) + c[k];
    }
    return div(b, d);
  }
  const C y = inv(z);
  C b = c[0], d = 0;  // r's coefficients are c reversed: r_k = c[n - k]
  for (std::size_t k = 1; k <= n; ++k) {
    d = mul(d, y) + b;
    b = mul(b, y) + c[k];
  }
  return div(mul(z, b), static_cast<double>(n) * b - mul(y, d));
}

}  // namespace

std::vector<C> approximate_complex_roots(const Poly& p, bool* converged, int max_sweeps) {
  if (p.is_zero()) throw InvalidArgument("approximate_complex_roots: the zero polynomial has no finite root set");
  if (converged) *converged = false;
  const long deg = p.degree();
  const fmpz* a = p.get()->coeffs;
  long v = 0;  // roots at 0
  while (fmpz_is_zero(a + v)) ++v;
  std::vector<C> out(static_cast<std::size_t>(v), C(0));
  const long n = deg - v;
  if (n == 0) {
    if (converged) *converged = true;
    return out;
  }
  // coefficients of p / t^v scaled by a common power of 2 (the largest to ~1)
  std::vector<double> m(static_cast<std::size_t>(n + 1));
  std::vector<slong> e(static_cast<std::size_t>(n + 1));
  slong emax = std::numeric_limits<slong>::min();
  for (long k = 0; k <= n; ++k) {
    m[k] = fmpz_get_d_2exp(&e[k], a + v + k);
    if (m[k] != 0) emax = std::max(emax, e[k]);
  }
  std::vector<double> c(static_cast<std::size_t>(n + 1));
  for (long k = 0; k <= n; ++k) c[k] = m[k] == 0 ? 0 : std::ldexp(m[k], static_cast<int>(std::max<slong>(e[k] - emax, -2000)));
  if (c[n] == 0 || c[0] == 0) return {};  // a leading or trailing coefficient underflowed
  // Start on a circle of the roots' geometric mean modulus, turned off the axes.
  const double r0 = std::pow(std::abs(c[0]) / std::abs(c[n]), 1.0 / static_cast<double>(n));
  std::vector<C> z(static_cast<std::size_t>(n));
  std::vector<char> done(static_cast<std::size_t>(n), 0);
  for (long k = 0; k < n; ++k) z[k] = std::polar(r0, 0.4 + 2 * kPi * static_cast<double>(k) / static_cast<double>(n));
  bool all = false;
  for (int sweep = 0; sweep < max_sweeps && !all; ++sweep) {
    all = true;
    for (long k = 0; k < n; ++k) {
      if (done[k]) continue;
      const C ratio = newton_ratio(c, z[k]);
      C s = 0;
      for (long j = 0; j < n; ++j)
        if (j != k) s += inv(z[k] - z[j]);
      const C w = div(ratio, 1.0 - mul(ratio, s));
      if (!std::isfinite(w.real()) || !std::isfinite(w.imag())) {
        // p'(z) = 0 or two iterates met: nudge the iterate and go on
        z[k] += C(0x1p-20, 0x1p-21) * std::max(1.0, std::abs(z[k]));
        all = false;
        continue;
      }
      z[k] -= w;
      if (std::abs(w) <= kSettled * std::max(std::abs(z[k]), 1.0)) done[k] = 1;
      else all = false;
    }
  }
  for (const C& r : z)
    if (!std::isfinite(r.real()) || !std::isfinite(r.imag())) return {};
  if (converged) *converged = all;
  out.insert(out.end(), z.begin(), z.end());
  return out;
}

}  // namespace uniparam
