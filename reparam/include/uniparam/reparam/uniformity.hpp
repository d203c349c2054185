// uniparam/reparam/uniformity.hpp -- certified mean speed and uniformity
// (docs/math.md section 1): mu = int_0^1 sigma, u = mu^2 / int_0^1 sigma^2.
#pragma once

#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

/// The most correct decimal digits a caller may ask for (--digits, the
/// public API's and Python's Options::digits). The quadrature's
/// Gauss-Legendre rules have at most 1024 nodes (their nodes cost seconds
/// each above that degree at these precisions), so past about 2000 digits
/// it must subdivide until each subinterval is 2^(prec/2048) times smaller
/// than its distance to the speed's nearest singularity: the cost grows
/// exponentially with the digits ((t, t^3): 2.4 s at 2000 digits, 118 s at
/// 4000).
constexpr long kMaxDigits = 2000;
/// The engine's own bound on Options::digits (validate()): kMaxDigits and
/// the guard digits the engine adds to a caller's (a composite curve's
/// segments, a rational Bezier curve's new weights).
constexpr long kMaxEngineDigits = kMaxDigits + 100;

/// Accuracy and budgets shared by every certified computation.
struct Options {
  /// Correct decimal digits wanted: every reported ball has
  /// rad <= 10^-digits * max(1, |mid|). 1 <= digits <= kMaxDigits from a
  /// caller (the engine accepts up to kMaxEngineDigits, for its own guard
  /// digits).
  long digits = 15;
  /// Largest working precision (bits) the quadrature may use before giving up
  /// with BudgetExceeded (CLI: --max-prec; its default there is
  /// default_max_prec(digits)).
  long max_prec = 16384;
  /// Largest curve degree accepted (CLI: --max-degree). Degree 1000 keeps
  /// uniformity and radical within seconds on dense curves such as
  /// (t, (1 + t)^1000); higher degrees are accepted when asked for.
  long max_degree = 1000;
};

/// Throws InvalidArgument when an option is out of range (digits outside
/// [1, kMaxEngineDigits], max_prec outside [64, 2^24], max_degree < 1).
void validate(const Options& o);

/// Bits of the scale on which sigma may vary next to an end of [0, 1]:
/// Speed::scale_bits, a certified bound from the Newton polygons of the
/// factored form's g, D and sum K_k^2 at 0 and at 1 (no zero, pole or
/// branch point of sigma comes within 2^-scale_bits of an end, other than
/// at the end itself). (t, C t^2) has D = 1 + 4 C^2 t^2 and a peak of width
/// 1 / (2 C) at t = 0: about log2 C + 3 bits. A quadrature of sigma,
/// sigma^2 or their weighted forms may need that many bisections
/// (QuadratureOptions::scale_bits).
/// \post >= 0; depends on s's polynomials only.
long speed_scale_bits(const Speed& s);

/// The largest coefficient size, in bits, of the factored form's
/// polynomials g, K_k and D: where it is small, sigma and its integrals are
/// within a few powers of 2^bits of 1 and need no exact scaling (the
/// integrals of (C t, t^3) with a 5000-digit C are about 2^-33000).
/// \post >= 0; depends on s's polynomials only.
long speed_coefficient_bits(const Speed& s);

/// Certified integral of sigma over [a, b], split at the zeros of sigma
/// inside, so that every piece's integrand is analytic. \pre 0 <= a <= b <= 1.
Ball integrate_speed(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b, long rel_goal_bits,
                     long max_prec);
/// Certified integral of sigma^2 over [a, b].
Ball integrate_speed_squared(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b,
                             long rel_goal_bits, long max_prec);

struct UniformityResult {
  SpeedKind kind;
  RatFunc speed_squared;          ///< sigma^2, exact
  std::vector<SpeedZero> zeros;   ///< zeros of sigma in [0, 1]
  bool identically_zero = false;  ///< angular speed of a line: mu = 0, u = 1 exactly
  Ball mu;                        ///< int_0^1 sigma
  Ball mean_square;               ///< int_0^1 sigma^2
  Ball u;                         ///< mu^2 / int sigma^2 (1 exactly when identically_zero)
};

/// Certified uniformity of the curve for the chosen speed.
/// \post mu, mean_square and u contain the true values and each meets
///       Options::digits.
/// \throws BudgetExceeded if that accuracy cannot be reached within
///         Options::max_prec, a curve above Options::max_degree, or the
///         thread's TimeBudget expiring (budget.hpp); InvalidArgument for bad
///         options; DomainError for a non-regular curve.
UniformityResult uniformity(const Curve& c, SpeedKind kind, const Options& opt = {});
/// The same for an already built speed (the curve's degree is not checked).
UniformityResult uniformity(const Speed& s, const Options& opt = {});
struct BalancedCurve;
/// uniformity(c, kind, opt) for a curve c with balance(c) = bal
/// (scaling.hpp), from the already built speeds s = Speed(c, kind) and
/// q_speed = Speed(bal.q, kind): sigma^2 and the zeros are s's, the
/// integrals q's (mu, and sigma^2 with the weight 1 / m'). Same contract as
/// uniformity(c, kind, opt); the pairing of s, bal and q_speed is not checked.
UniformityResult uniformity_balanced(const Speed& s, const BalancedCurve& bal, const Speed& q_speed,
                                     const Options& opt = {});
/// mu = int_0^1 sigma alone, split and threaded as in uniformity(), each
/// part to relative accuracy 2^-rel_goal_bits (so mu too: sigma >= 0). For
/// callers that get int sigma^2 elsewhere (radical(): from its pieces'
/// integrals L_i), at half the uniformity's cost or less.
/// \post contains mu; 0 exactly for an identically zero speed.
/// \throws as uniformity(Speed, opt) (BudgetExceeded, InvalidArgument).
Ball mean_speed(const Speed& s, long rel_goal_bits, const Options& opt = {});
/// Throws BudgetExceeded (naming --max-degree) when the curve's degree exceeds
/// Options::max_degree.
void check_degree(const Curve& c, const Options& opt);

/// Bits of relative accuracy that give `digits` decimal digits with margin.
long digits_to_bits(long digits);
/// The precision limit for `digits` when none is chosen: 16384 bits, or
/// twice digits_to_bits(digits) where that is more (from 2464 digits, so
/// never for digits <= kMaxEngineDigits: every digits a caller may ask for
/// is accepted with the default limit, with room to double the precision).
/// \pre digits >= 1.
long default_max_prec(long digits);

namespace detail {
/// The split of uniformity()'s integrals into tasks: the sorted union of
/// `ends` and the rationals j / parts (0 < j < parts) strictly inside
/// (ends.front(), ends.back()), none repeated.
/// \pre ends sorted strictly increasing, at least two of them; parts >= 1.
std::vector<RealAlgebraic> with_split_points(std::vector<RealAlgebraic> ends, long parts);
}  // namespace detail

}  // namespace uniparam
