// uniparam/reparam/composite.hpp -- composite curves (a path of segments, a
// spline split at its knots) and every method on them.
//
// A composite curve is p(t) = p_j((t - k_j) / (k_{j+1} - k_j)) for t in
// [k_j, k_{j+1}], with segments p_0, ..., p_{m-1}, each an exact rational
// Curve on its own parameter [0, 1], and exact knots 0 = k_0 < ... < k_m = 1.
// Every quantity is additive over the segments: with mu_j = int sigma_j and
// I_j = int sigma_j^2 in segment j's own parameter,
//     mu = sum mu_j,    int_0^1 sigma^2 = sum I_j / (k_{j+1} - k_j).
// A reparameterization is one map r_j per segment (the method run on the
// segment: the joints are breakpoints of every method) and new joints
// 0 = S_0 < ... < S_m = 1: s in [S_j, S_{j+1}] goes to segment j at
// s_j = (s - S_j) / (S_{j+1} - S_j). With E_j = mu_j^2 / u(p_j o r_j),
//     int_0^1 sigma_{p o r}^2 ds = sum E_j / (S_{j+1} - S_j),
// least for S_{j+1} - S_j proportional to sqrt(E_j); the S_j are exact
// rationals near that optimum, and u(p o r) is certified for the S_j used.
// (docs/inputs.md; docs/math.md section 7.)
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/locate.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/sample.hpp"
#include "uniparam/reparam/speed.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

/// Segments and knots of a composite curve, checked at construction.
class CompositeCurve {
 public:
  /// \pre at least one segment, all of the same dimension; knots.size() ==
  ///      segments.size() + 1, strictly increasing from exactly 0 to exactly
  ///      1; labels empty (then "segment j") or one per segment.
  /// \throws InvalidArgument naming what is wrong.
  CompositeCurve(std::vector<Curve> segments, std::vector<Rational> knots, std::vector<std::string> labels = {});
  /// One segment on [0, 1].
  explicit CompositeCurve(Curve c);

  /// The number of segments; segment j (std::out_of_range for j >= size());
  /// all segments; the knots (size() + 1, from 0 to 1); segment j's label
  /// (std::out_of_range as segment()); the dimension.
  std::size_t size() const { return segments_.size(); }
  const Curve& segment(std::size_t j) const { return segments_.at(j); }
  const std::vector<Curve>& segments() const { return segments_; }
  const std::vector<Rational>& knots() const { return knots_; }
  const std::string& label(std::size_t j) const { return labels_.at(j); }
  std::size_t dimension() const { return segments_.front().dimension(); }
  /// Largest degree among the segments.
  long degree() const;
  /// Enclosures of p's components at the ball t in [0, 1]: the segment's
  /// value at an exact t (the later segment at a knot), else the union over
  /// the segments t meets (t clipped to each).
  /// \throws InvalidArgument when t does not meet [0, 1].
  std::vector<Ball> eval(const Ball& t, long prec) const;
  /// The segment holding the exact parameter x in [0, 1] (the later one at
  /// an interior knot).
  std::size_t segment_of(const Rational& x) const;
  /// Every segment's speed of kind `kind` (Speed's constructor per segment;
  /// throws as it does, the message prefixed with the segment's label).
  std::vector<Speed> speeds(SpeedKind kind) const;

 private:
  std::vector<Curve> segments_;
  std::vector<Rational> knots_;
  std::vector<std::string> labels_;
};

/// Where segment index - 1 ends and segment index begins (1 <= index < m).
struct Joint {
  std::size_t index = 0;
  /// p_{index-1}(1) == p_index(0) exactly.
  bool continuous = false;
  /// Continuous with the same tangent direction on both sides (exactly).
  bool smooth = false;
  /// The turning angle between the incoming and the outgoing tangent
  /// direction, in radians, in [0, pi]: exactly 0 where smooth. The tangent
  /// direction at an end is that of the first nonvanishing derivative there
  /// (a segment whose p' vanishes at its end still has one).
  Ball angle;
};

/// The joints of c, one per interior knot.
/// \post angle contains the true angle, to about `prec` bits.
std::vector<Joint> joints(const CompositeCurve& c, long prec);

/// Certified uniformity of a composite curve (see the top of this file).
struct CompositeUniformity {
  SpeedKind kind;
  std::vector<UniformityResult> segments;  ///< each segment in its own parameter
  std::vector<Joint> joints;
  Ball mu;           ///< sum of the segments' mu (corners not included)
  Ball mean_square;  ///< int_0^1 sigma^2 in the global parameter
  Ball u;            ///< mu^2 / mean_square (1 exactly when every segment's speed is identically 0)
  bool identically_zero = false;
  /// Sum of the joints' angles (angular speed: the turning the corners add
  /// to mu, which no parameterization's angular speed carries).
  Ball corner_turning;
};

/// \post mu, mean_square and u contain the true values and meet opt.digits;
///       each segment's result meets opt.digits + 2.
/// \throws as uniformity(Curve, ...) for each segment, the message prefixed
///         with the segment's label.
CompositeUniformity uniformity(const CompositeCurve& c, SpeedKind kind, const Options& opt = {});

/// Which map each segment gets.
struct CompositeMethod {
  enum class Kind { None, Radical, Moebius, Pieces, Breakpoints, Target };
  Kind kind = Kind::None;
  long pieces = 0;                   ///< Pieces: over the whole curve, >= number of segments
  std::vector<Rational> breakpoints;  ///< Breakpoints: in the global t (0 and 1 included)
  Rational target;                   ///< Target: 0 < target < 1, for every segment
  long max_pieces = 64;              ///< Target: per segment
  bool rational = false;             ///< Moebius kinds: exact rational data (make_rational)
  long rational_digits = 8;
};

