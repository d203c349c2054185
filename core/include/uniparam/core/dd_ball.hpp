// uniparam/core/dd_ball.hpp -- real balls with a double-word midpoint: a
// fixed-precision (~100-bit) ball arithmetic for the quadrature's nodes,
// several times cheaper than Arb's 2-limb balls, and as rigorous.
#pragma once

#include <arb.h>

#include <cmath>
#include <vector>

#include "uniparam/core/poly.hpp"

namespace uniparam {

/// The real ball [hi + lo +/- rad]: hi + lo is a double-word number
/// (|lo| <= ulp(hi) / 2) and rad >= 0 a double.
///
/// Every operation below returns a ball that contains the exact result of
/// the operation for every choice of points in its input balls (the proof
/// is at the top of dd_ball.cpp). Relative accuracy is about 2^-100 of the
/// midpoint plus the propagated radii. A ball that is not finite (hi, lo or
/// rad NaN or infinite) means "nothing is known"; operations propagate it,
/// so callers check dd_is_finite once at the end. Magnitudes are kept within
/// 2^+-900: a product with a larger factor answers a non-finite ball, and an
/// absolute 2^-1000 is added to every radius to cover underflow.
struct DDBall {
  double hi = 0, lo = 0, rad = 0;
};

/// True if hi, lo and rad are finite.
inline bool dd_is_finite(const DDBall& x) {
  return std::isfinite(x.hi) && std::isfinite(x.lo) && std::isfinite(x.rad);
}
/// x as a DDBall. False (out unspecified) if x is not finite or its midpoint
/// or radius is outside 2^+-900. The midpoint is split into hi + lo and
/// what is left of it (for midpoints of more than 106 bits) goes to rad.
bool dd_set_arb(DDBall& out, const arb_t x);
/// out = x exactly (midpoint hi + lo, radius rad rounded upward).
/// \pre dd_is_finite(x)
void dd_get_arb(arb_t out, const DDBall& x);
/// The exact ball [v +/- 0] for a double v.
DDBall dd_from_double(double v);

/// -a, a + b, a - b, a b: balls containing the exact result for every
/// choice of points in the input balls (see DDBall); not finite when an
/// input is not, or beyond the magnitudes kept.
DDBall dd_neg(const DDBall& a);
DDBall dd_add(const DDBall& a, const DDBall& b);
DDBall dd_sub(const DDBall& a, const DDBall& b);
DDBall dd_mul(const DDBall& a, const DDBall& b);
/// a * 2^e, exact for |e| <= 64 (midpoints and radii within range).
DDBall dd_mul_2exp(const DDBall& a, int e);
/// a / b. False (out non-finite) if b's ball contains 0. out may alias a or b.
bool dd_div(DDBall& out, const DDBall& a, const DDBall& b);
/// sqrt(a). False (out non-finite) unless a's ball is contained in (0, inf).
/// out may alias a.
bool dd_sqrt(DDBall& out, const DDBall& a);
/// An upper bound of rad / |midpoint| (infinity when the midpoint is 0 or
/// the ball not finite): the relative accuracy of x.
double dd_rel_rad(const DDBall& x);

/// Whether this processor has a fused multiply-add that the double-word
/// products use (chosen once, at run time). Both paths give bit for bit the
/// same results (their TwoProds are both exact); the FMA one is faster.
bool dd_fma_available();
/// For tests and benchmarks: use the FMA path when `on` and available, the
/// portable one otherwise (the default is the FMA path where available).
/// Returns whether the FMA path is now in use. Safe to call at any time
/// (results do not change).
bool dd_set_fma(bool on);

/// A polynomial in Z[t] evaluated with its first two derivatives by Horner's
/// rule in double-word arithmetic, with a priori rounding bounds
/// (Higham, Accuracy and Stability of Numerical Algorithms, eq. 5.3).
/// For low degrees and coefficients that do not cancel much on the point,
/// several times cheaper than a ball evaluation at 2 limbs; the caller
/// checks the result's accuracy and falls back to Arb otherwise.
class DDPoly {
 public:
  DDPoly() = default;
  /// \post usable() iff every coefficient of p, p' and p'' is exactly a
  ///       double-word number below 2^500 in magnitude.
  explicit DDPoly(const Poly& p);
  bool usable() const { return usable_; }
  long degree() const { return n_; }
  /// v = p(x), d1 = p'(x), d2 = p''(x) (d1 and d2 may be null): balls that
  /// contain the values at every point of x. \pre usable().
  /// \return false if a bound is not finite (x too large).
  bool eval(DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) const;
  /// eval's body, inlined into a caller's loop (core/dd_inline.hpp, which
  /// defines it): F = true only inside a function compiled for FMA
  /// (UNIPARAM_DD_FMA) and called where dd_fma_in_use().
  template <bool F>
  bool eval_t(DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) const;
  /// Lanes q < k: out[q] = p[q]^(j[q])(x) (j[q] in 0..2), each bit for bit
  /// eval_t's ball, with the k Horner loops interleaved in one (independent
  /// chains of double-word operations, whose latency a lone loop waits on).
  /// Defined in core/dd_inline.hpp, as eval_t. \pre 1 <= k <= kMaxLanes,
  /// every p[q]->usable(); out[q] distinct. \return as eval_t, for all lanes
  /// (false, outputs unspecified, for k outside 1..kMaxLanes).
  static constexpr int kMaxLanes = 12;
  template <bool F>
  static bool eval_lanes(int k, const DDPoly* const* p, const int* j, DDBall* const* out, const DDBall& x);
  /// eval_lanes, out of line (the FMA path where in use, as eval).
  static bool eval_many(int k, const DDPoly* const* p, const int* j, DDBall* const* out, const DDBall& x);
  /// UNCERTIFIED estimate, for choosing a path only: the bits that
  /// Horner's rule loses on [0, 1] for p, p' and p'' (horner_loss_bits(p,
  /// 0, 1, 2), core/horner_loss.hpp); 0 for the zero polynomial and where
  /// the coefficients do not fit double words (not usable()).
  double cancellation_bits() const { return loss_; }

 private:
  // eval_t's and eval_lanes' rounding and slope bound (dd_inline.hpp)
  double horner_radius(int j, std::size_t len, double habs, double mr, double rad) const;
  bool usable_ = false;
  long n_ = -1;
  // coefficients (low to high) of p, p', p'' as double words
  std::vector<double> hi_[3], lo_[3];
  // single_[j]: every lo_[j] is 0 (Horner adds doubles, not double words)
  bool single_[3] = {false, false, false};
  // upper bounds of |coefficients| of p, p', p'', p'''
  std::vector<double> abs_[4];
  // horner_abs(abs_[j], 1): bounds of |p^(j)| on [-1, 1]
  double abs1_[4] = {0, 0, 0, 0};
  double loss_ = 0;
};

}  // namespace uniparam
