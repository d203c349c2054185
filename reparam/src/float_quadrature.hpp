// reparam/src/float_quadrature.hpp -- UNCERTIFIED double-precision quadrature
// of the piece integrals, private to reparam/.
//
// Used only to *choose* data that is certified afterwards (the optimiser of
// the breakpoints T, the refinement of the C1 method): nothing computed here
// is ever reported as a result. sigma^2 is evaluated in double from the speed's
// local expansions (Speed::squared_double), in ball arithmetic where that is
// not finite.
#pragma once

#include "uniparam/reparam/speed.hpp"

namespace uniparam::detail {

/// The 20-point Gauss-Legendre rule on [-1, 1] (nodes x, weights w), by
/// Newton's method on P_20 in double: for the uncertified quadratures only.
struct GaussLegendre20 {
  static constexpr int kNodes = 20;
  double x[kNodes], w[kNodes];
};
const GaussLegendre20& gauss_legendre20();

/// sigma(t)^2 rounded to double (uncertified). t in [0, 1].
double sigma2_double(const Speed& s, double t);

/// Uncertified A, B, C of a piece [a, b] (the integrals of sigma^2 (1-t~)^2,
/// sigma^2 2 t~ (1-t~), sigma^2 t~^2 over dt), by adaptive 20-point
/// Gauss-Legendre with the usual error estimate (relative tolerance 1e-12, at
/// most 256 bisections).
struct FloatABC {
  double A = 0, B = 0, C = 0;
  /// The contribution min_alpha (b-a)[(1-a)/a A + B + a/(1-a) C] = (b-a)(B + 2 sqrt(AC)).
  double M(double h) const;
};
FloatABC float_abc(const Speed& s, double a, double b);

}  // namespace uniparam::detail
