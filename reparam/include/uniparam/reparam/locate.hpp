// uniparam/reparam/locate.hpp -- the exactly uniform parameterization,
// evaluated: the parameter t at which int_0^t sigma reaches a given value
// (arc length for the parametric speed, turning angle for the angular one),
// and K points at exactly equal steps of it (docs/locate.md).
#pragma once

#include <functional>
#include <memory>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/sample.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

class CompositeCurve;  // composite.hpp
class Track;           // internal: int sigma on a curve or a composite curve

/// What the value given to locate() measures: G(t) = int_0^t sigma itself
/// (an arc length for the parametric speed, a turning angle in radians for
/// the angular one), or the fraction G(t) / mu of mu = G(1).
enum class LocateTarget { Integral, Fraction };

/// One located point.
struct LocatedPoint {
  Ball t;                   ///< contains the unique t in [0, 1] with G(t) = target
  std::vector<Ball> point;  ///< contains p(t), one ball per component
};

struct LocateResult {
  LocatedPoint at;
  Ball mu;      ///< contains mu = int_0^1 sigma
  Ball target;  ///< contains G(t) (the value asked for, or fraction * mu)
};

/// The unique t in [0, 1] with int_0^t sigma = value (target Integral) or
/// = value * mu (target Fraction), for the speed `s` of the curve `c`.
/// Unique because sigma >= 0 vanishes only at isolated points (the zeros of
/// sigma); those need no special case: t is bracketed by certified signs of
/// G(x) - target at rational x, where G(x) is integrate_speed (split at the
/// zeros inside), and narrowed by safeguarded Newton steps (the derivative
/// sigma from an uncertified estimate: it only chooses the next points),
/// bisecting where Newton does not shrink the bracket (near a zero of sigma
/// Newton's derivative vanishes).
/// \pre `s` is the speed of `c` (not checkable).
/// \post at.t contains t and has rad <= 10^-digits; every at.point
///       component contains p(t) and meets opt.digits; mu and target
///       meet opt.digits. value 0 gives t = 0 exactly, fraction 1 gives
///       t = 1 exactly.
/// \throws DomainError when sigma is identically zero (the angular speed
///         of a straight line: no t is determined); InvalidArgument when
///         value < 0, a fraction > 1, or an integral certainly > mu (the
///         message gives mu); BudgetExceeded when an integral value cannot
///         be told apart from mu, or t cannot be certified to opt.digits,
///         within opt.max_prec bits; and as uniformity() (time budget).
LocateResult locate(const Curve& c, const Speed& s, const Rational& value, LocateTarget target,
                    const Options& opt = {});

/// K points at exactly equal steps of G: t_k with G(t_k) = k mu / (K - 1),
/// k = 0, ..., K - 1 (t_0 = 0 and t_{K-1} = 1 exactly).
struct ExactSamples {
  Ball mu;                          ///< contains mu
  std::vector<LocatedPoint> points;  ///< size K, t increasing
};

/// Receives the points of exact_samples_each one by one, in order of k.
using LocatedSink = std::function<void(long k, const LocatedPoint&)>;

/// The K points of ExactSamples, located one after the other and handed to
/// `sink` as soon as each is certified (nothing kept: memory does not grow
/// with K). First G is covered by certified Taylor models on cells of the
/// parameter (docs/locate.md, "Taylor models": sigma's Taylor polynomial
/// at each cell's centre with a Cauchy bound of the remainder, integrated),
/// which give mu and, by one interval Newton step in the cell holding the
/// target, most points without any certified integral. Where no model
/// certifies (an irrational zero of sigma, a singularity of sigma's
/// continuation too close, a speed of high degree) or a point misses its
/// model's accuracy, the point is narrowed by certified integrals from the
/// previous point's bracket (or the cover's, whichever is ahead), so K
/// points cost O(K) integrals over short pieces at most, never K integrals
/// from 0. Where a point needs more working precision than the chain has,
/// mu and G at the bracket are recomputed at the higher one (the points
/// already handed over stay valid). `mu` receives mu (to opt.digits)
/// before the first point.
/// \pre 2 <= K <= 1000000 (checked: InvalidArgument); `s` the speed of `c`.
/// \post each t and point component contains the true value and meets
///       opt.digits (as locate()); mu meets opt.digits.
/// \throws as locate(), after the points before the failing one were handed
///         over; an exception from the sink stops the loop and propagates.
void exact_samples_each(const Curve& c, const Speed& s, long K, const Options& opt, Ball& mu,
                        const LocatedSink& sink);

/// exact_samples_each, collected (memory grows with K).
ExactSamples exact_samples(const Curve& c, const Speed& s, long K, const Options& opt = {});

/// G(t) / mu, the fraction of the whole arc length (turning angle) reached
/// at t, for balls t visited in (roughly) increasing order: each call
/// integrates sigma only from the previous call's point, so K calls cost K
/// short integrals. Enclosed from the monotone G on the rational ends of t
/// (clipped to [0, 1]).
class ArcFraction {
 public:
  /// mu to relative accuracy 2^-bits (mean_speed) at construction.
  /// \throws DomainError for an identically zero speed (mu = 0);
  ///         BudgetExceeded as mean_speed.
  ArcFraction(const Speed& s, long bits, const Options& opt);
  /// The same for a composite curve (G over the global parameter).
  /// \pre speeds are c's; c and speeds outlive this object.
  ArcFraction(const CompositeCurve& c, const std::vector<Speed>& speeds, long bits, const Options& opt);
  const Ball& mu() const { return mu_; }
  /// A ball containing G(x) / mu for every x in t (the integrals at
  /// relative accuracy 2^-bits). \pre t finite (DomainError otherwise).
  Ball at(const Ball& t);

 private:
  Ball G(const Rational& x);  // G(x), from the last point visited
  std::shared_ptr<const Track> track_;
  long bits_, max_prec_;
  Ball mu_;
  Rational last_;
  Ball G_last_;
};

/// How far the points of a reparameterization r sit from the exact ones:
/// max over k of |G(r(s_k)) / mu - s_k| for s_k = k / (K - 1), k = 0, ..., K-1
/// (the largest deviation in fraction of mu: arc-length fraction for the
/// parametric speed, turning-angle fraction for the angular one), by
/// ArcFraction (O(K) short integrals).
/// \pre 2 <= K <= 1000000 (InvalidArgument); r computed for `s`.
/// \post the result contains the maximum deviation; its upper end is a
///       certified upper bound. Its width comes from r's own balls (r's
///       accuracy) and from the integrals' 2^-bits relative accuracy,
///       bits = digits_to_bits(opt.digits).
/// \throws DomainError for an identically zero speed; BudgetExceeded as
///         integrate_speed.
Ball fraction_deviation(const Speed& s, const Reparameterization& r, long K, const Options& opt = {});

}  // namespace uniparam
