// uniparam/reparam/sample.hpp -- one interface to every reparameterization
// r : [0, 1] -> [0, 1] the engine computes (none, radical, C0 / C1 piecewise
// Moebius), and certified samples of p o r at equally spaced parameters (the
// points a CNC or animation pipeline consumes, and what the plots show).
#pragma once

#include <functional>
#include <string>
#include <variant>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/radical.hpp"

namespace uniparam {

/// A reparameterization r of [0, 1] as computed by one of the methods, seen
/// through one method-independent interface. The new parameter is called s
/// here whatever the method calls it (z for the radical method).
///
/// Joints: 0 = s_0 < s_1 < ... < s_N = 1 (balls) with r(s_i) = t_i (exact
/// real algebraic numbers). Between joints r is analytic; at an interior joint
/// it is continuous, and r' (so the speed of p o r) may jump.
class Reparameterization {
 public:
  /// r = id on [0, 1] (the original parameterization, one piece). `u` is u(p)
  /// (it is reported as both u_before and u_after).
  static Reparameterization identity(const Ball& mu, const Ball& u);
  explicit Reparameterization(RadicalResult r);
  explicit Reparameterization(MoebiusResult r);

  /// "none", "radical", "C0 piecewise Moebius" or "C1 piecewise Moebius".
  std::string method() const;
  bool is_identity() const;
  /// The result this view wraps (null when it wraps another kind).
  const RadicalResult* radical_result() const;
  const MoebiusResult* moebius_result() const;

  /// The number N of pieces (>= 1).
  std::size_t pieces() const { return t_.size() - 1; }
  /// Joints in s (balls, s_0 = 0 and s_N = 1 exactly) and their images t_i.
  const std::vector<Ball>& joints_s() const { return s_; }
  const std::vector<RealAlgebraic>& joints_t() const { return t_; }
  /// mu = int_0^1 sigma, u(p) and u(p o r) as certified by the method.
  const Ball& mu() const { return mu_; }
  const Ball& u_before() const { return u_before_; }
  const Ball& u_after() const { return u_after_; }

  /// Enclosure of r(s) for a ball s in [0, 1] (InvalidArgument otherwise);
  /// where s meets a joint's ball, the union of both pieces' values.
  Ball eval_r(const Ball& s, long prec) const;
  /// Enclosure of sigma_{p o r}(s) = sigma_p(r(s)) r'(s) (>= 0); `sp` must be
  /// the speed r was computed for. Where s meets an interior joint's ball, the
  /// union of both one-sided speeds.
  Ball eval_speed(const Speed& sp, const Ball& s, long prec) const;
  /// Enclosures of the components of p(r(s)); `c` must be the curve of r.
  /// Where r(s) is an exact rational (s an exact joint with a rational t_i,
  /// such as s = 0 and s = 1), p is evaluated exactly there.
  std::vector<Ball> eval_point(const Curve& c, const Ball& s, long prec) const;

  /// The same map r with its data recomputed more accurately: the joints s_i,
  /// the alphas and the radical pieces' constants each meet `digits` (the
  /// breakpoints t_i are exact algebraic numbers, refined on demand anyway).
  /// The map is the one the method defines for these t_i (the optimal one;
  /// for C1, the C1 optimum; for an exact rational map, its exact data), so
  /// every enclosure of the refined map is one of r; mu and the uniformities
  /// are kept. The identity (and r = id for an identically zero speed) is
  /// returned as is.
  /// \pre `sp` is the speed r was computed for (not checkable).
  /// \throws InvalidArgument for digits < 1; BudgetExceeded when the data
  ///         cannot meet `digits` within max_prec bits or the thread's
  ///         TimeBudget.
  Reparameterization refined(const Speed& sp, long digits, long max_prec) const;

