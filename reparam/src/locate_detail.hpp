// reparam/src/locate_detail.hpp -- INTERNAL to the locator (not installed):
// what locate.cpp (locate() and the shared checks), locate_chain.cpp (the
// chain of certified integrals), locate_cover.cpp (the Taylor-model cover
// of G), exact_samples.cpp and arc_fraction.cpp share.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/locate.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"
#include "arc_model.hpp"
#include "track.hpp"

namespace uniparam {
struct SpeedCharts;  // speed_charts.hpp
}  // namespace uniparam

namespace uniparam::locate_detail {

// G(x) - T is decided at rational points x only, from a bracket
//     lo <= t <= hi,  G(lo) in Glo,
// where G(x) = G(lo) + int_lo^x sigma (integrate_speed: split at the zeros
// of sigma inside, each part analytic). Moving lo forward adds the integral
// over [lo, x] to Glo: the parts are disjoint, so their radii add up to at
// most 2^-bits of the integral over what was covered.
struct Bracket {
  Rational lo, hi;
  Ball Glo;
};

// ---- locate.cpp: checks and messages shared by every entry point ----

/// \throws DomainError (the angular speed of a straight line: no parameter
///         is determined) when identically_zero.
void check_not_zero_speed(bool identically_zero);
/// \throws BudgetExceeded when opt.digits need more bits of working
///         precision than opt.max_prec.
void check_digits_fit(const Options& opt);
/// The value in messages: exact when short, else 12 significant digits.
std::string shown(const Rational& x);
/// \throws BudgetExceeded, always: `what` could not be certified to
///         opt.digits within opt.max_prec bits.
[[noreturn]] void throw_budget(const std::string& what, const Options& opt);
/// The next integral accuracy after `bits`: bits + max(32, bits / 2).
long next_bits(long bits);
/// The point at the exact parameter t (0 or 1): t exact, p(t) at 128 bits.
LocatedPoint exact_point(const Track& tr, long t);

/// b.meets_digits(digits), first by a cheap sufficient test (rad <=
/// 2^-e <= 10^-digits, so rad <= 10^-digits max(1, |mid|)); false for a
/// ball that is not finite. (locate_cover.cpp)
bool meets(const Ball& b, long digits);

// ---- locate_balanced.cpp: locating on a balanced curve ----

/// The point of the balanced curve q = p o m (scaling.hpp) located at s,
/// carried to p: t = m(s), and p(t) = q(s) as located, except at the ends
/// s = 0, 1 (t = s exactly), where p is evaluated as on the unbalanced path
/// (q's coefficients may be far larger than p's). Whether t meets `digits`
/// is the caller's check (m stretches s where m' > 1).
LocatedPoint mapped_point(const Curve& p, const BalancedCurve& bal, const LocatedPoint& on_q, long digits);
/// locate() on the balanced curve: G_q(s) = G_p(m(s)) (sigma_q ds =
/// sigma_p dt), so t = m(s) for q's s, located to more digits where m
/// stretches it. \pre sq is q's speed of the caller's kind.
/// \throws as locate(); BudgetExceeded when the digits s needs exceed
///         opt.max_prec.
LocateResult locate_balanced(const Curve& p, const BalancedCurve& bal, const Speed& sq, const Rational& value,
                             LocateTarget target, const Options& opt);

// ---- locate_charts.cpp: locating on a speed with charts ----

/// locate() where s has charts (speed_charts.hpp): on a track whose
/// parameter v takes each part's half at its feature in the part's chart
/// and the other half on t, so that G is smooth on the scale of v; t is
/// the exact increasing image of v, p(t) the chart's curve at u (or p at
/// t), and v is located to more digits where the map stretches it.
/// \pre ch is s's charts, s the speed of p. \throws as locate();
///         BudgetExceeded when the digits v needs exceed opt.max_prec.
LocateResult locate_charts(const Curve& p, const Speed& s, const SpeedCharts& ch, const Rational& value,
                           LocateTarget target, const Options& opt);
/// exact_samples_each() on that track, each point carried to t (located
/// again alone, to more digits, where t misses opt.digits).
void exact_samples_charts(const Curve& p, const Speed& s, const SpeedCharts& ch, long K, const Options& opt,
                          Ball& mu, const LocatedSink& sink);

// ---- locate_chain.cpp: the chain of certified integrals ----

/// Narrows b, a bracket of the unique t with G(t) = T, to a ball t meeting
/// opt.digits with p(t) meeting opt.digits too, deciding the signs of
/// G(x) - T by integrals at relative accuracy 2^-bits.
/// \pre b.Glo contains G(b.lo); T contains the target.
/// \post true: out.t contains t, out.point contains p(t), both meet
///       opt.digits. false: more bits are needed; b is still a bracket of
///       t with G(b.lo) in b.Glo.
/// \throws as Track::integral and check_time_budget().
bool finish_point(const Track& tr, Bracket& b, const Ball& T, long bits, const Options& opt,
                  LocatedPoint& out);

// ---- locate_cover.cpp: the Taylor-model cover of G ----

// G on [0, 1] as a chain of regions, each either a Taylor model (ArcCell,
// arc_model.hpp) of one segment's speed or, where no model certifies (an
// irrational zero of sigma, a singularity of sigma's continuation too close
// to the real axis), a gap integrated by the track. G at each region's
// start is the sum of the regions before it (disjoint: their radii add up
// to about 2^-bits of the sum, as the chain of integrals does).
class Cover {
 public:
  // Builds the regions at integral accuracy `bits`. False (the cover is
  // not to be used) when the track has no segments, no segment's speed is
  // worth modelling (ArcModeller::worthwhile) or no model certifies.
  bool build(const Track& tr, long bits);