/// A reparameterization of a composite curve: one map per segment and the
/// joints S (see the top of this file).
class CompositeMap {
 public:
  /// "none", "radical", "C0 piecewise Moebius", "C1 piecewise Moebius".
  std::string method() const;
  const std::vector<Reparameterization>& parts() const { return parts_; }
  /// S_0 = 0 < ... < S_m = 1, exact.
  const std::vector<Rational>& S() const { return S_; }
  std::size_t pieces() const;
  const Ball& mu() const { return mu_; }
  const Ball& u_before() const { return u_before_; }
  const Ball& u_after() const { return u_after_; }
  /// The C1 target was used and is reached (certified) by every segment, so
  /// by the whole map (u >= target on every segment implies it overall).
  bool target_reached() const;

  /// Enclosure of r(s) in the global t for a ball s in [0, 1]: where s meets
  /// several segments' intervals [S_j, S_{j+1}], the union of their values.
  /// \pre c is the curve of this map. \throws InvalidArgument for s
  ///      outside [0, 1].
  Ball eval_r(const CompositeCurve& c, const Ball& s, long prec) const;
  /// Enclosure of the speed of p o r at s (the union over the segments s
  /// meets, as eval_r). \pre c and sp are the curve and speeds of this map.
  Ball eval_speed(const CompositeCurve& c, const std::vector<Speed>& sp, const Ball& s, long prec) const;
  /// Every piece's joints over the whole curve, in order, 0 and 1 included:
  /// (s_i, t_i) in the global parameters, as balls at `prec`.
  std::vector<std::pair<Ball, Ball>> joints(const CompositeCurve& c, long prec) const;

 private:
  friend CompositeMap composite_map(const CompositeCurve&, const std::vector<Speed>&, const CompositeMethod&,
                                    const Options&);
  std::vector<Reparameterization> parts_;
  std::vector<Rational> S_;
  Ball mu_, u_before_, u_after_;
};

/// Runs `m` on c (speeds = c.speeds(kind), one per segment): None, the
/// identity (S = the knots); Radical, radical() per segment; Moebius,
/// moebius_optimal per segment; Pieces, reparam_c0 with the pieces shared
/// among the segments greedily (each next piece to the segment where it
/// lowers sum sqrt(E_j) most); Breakpoints, moebius_c0 per segment at the
/// given breakpoints that fall inside it (the knots are added); Target,
/// reparam_c1 per segment with the same target.
/// \pre speeds are c's (checked by count only).
/// \post u_before, u_after and mu contain the true values and meet
///       opt.digits; every part's balls meet opt.digits + 2.
/// \throws InvalidArgument for pieces < c.size() or > 1000, breakpoints not
///         strictly increasing from 0 to 1, a bad target; DomainError when a
///         segment's angular speed is identically 0 (a straight segment)
///         but not every segment's is: no map can give it a share of s with
///         a positive speed (use the parametric speed); and as the method on
///         one curve, with the segment's label in the message.
CompositeMap composite_map(const CompositeCurve& c, const std::vector<Speed>& speeds, const CompositeMethod& m,
                           const Options& opt = {});

/// Certified samples of p o r for a composite map, one parameter at a time
/// (a Sampler per segment, created on first use).
class CompositeSampler {
 public:
  /// \pre c, speeds and r belong together; c and speeds outlive the sampler.
  /// \throws as Sampler's constructor.
  CompositeSampler(const CompositeCurve& c, const std::vector<Speed>& speeds, const CompositeMap& r, long digits,
                   long max_prec);
  /// The sample at s in [0, 1] (InvalidArgument otherwise): t in the global
  /// parameter, p(r(s)), the speed of p o r at s (at_joint and the union of
  /// both sides' speeds at an interior S_j, and at the segments' own joints).
  /// \post as Sampler::at.
  SamplePoint at(const Rational& s);
  /// The segment s lies in (the later one at an interior S_j).
  std::size_t segment_of(const Rational& s) const;

 private:
  const CompositeCurve& c_;
  const std::vector<Speed>& sp_;
  const CompositeMap& r_;
  long digits_, max_prec_;
  std::vector<std::unique_ptr<Sampler>> parts_;
  Sampler& part(std::size_t j);
};

/// locate() on a composite curve: the unique global t with
/// int_0^t sigma = value (or value * mu), sigma the composite's speed.
/// \pre speeds are c's.
/// \post as locate(); a t at a knot is exact when the value is certified to
///       be that knot's cumulative integral only by exactness (value 0,
///       fraction 1).
/// \throws as locate(); DomainError when every segment's speed is
///         identically zero, or some (straight segments, angular speed)
///         but not all: the integral is constant on them, and a value it
///         takes there determines no parameter.
LocateResult locate(const CompositeCurve& c, const std::vector<Speed>& speeds, const Rational& value,
                    LocateTarget target, const Options& opt = {});

/// exact_samples_each() on a composite curve: K points at equal steps of
/// the composite's int sigma, the chain running through the segments.
/// \pre 2 <= K <= 1000000 (InvalidArgument); speeds are c's.
/// \post as exact_samples_each(); t in the global parameter.
/// \throws as locate() on a composite curve.
void exact_samples_each(const CompositeCurve& c, const std::vector<Speed>& speeds, long K, const Options& opt,
                        Ball& mu, const LocatedSink& sink);

}  // namespace uniparam
