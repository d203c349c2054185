// uniparam/reparam/sample.hpp -- one interface to every reparameterization
// r : [0, 1] -> [0, 1] the engine computes (none, radical, C0 / C1 piecewise
// Moebius), and certified samples of p o r at equally spaced parameters (the
// points a CNC or animation pipeline consumes, and what the plots show).
#pragma once

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
  std::vector<Ball> eval_point(const Curve& c, const Ball& s, long prec) const;

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
  /// True when s lies in the ball of an interior joint s_i (1 <= i < N): which
  /// side of the joint s is on is then unknown. `speed` is the union of both
  /// one-sided speeds and exempt from the accuracy contract. t and point are
  /// still enclosures and usually meet it (r is continuous), but at a joint
  /// where sigma vanishes with multiplicity k - 1, r is only Hoelder-1/k
  /// continuous: a joint ball of radius rho gives t a width of about
  /// rho^(1/k). Computing r with k times the digits cures that (see
  /// meets_digits(Samples)).
  bool at_joint = false;
};

/// K samples of the original curve and of the reparameterized one.
struct Samples {
  std::vector<SamplePoint> before;  ///< p at t = k / (K - 1) (r = id)
  std::vector<SamplePoint> after;   ///< p o r at s = k / (K - 1)
};

/// Certified samples at K equally spaced parameters, k = 0, ..., K - 1: the
/// original curve p at t = k/(K-1) and p o r at s = k/(K-1) (first s = 0,
/// last s = 1).
/// \pre 2 <= K <= 1000000 (checked: InvalidArgument); `r` was computed for
///      `c` and `sp` (not checkable; the balls would be meaningless otherwise).
/// \post every t, point component and speed contains the true value and
///       meets `digits` (rad <= 10^-digits max(1, |mid|)), except for a
///       sample with at_joint (see SamplePoint): there the balls are
///       enclosures only, and meets_digits(Samples) tells whether they also
///       meet `digits`.
/// \throws BudgetExceeded when a sample off the joints cannot meet `digits`
///         within max_prec bits: r's data (joints, alpha) are balls of fixed
///         accuracy, so r must have been computed with more digits than asked
///         here (3 more suffice off the joints).
Samples sample(const Curve& c, const Speed& sp, const Reparameterization& r, long K, long digits,
               long max_prec);

/// True when every t, point component and (off the joints) speed of the
/// samples meets `digits`.
bool meets_digits(const Samples& s, long digits);

/// The midpoint of b rounded to the nearest double. Not an enclosure: for
/// drawing only (uncertified).
double mid_double(const Ball& b);

}  // namespace uniparam