  /// mu = G(1) as the sum of the regions. \pre build() returned true.
  const Ball& mu() const { return mu_; }

  // The point with G(t) = T, from the region holding T. True: pt is
  // certified and meets opt.digits, and br is a bracket for any larger
  // target (the region's start). False: br is a bracket lo <= t <= hi with
  // G(lo) in br.Glo for the track's own narrowing.
  // A cursor moves forward only: targets in increasing order are found
  // without searching the regions again.
  bool locate(const Track& tr, const Ball& T, const Options& opt, LocatedPoint& pt, Bracket& br);

  /// The integral accuracy the cover was built at (its brackets' G(lo)).
  long bits() const { return bits_; }

 private:
  struct Region {
    Rational lo, hi;      // in the track's parameter
    Ball G0;              // G(lo)
    bool model = false;   // cell holds a model; else a gap
    ArcCell cell;         // in the segment's parameter u
    Rational off, scale;  // t = off + scale u
  };

  // Cells over [A, B] of segment sg's parameter (no zero of sigma inside):
  // as long as possible (doubling after a success, halving after a
  // failure); where cells would have to become very short, or too many
  // (512), or too many attempts fail (more than 12 + twice the cells), the
  // rest is a gap.
  template <class AddGap>
  void stretch(const ArcModeller& mod, const Track::Segment& sg, const Rational& A, const Rational& B, Ball& G,
               AddGap& add_gap);

  std::vector<Region> regions_;
  Ball mu_;
  std::size_t cursor_ = 0;
  long bits_ = 0;
};

// ---- the tracks of one curve ----

// int sigma of one speed (no curve: eval is not available).
class SpeedTrack : public Track {
 public:
  SpeedTrack(const Speed& s, long max_prec) : s_(s), max_prec_(max_prec) {}
  bool identically_zero() const override { return s_.identically_zero(); }
  SpeedKind kind() const override { return s_.kind(); }
  Ball mu(long bits, const Options& opt) const override { return mean_speed(s_, bits, opt); }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    return integrate_speed(s_, RealAlgebraic(a), RealAlgebraic(b), bits, max_prec_);
  }
  double sigma_estimate(const Rational& x) const override { return uniparam::sigma_estimate(s_, x); }
  std::vector<Segment> segments() const override { return {Segment{Rational(0), Rational(1), &s_}}; }
  std::vector<Ball> eval(const Ball&, long) const override {
    throw std::logic_error("SpeedTrack::eval: no curve");
  }

 private:
  const Speed& s_;
  long max_prec_;
};

// int sigma and p of one curve.
class CurveTrack final : public SpeedTrack {
 public:
  CurveTrack(const Curve& c, const Speed& s, long max_prec) : SpeedTrack(s, max_prec), c_(c) {}
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }

 private:
  const Curve& c_;
};

}  // namespace uniparam::locate_detail
