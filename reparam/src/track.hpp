// reparam/src/track.hpp -- INTERNAL: what the locator (locate*.cpp) needs of
// a curve, so that one curve and a composite curve share it.
#pragma once

#include <memory>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/locate.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

/// G(x) = int_0^x sigma on the curve's parameter [0, 1], through the
/// operations the locator uses.
class Track {
 public:
  virtual ~Track() = default;
  /// sigma == 0 on the whole curve (no parameter is determined).
  virtual bool identically_zero() const = 0;
  virtual SpeedKind kind() const = 0;
  /// mu = G(1) to relative accuracy 2^-bits (as mean_speed).
  virtual Ball mu(long bits, const Options& opt) const = 0;
  /// int_a^b sigma for rationals 0 <= a <= b <= 1, to relative accuracy
  /// 2^-bits (as integrate_speed).
  virtual Ball integral(const Rational& a, const Rational& b, long bits) const = 0;
  /// An uncertified estimate of sigma(x) (0 where unknown): it only chooses
  /// the next probe.
  virtual double sigma_estimate(const Rational& x) const = 0;
  /// Enclosures of p's components at the ball t in [0, 1].
  virtual std::vector<Ball> eval(const Ball& t, long prec) const = 0;

  /// A part [lo, hi] of the track's parameter on which G is the integral
  /// of one speed: G(lo + (hi - lo) u) = G(lo) + int_0^u sigma_speed for u
  /// in [0, 1].
  struct Segment {
    Rational lo, hi;
    const Speed* speed;
  };
  /// The segments, in order, covering [0, 1] (their speeds outlive the
  /// track); empty when G is known through integral() only. The locator
  /// builds Taylor models of G from them (arc_model.hpp); integral() must
  /// agree with them.
  virtual std::vector<Segment> segments() const { return {}; }
};

/// An uncertified estimate of sigma(x): the square root of sigma(x)^2's
/// midpoint at 64 bits; 0 where that is not a positive finite double.
double sigma_estimate(const Speed& s, const Rational& x);

/// The track of a composite curve (composite_locate.cpp). \pre c and speeds outlive it.
std::shared_ptr<const Track> composite_track(const CompositeCurve& c, const std::vector<Speed>& speeds, long max_prec);

/// locate() and exact_samples_each() on a track (same contracts).
/// \pre opt validated.
LocateResult locate_on(const Track& tr, const Rational& value, LocateTarget target, const Options& opt);
void exact_samples_on(const Track& tr, long K, const Options& opt, Ball& mu, const LocatedSink& sink);

}  // namespace uniparam