 private:
  Reparameterization() = default;
  std::variant<std::monostate, RadicalResult, MoebiusResult> result_;
  std::vector<Ball> s_;
  std::vector<RealAlgebraic> t_;
  Ball mu_, u_before_, u_after_;
  void init_common();
};

/// One sample of p o r at the exact parameter s.
struct SamplePoint {
  Rational s;               ///< k / (K - 1), exact
  Ball t;                   ///< r(s)
  std::vector<Ball> point;  ///< p(r(s)), one ball per component
  Ball speed;               ///< sigma_{p o r}(s), see at_joint
  /// True when s lies in the ball of an interior joint s_i (1 <= i < N) of
  /// the map as refined for this sample (s equal to s_i, or s_i not
  /// separable from s within max_prec): which side of the joint s is on is
  /// then unknown. `speed` is the union of both one-sided speeds and exempt
  /// from the accuracy contract; t and point still meet it (r is continuous;
  /// at a joint where sigma vanishes with multiplicity k - 1, r is only
  /// Hoelder-1/k continuous, and r's data are refined until t meets it).
  bool at_joint = false;
};

/// Certified samples of one reparameterization, one parameter at a time:
/// r(s), p(r(s)) and the speed of p o r at s to `digits` digits. When the
/// working precision alone no longer improves a sample (r's data, balls of
/// fixed accuracy, limit it: an ill-conditioned but well-posed map), r's data
/// are refined (Reparameterization::refined, the digits doubled each time)
/// and the more accurate map is kept for the following samples. Memory does
/// not depend on how many samples are taken.
class Sampler {
 public:
  /// \pre `c` and `sp` are the curve and speed r was computed for, and
  ///      outlive the Sampler (they are held by reference).
  /// \throws InvalidArgument unless 1 <= digits <= 10000 and max_prec >= 64.
  Sampler(const Curve& c, const Speed& sp, Reparameterization r, long digits, long max_prec);

  /// The sample at s in [0, 1] (InvalidArgument otherwise).
  /// \post t, every point component and (unless at_joint) speed contain the
  ///       true values and meet `digits` (rad <= 10^-digits max(1, |mid|));
  ///       t is exact where r(s) is an exact rational (s = 0: t = 0, s = 1:
  ///       t = 1), and then so is every component of p(t) that is a dyadic
  ///       number.
  /// \throws BudgetExceeded when the working precision or r's data would
  ///         need more than max_prec bits, or the thread's TimeBudget ends.
  SamplePoint at(const Rational& s);

  /// The map as currently refined (the one given until a sample needed more).
  const Reparameterization& map() const { return r_; }
  /// How many times r's data have been refined so far.
  long refinements() const { return refinements_; }

 private:
  const Curve& c_;
  const Speed& sp_;
  Reparameterization r_;
  long digits_, max_prec_;
  long data_digits_ = 0;  // digits of the last refinement (0: r as given)
  long refinements_ = 0;
};

/// Receives the samples of sample_each one by one, in order of k.
using SampleSink = std::function<void(long k, const SamplePoint&)>;

/// Certified samples of p o r at the K equally spaced s = k / (K - 1),
/// k = 0, ..., K - 1 (first 0, last 1), handed to `sink` one at a time as
/// soon as each is certified (a Sampler; nothing is kept between calls, so
/// memory does not grow with K). An exception from the sink stops the loop
/// and propagates.
/// \pre 2 <= K <= 1000000 (checked: InvalidArgument), as Sampler.
/// \post each sample as Sampler::at.
/// \throws as Sampler::at, after the samples before the failing one were
///         handed over.
void sample_each(const Curve& c, const Speed& sp, const Reparameterization& r, long K, long digits, long max_prec,
                 const SampleSink& sink);

/// K samples of the original curve and of the reparameterized one.
struct Samples {
  std::vector<SamplePoint> before;  ///< p at t = k / (K - 1) (r = id)
  std::vector<SamplePoint> after;   ///< p o r at s = k / (K - 1)
};

/// Certified samples at K equally spaced parameters, k = 0, ..., K - 1: the
/// original curve p at t = k/(K-1) and p o r at s = k/(K-1) (first s = 0,
/// last s = 1), both by sample_each, collected (memory grows with K; for
/// many points, use sample_each).
/// \pre 2 <= K <= 1000000 (checked: InvalidArgument); `r` was computed for
///      `c` and `sp` (not checkable; the balls would be meaningless otherwise).
/// \post as Sampler::at for every sample; meets_digits(result, digits).
/// \throws as sample_each.
Samples sample(const Curve& c, const Speed& sp, const Reparameterization& r, long K, long digits,
               long max_prec);

/// True when every t, point component and (off the joints) speed of the
/// samples meets `digits`.
bool meets_digits(const Samples& s, long digits);

/// The midpoint of b rounded to the nearest double. Not an enclosure: for
/// drawing only (uncertified).
double mid_double(const Ball& b);

}  // namespace uniparam
