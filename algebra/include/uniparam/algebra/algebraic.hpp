// uniparam/algebra/algebraic.hpp -- real algebraic numbers.
//
// A RealAlgebraic is either an exact rational, or the unique root of a
// squarefree integer polynomial in an open isolating interval (lo, hi) with
// rational ends. Refinement only shrinks the interval, so every enclosure
// ever handed out stays valid.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/algebra/real_roots.hpp"

namespace uniparam {

class RealAlgebraic {
 public:
  /// The rational q (exact), with polynomial den*t - num.
  RealAlgebraic(const Rational& q);  // NOLINT: exact conversion
  RealAlgebraic(long q) : RealAlgebraic(Rational(q)) {}  // NOLINT: exact conversion
  /// From an isolated root (see real_roots.hpp). Unless r.certified (the
  /// isolator proved it), the contract of IsolatedRoot is checked exactly
  /// (InvalidArgument when the ends are roots or the factor does not change
  /// sign between them).
  explicit RealAlgebraic(const IsolatedRoot& r);
  /// From an isolated root, refined with the help of `sev` (may be null):
  /// an evaluator (real_roots.hpp) of lambda * r.factor, typically the
  /// factor's values from the factors of a product, far cheaper than its
  /// power basis at high degree. refine() then takes interval Newton steps
  /// with the derivative from sev at 64 bits, and needs no exact sign
  /// (root_refine.hpp). The check that r.lo and r.hi are not roots and
  /// that r.factor changes sign between them (skipped when r.certified)
  /// uses sev's enclosures at 64 bits first, exact signs only where those
  /// hold 0. The number keeps
  /// (shares) sev for as long as any copy lives: whatever sev refers to must
  /// live as long (capture it by value).
  /// \pre as for RealAlgebraic(r); sev's contract is trusted, not checked.
  RealAlgebraic(const IsolatedRoot& r, std::shared_ptr<const ScaledEvaluator> sev);
  /// The root of `squarefree` in (lo, hi).
  /// \pre squarefree is squarefree, lo < hi, neither end is a root and there
  ///      is exactly one root in (lo, hi) -- all checked exactly
  ///      (InvalidArgument otherwise).
  RealAlgebraic(const Poly& squarefree, const Rational& lo, const Rational& hi);

  /// True when the number is held exactly as a rational q (interval [q, q]);
  /// false for a root held by an isolating interval (irrational unless its
  /// polynomial, of degree >= 2, has a rational root there).
  bool is_rational() const { return lo_ == hi_; }
  /// The exact value; \pre is_rational().
  const Rational& rational() const;
  /// A squarefree polynomial with this number as a root (primitive,
  /// positive leading coefficient; degree 1 for rationals).
  const Poly& poly() const { return poly_; }
  /// Current isolating interval (lo == hi for rationals).
  const Rational& lo() const { return lo_; }
  const Rational& hi() const { return hi_; }

  /// Shrinks the interval until hi - lo <= 2^-bits (no-op for rationals).
  /// Copies share what any of them refined: refine() first adopts the
  /// narrowest interval a copy published, and publishes its own result, so
  /// an algebraic number is refined about once however many copies (worker
  /// threads) ask. Thread-safe across copies (the shared interval is
  /// locked); one object is not to be used from two threads at once.
  /// Value-neutral: lo() and hi() only ever narrow, and to_ball() does not
  /// depend on earlier refinements.
  void refine(long bits) const;
  /// Ball containing the number with radius <= 2^-prec * |x| (relative
  /// accuracy at every size: a number next to 0, such as the image of a
  /// breakpoint in a chart that zooms in on it, keeps its digits; exact for
  /// x = 0). Canonical: a function of (x, prec) alone, whatever was refined
  /// before (irrational x: the dyadic cell [k, k + 1] 2^-(prec+1+e) holding
  /// x, with e = max(0, -floor(log2 |x|)) and k decided exactly), so
  /// computations do not depend on evaluation order. Memoised for the last
  /// precision asked. Refines to prec + e + kToBallExtraBits bits first
  /// (callers refining beforehand, e.g. on worker threads, ask for
  /// prec + kToBallExtraBits; the shift e is found once per object).
  /// \throws BudgetExceeded when |x| < 2^-(2^20) (not bounded away from 0
  /// within the refinement limit).
  Ball to_ball(long prec) const;
  static constexpr long kToBallExtraBits = 11;
  /// Exact sign.
  int sign() const;
  /// Decimal with `digits` significant digits, e.g. "0.438691337650831",
  /// correctly rounded is not promised; the value is within one unit of the
  /// last digit.
  std::string decimal(long digits) const;
  /// A short isolating interval, for printing: the cell (k 10^-d, (k + 1) 10^-d)
  /// holding the number for the smallest d (possibly negative) for which that
  /// cell lies in the isolating interval the number was constructed with
  /// (so poly() has no other root in its closure, and its ends are no roots).
  /// A function of the number and that interval alone, never of earlier
  /// refinements. Costs a refinement to about 10^-d and at most one exact
  /// sign per d; no root isolation. Should d need more than 2^14 bits (the
  /// number within 10^-4900 of an end of that interval), the current
  /// interval is returned instead (still isolating). (q, q) for a rational q.
  std::pair<Rational, Rational> short_interval() const;
  /// "t^4*27 - 1 in (43/100, 11/25)"-style description:
  /// "root of 27*t^4 - 1 in [lo, hi]" or the rational "1/2".
  std::string str() const;

 private:
  friend int compare(const RealAlgebraic& x, const RealAlgebraic& y);
  // The constructors from an isolated root; sev (may be null) checks the
  // ends' signs first.
  void init(const IsolatedRoot& r, const ScaledEvaluator* sev);
  struct Shared;  // the narrowest interval known to the copies (irrational only)
  Poly poly_;
  mutable Rational lo_, hi_;
  std::shared_ptr<Shared> shared_;
  // The last enclosure handed out and its precision (integrands ask for the
  // same precision many thousand times per quadrature).
  mutable Ball ball_;
  mutable long ball_prec_ = -1;
  // max(0, -floor(log2 |x|)) for an irrational x, once found (-1: not yet).
  mutable long small_shift_ = -1;
  long small_shift() const;
};

/// Exact comparison: -1, 0, 1. Equality is decided exactly (gcd of the two
/// polynomials has a root in the intersection of the intervals).
int compare(const RealAlgebraic& x, const RealAlgebraic& y);
inline bool operator==(const RealAlgebraic& x, const RealAlgebraic& y) { return compare(x, y) == 0; }
inline bool operator!=(const RealAlgebraic& x, const RealAlgebraic& y) { return compare(x, y) != 0; }
inline bool operator<(const RealAlgebraic& x, const RealAlgebraic& y) { return compare(x, y) < 0; }

/// Exact sign of an integer polynomial at an algebraic number.
int sign_at(const Poly& p, const RealAlgebraic& x);

}  // namespace uniparam
