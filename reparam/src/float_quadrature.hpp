// reparam/src/float_quadrature.hpp -- UNCERTIFIED double-precision quadrature
// of the piece integrals, private to reparam/.
//
// Used only to *choose* data that is certified afterwards (the optimiser of
// the breakpoints T, the refinement of the C1 method): nothing computed here
// is ever reported as a result. sigma^2 is evaluated in double from the speed's
// local expansions (Speed::squared_double), in ball arithmetic where that is
// not finite.
#pragma once

#include <map>
#include <utility>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam::detail {

/// The 20-point Gauss-Legendre rule on [-1, 1] (nodes x, weights w), by
/// Newton's method on P_20 in double: for the uncertified quadratures only.
struct GaussLegendre20 {
  static constexpr int kNodes = 20;
  double x[kNodes], w[kNodes];
};
const GaussLegendre20& gauss_legendre20();

/// sigma(t)^2 2^(-2 scale_exp) rounded to double (uncertified). t in [0, 1].
/// A nonzero scale_exp brings a speed beyond double's range (sigma^2 near
/// 2^2000 for a huge coefficient) into it: such values come from the ball
/// path, scaled exactly before the rounding to double.
double sigma2_double(const Speed& s, double t, long scale_exp = 0);

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

/// x rounded to double from a 64-bit enclosure (uncertified).
double midpoint_double(const RealAlgebraic& x);

/// The C1 method's draft integrals of a piece [a, a + h] (uncertified): the
/// integrals of sigma^2 (1-t~)^2, 2 t~ (1-t~), t~^2 and of sigma, all over dt.
struct FloatPiece {
  double A = 0, B = 0, C = 0, len = 0;
};
FloatPiece operator+(const FloatPiece& x, const FloatPiece& y);

/// FloatPiece integrals of the pieces [a, b], cached per pair of
/// breakpoints (a refinement round keeps most breakpoints, so most pieces are
/// reused): 20-point Gauss-Legendre panels, split at the zeros of sigma and
/// bisected until the moments and the length change by at most 1e-13 of the
/// piece's first estimates (at most 30 levels; the time budget is checked
/// every 4; at most 1024 panel pairs per part between zeros). The
/// integrals are of sigma 2^-scale_exp (sigma2_double): the draft's
/// quantities are all relative, so any exact scale serves, and one near
/// 1 / mu keeps a speed beyond double's range inside it.
/// \pre s outlives the object. Not thread-safe.
class FloatPieces {
 public:
  explicit FloatPieces(const Speed& s, long scale_exp = 0);
  const FloatPiece& get(double a, double b);

 private:
  const Speed& s_;
  long scale_exp_;
  std::vector<double> zeros_;
  std::map<std::pair<double, double>, FloatPiece> cache_;
};

}  // namespace uniparam::detail
