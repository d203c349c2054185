// reparam/src/speed_charts.hpp -- INTERNAL: the exact charts of the parts of
// [0, 1] a speed with narrow interior features is integrated over
// (Speed::charts, peak_split in scaling.hpp), and the spans of an interval
// in them.
#pragma once

#include <acb.h>

#include <cstddef>
#include <memory>
#include <optional>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

/// One part [min(k0, k1), max(k0, k1)] of [0, 1] and its chart
/// t = phi(u) = k0 + (k1 - k0) m(u), u in [0, 1], with m the balancing map
/// of scaling.hpp (m(u) = a u / (a u + b (1 - u))) or the identity:
/// phi(0) = k0 is the end with the part's feature, where the power basis of
/// p o phi is accurate. For either speed, sigma_phi(u) = sigma(phi(u))
/// |phi'(u)|, so
///     int sigma dt   = int sigma_phi du,
///     int sigma^2 dt = int sigma_phi(u)^2 / |phi'(u)| du,
///     1 / |phi'(u)| = (a u + b (1 - u))^2 / (a b |k1 - k0|)
/// over corresponding intervals, exactly.
struct SpeedChart {
  Rational k0, k1;
  std::optional<BalancedCurve> bal;  ///< m; the identity where empty
  Curve curve;                       ///< p o phi, exactly
  Speed speed;                       ///< sigma_phi: its speed (no charts of its own)
  /// w0 = 1 / (a b |k1 - k0|) (below), exactly: made once by build, so the
  /// integrands that ask for w0 at every point only round it.
  Rational w0_exact;

  /// |k1 - k0|.
  Rational length() const;
  /// phi^-1(t) exactly. \pre t lies between k0 and k1.
  RealAlgebraic local(const RealAlgebraic& t) const;
  /// phi(u) exactly, for u in [0, 1].
  Rational at(const Rational& u) const;
  /// An enclosure of phi(u) for the exact real u in [0, 1]: m(u) as a
  /// quotient of sums of non-negative terms (relative accuracy about
  /// 2^-prec, however close m(u) is to 0 or 1).
  Ball at(const arf_t u, long prec) const;
  /// For the complex ball z, with m(z) = a z / d(z) (a = b = 1 for the
  /// identity): d(z) = a z + b (1 - z), and 1 / |phi'(z)| = d(z)^2 w0
  /// with w0 = 1 / (a b |k1 - k0|) (an exact rational, here a ball).
  void denominator(acb_t d, const acb_t z, long prec) const;
  /// w0_exact at prec. \pre the chart was made by SpeedCharts::build.
  Ball w0(long prec) const { return Ball(w0_exact, prec); }
  /// d(z) (phi(z) - x) = (k1 - x) a z + (k0 - x) b (1 - z) for the real ball
  /// x: polynomial in z (no pole near the part, unlike phi), and a sum of
  /// two terms of one sign for x outside the part; for x inside, its error
  /// is at most about 2^-prec d(z) on [0, 1], as that of phi(z) - x would
  /// be, times d(z).
  void offset(acb_t out, const acb_t z, const arb_t x, long prec) const;
  /// The same for an exact x: k1 - x and k0 - x are formed exactly, so
  /// x = k0 (a point of the neighbouring part given as k0 + delta) leaves
  /// no rounding of x in the result.
  void offset(acb_t out, const acb_t z, const Rational& x, long prec) const;
  /// d(z) (phi(z) - phi(v)) = (k1 - k0) a b (z - v) / d(v) for the real
  /// ball v in [0, 1] (a point given by its chart coordinate): m's
  /// difference quotient, so next to v the result keeps the relative
  /// accuracy of z - v (that of v's ball: a breakpoint's image next to the
  /// feature at u = 0, enclosed relatively), where offset(z, phi(v)) would
  /// lose phi(v)'s absolute rounding to cancellation.
  void offset_local(acb_t out, const acb_t z, const arb_t v, long prec) const;
  /// |phi(v1) - phi(v0)| = |k1 - k0| a b (v1 - v0) / (d(v0) d(v1)) for the
  /// real balls 0 <= v0 <= v1 <= 1: the length in t of the span between
  /// two chart points, with the relative accuracy of v1 - v0.
  Ball length_between(const arb_t v0, const arb_t v1, long prec) const;
};

struct SpeedCharts {
  /// The parts in the order of t, covering [0, 1].
  std::vector<SpeedChart> charts;

  /// A piece of [a, b] inside one part, in that part's coordinate (phi
  /// maps [u0, u1], u0 < u1, onto it), or, where plain, on p's own
  /// parameter: [u0, u1] is the piece itself.
  struct Span {
    std::size_t chart;
    RealAlgebraic u0, u1;
    bool plain = false;
  };
  /// [a, b] cut at the parts' ends strictly inside, in order of t. A piece
  /// farther from its part's feature end k0 than a quarter of its length is
  /// plain: there sigma varies on the scale of that distance, which p's own
  /// parameter resolves (a balanced chart would squeeze it next to u = 1,
  /// within 2^-k for a map of ratio 2^k, where no working precision below k
  /// bits tells its ends apart). The choice only affects the cost, never a
  /// result.
  /// \pre 0 <= a < b <= 1.
  std::vector<Span> spans(const RealAlgebraic& a, const RealAlgebraic& b) const;

  /// The affine charts (bal empty) of the speed s of the curve c from
  /// peak_split(s); null where that is empty. The charts' speeds are marked
  /// to have no charts.
  static std::shared_ptr<const SpeedCharts> build(const Speed& s, const Curve& c);
  /// The parts of `affine` (made by build), each balanced where balance()
  /// balances its restriction; a part whose feature has roots on several
  /// scales (Newton polygons of g, D and the K_k about it, more than 2^32
  /// apart) is first cut into a ladder of rungs zooming by 2^16 each, down
  /// to the deepest scale, so that every scale is spread by some rung's
  /// chart. kind is the speed's.
  static std::shared_ptr<const SpeedCharts> balanced(const SpeedCharts& affine, SpeedKind kind);
};

}  // namespace uniparam
