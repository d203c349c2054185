// reparam/src/arc_model.hpp -- INTERNAL: certified Taylor models of
// G(u) = int sigma on short intervals of one speed's parameter, for the
// locator's cover (locate_cover.cpp; docs/locate.md, "Taylor models").
//
// On an interval [a, b] of the parameter free of zeros of sigma in its
// interior, sigma is the restriction of the analytic function
//     f(z) = s * g(z) * sqrt(Q(z)) / D(z),   Q = sum K_k^2,  s = +-1
// (Speed's factored form), holomorphic on the disc |z - c| <= rho around
// the centre c where Q avoids (-inf, 0] and D does not vanish. With M a
// bound of |f| on that disc, Cauchy's estimates give, for |x| <= h <= rho,
//     |f(c + x) - T_N(x)| <= e = M q^(N+1) / (1 - q),  q = h / rho,
// T_N the Taylor polynomial of degree N (its coefficients as balls, from
// Arb's power series arithmetic on g, Q and D shifted to c). So with
// P(x) = int_0^x T_N,
//     int_{c+x1}^{c+x2} sigma  in  P(x2) - P(x1) +- |x2 - x1| e
// for every -h <= x1, x2 <= h: one model gives G on the whole interval.
#pragma once

#include <arb_poly.h>

#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

/// One certified model of int sigma on [a, b] (see above).
class ArcCell {
 public:
  ArcCell();
  ~ArcCell();
  ArcCell(const ArcCell&);
  ArcCell& operator=(const ArcCell&);

  Rational a, b;     ///< the interval, a < b
  Rational c;        ///< its centre (dyadic), a < c < b
  Ball xa, xb;       ///< a - c and b - c (exact)
  Ball e;            ///< the bound e of |sigma(c + x) - T_N(x)| on [xa, xb]
  Ball integral;     ///< contains int_a^b sigma
  arb_poly_t T;      ///< T_N (balls)
  arb_poly_t P;      ///< int_0^x T_N (balls)
  std::vector<double> Td, Pd;  ///< the midpoints of T and P, in double (Newton's guesses only)
  Ball Pxa;          ///< P(xa)
  std::vector<DDBall> Pdd;  ///< P's coefficients as double-word balls (containing Arb's)
  double L = 0;      ///< an upper bound of |T_N'| on [xa, xb] (rounded up)
  double Terr = 0;   ///< |T_N(x) - Horner's rule on Td in double at x| <= Terr on [xa, xb]
  bool use_dd = false;  ///< P evaluated in double-word balls (their ~100 bits suffice for the accuracy asked)
  /// The accuracies (bits) up to which double-word balls serve.
  static constexpr long kDDBits = 80;
  long wp = 128;     ///< the working precision of the model's balls

  /// A ball containing int_a^{c + x} sigma for the ball x within [xa, xb].
  Ball from_a(const Ball& x, long prec) const;
  /// from_a at a double x in [xa, xb], by Horner's rule in double-word
  /// balls (~100 bits; the coefficients' and the rounding's errors
  /// included), and an enclosure [s - r, s + r] of sigma(c + x) from
  /// Horner's rule in double on Td. False when a result is not finite.
  bool at_double(double x, Ball& from_a_x, double& s, double& r) const;
};

/// Builds ArcCells for one speed (its polynomials converted once).
class ArcModeller {
 public:
  /// \pre s not identically zero.
  explicit ArcModeller(const Speed& s);
  ~ArcModeller();
  ArcModeller(const ArcModeller&) = delete;
  ArcModeller& operator=(const ArcModeller&) = delete;

  /// A model of int sigma on [a, b] (0 <= a < b <= 1; the open interval
  /// (a, b) holds no zero of sigma: the caller checks) whose integral over
  /// [a, b] has a relative radius of at most about 2^-bits, with Taylor
  /// degree at most max_degree. \return false (out unspecified) when the
  /// hypotheses cannot be certified on [a, b] (a singularity of sigma's
  /// continuation too close, sigma's sign at the centre undecided) or the
  /// accuracy needs a higher degree: the caller tries a shorter interval.
  bool build(const Rational& a, const Rational& b, long bits, ArcCell& out) const;

  static constexpr long max_degree = 48;

  /// False when the speed's polynomials are too large for models to pay
  /// off (A = 2 Q D above degree 64: every cell would shift polynomials of
  /// that degree, more work than a certified integral): the caller uses
  /// certified integrals instead.
  bool worthwhile() const { return !too_large_; }
  static constexpr long kMaxDegreeA = 64;

 private:
  const Speed& s_;
  arb_poly_t g_, Q_, D_;  // exact (integer coefficients)
  // h = sqrt(Q) / D solves A h' = B h, A = 2 Q D, B = Q' D - 2 Q D'
  // (exact): its Taylor coefficients by the recurrence of that equation
  arb_poly_t A_, B_;
  long extra_bits_ = 0;     // the shifts' precision above wp
  bool too_large_ = false;  // not worthwhile()
};

}  // namespace uniparam
