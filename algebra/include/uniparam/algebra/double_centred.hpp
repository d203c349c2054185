// uniparam/algebra/double_centred.hpp -- certified bounds of a low-degree
// integer polynomial and its first two derivatives on a wide complex ball,
// by the centred form at the ball's midpoint computed in IEEE double with a
// rigorous bound of its rounding errors.
//
// Why: the quadrature bounds a speed on ellipses around each subinterval
// (wide balls). At low degree a LocalPoly cell's build (Taylor shifts in
// Arb) costs far more than the O(n^2) flops of a shift in double, and the
// centred form at the ball's own midpoint is at least as tight as a cell's
// expansion at a nearby dyadic centre. Its rounding errors are about
// 2n 2^-53 of the Taylor coefficients of |p| (the polynomial of the
// |coefficients|) at the centre, so it suits degrees <= 64 whose power basis
// loses few bits; where p is small against its coefficients the rounding
// dominates, and the caller may refuse such bounds (max_error).
#pragma once

#include <acb.h>

#include <vector>

#include "uniparam/core/cdisk.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// The centred form in double of a fixed integer polynomial p.
class DoubleCentredForm {
 public:
  /// Largest degree, and the bound 2^kMaxBits of the coefficients' size
  /// (so that no intermediate overflows before the radii).
  static constexpr long kMaxDegree = 64;
  static constexpr long kMaxBits = 800;

  DoubleCentredForm() = default;
  /// \post usable() iff 0 <= deg p <= kMaxDegree and every coefficient is
  ///       below 2^kMaxBits in magnitude.
  explicit DoubleCentredForm(const Poly& p);
  bool usable() const { return !a_.empty(); }

  /// Enclosures of p(z), p'(z), p''(z) (outputs may be null, and may not
  /// alias z) on a complex ball z with midpoint m (real or complex):
  ///     p^(j)(t) in j! c_j +- (j! E_j + sum_{k>j} k!/(k-j)! (|c_k| + E_k) r^(k-j))
  /// for every t in z, with c_k the Taylor coefficients at m rounded to a
  /// double, computed in double, E_k rigorous bounds of their errors, and
  /// r >= |t - m| the hypot of z's radii (a disc holding the box). A real z
  /// (zero imaginary radius) gives real enclosures.
  /// \pre usable().
  /// \return true with the enclosures; false (outputs unspecified) when
  ///       |m| > 2, r > 2^8, a bound is not finite,
  ///       or, for some output, the rounding part (the terms in E) exceeds
  ///       max_error times |centre| + variation (the terms in |c_k|).
  bool eval(acb_t v, acb_t d1, acb_t d2, const acb_t z, double max_error) const;
  /// eval's enclosures as the discs j! c_j +- (...) themselves (CDisk; a
  /// real z gives discs whose real segments enclose the real values), for
  /// callers that go on in disc arithmetic. Same \pre and \return.
  bool eval_disks(CDisk* v, CDisk* d1, CDisk* d2, const acb_t z, double max_error) const;

  /// Enclosure of p(t) / (t - gamma) for every t in z, for a real root gamma
  /// of p in [gamma_mid - gamma_rad, gamma_mid + gamma_rad]: the centred form
  /// of the quotient, whose Taylor coefficients at m come from p's by
  /// synthetic division by (w - (gamma - m)), with rigorous bounds of the
  /// rounding, of p's coefficients' errors and of gamma's uncertainty (no
  /// division by t - gamma, so no cancellation near gamma).
  /// \pre usable() and p(gamma) = 0 exactly (not checked here).
  /// \return as eval (false also for a constant p, |gamma_mid| > 4 or
  ///       gamma_rad > 1).
  bool eval_deflated(acb_t v, const acb_t z, double gamma_mid, double gamma_rad, double max_error) const;

 private:
  struct Shift {
    double m = 0, mi = 0, am = 0, r = 0, eps = 0;  // centre m + i mi, am >= |m|, radius, E_k / D_k
    // c_k (real parts; ci: imaginary parts, null for a real centre) and, when
    // asked, D_k (else null); thread-local
    const std::vector<double>*c = nullptr, *ci = nullptr, *D = nullptr;
  };
  // The Taylor coefficients at z's midpoint (see eval), with the majorants
  // D_k when `majorants`; false as eval.
  bool shift(const acb_t z, Shift& sh, bool majorants) const;

  std::vector<double> a_, abs_a_;  // p's coefficients rounded towards zero, and |.|
};

}  // namespace uniparam
