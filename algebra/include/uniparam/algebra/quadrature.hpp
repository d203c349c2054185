// uniparam/algebra/quadrature.hpp -- certified integration of analytic
// functions (adaptive bisection around a Gauss-Legendre step with Arb's
// ellipse error bound and rigorous nodes) with a precision budget.
#pragma once

#include <acb.h>

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/dd_ball.hpp"

namespace uniparam {

/// An integrand f on a complex neighbourhood of the segment [a, b].
/// Must write to `out` an enclosure of f(z) for every z in the ball `z`, at
/// working precision `prec`. When `analytic` is true, it must also certify
/// that f is holomorphic on the ball z and set `out` to indeterminate
/// (acb_indeterminate) when it cannot (branch cut, pole, non-analytic
/// point): this is acb_calc_integrate's order == 1 contract.
using Integrand = std::function<void(acb_t out, const acb_t z, bool analytic, long prec)>;

/// An optional fast path for the narrow real points, in double-word balls
/// (core/dd_ball.hpp): f(out, t, prec) for a real ball t of radius below
/// 2^-30 either writes to out[0 .. count) balls that contain f_k(t') for
/// every t' in t, each with a relative radius of at most
/// 2^-(prec - kNodeFastSlackBits), and returns true, or returns false (out
/// unspecified) and the point goes to the Integrand. At the first attempt's
/// precision, rel_goal_bits + 32, that is 2^-(rel_goal_bits + 4): for an
/// f_k of one sign the nodes' radii add at most 1/16 of the goal to the
/// integral's radius. (Only the radii depend on it: every answer is a
/// rigorous ball whatever its width.) Asked only at prec <= kNodeFastMaxPrec, first at every
/// narrow real point the quadrature evaluates: the Gauss-Legendre nodes
/// (radius about 2^-100 of the node; the weighted sum of the ones it
/// answers is formed in double words too, a rigorous ball with no Arb ball
/// per node), the start-precision probe's points (an answered point counts
/// as no loss to cancellation) and the ends' enclosures. So the Integrand
/// gets only the points it refused and the wide balls (segments,
/// ellipses), and need not try double words itself.
using NodeIntegrand = std::function<bool(DDBall* out, const DDBall& t, long prec)>;
/// NodeIntegrand's accuracy: relative radii up to 2^-(prec - kNodeFastSlackBits).
constexpr long kNodeFastSlackBits = 28;
/// The largest working precision at which NodeIntegrand is asked (double
/// words carry about 100 bits).
constexpr long kNodeFastMaxPrec = 110;

/// Evaluations allowed per bisection level that QuadratureOptions::scale_bits
/// adds (a Gauss-Legendre step and its error bounds on each level's pieces).
constexpr long kEvalsPerScaleBit = 400;

struct QuadratureOptions {
  /// Goal: the result's radius <= 2^-rel_goal_bits * |value|, or, when
  /// abs_goal_bits > 0, radius <= 2^-abs_goal_bits (whichever is met first).
  /// Use abs_goal_bits when the integral may be 0.
  long rel_goal_bits = 64;
  long abs_goal_bits = 0;
  /// First working precision; doubled after every miss up to max_prec (the
  /// last attempt is made at max_prec exactly; a larger initial precision is
  /// lowered to max_prec).
  long initial_prec = 0;    ///< 0: rel_goal_bits + 32
  long max_prec = 8192;
  /// Limits of the adaptive subdivision (with acb_calc_integrate's meaning):
  /// eval_limit 0 means Arb's default 1000 prec + prec^2 evaluations per
  /// attempt, capped at 2,000,000; depth_limit 0 means Arb's default
  /// 2 * prec bisections deep. Reaching either ends the attempt with the
  /// remaining subintervals' direct enclosures (rigorous, maybe wide).
  long eval_limit = 0;
  long depth_limit = 0;
  /// Bisections the integrand's scale may need beyond the defaults: where
  /// f varies on a scale of 2^-scale_bits (a peak of that width next to an
  /// end of [a, b], the complex singularities that close to it), the
  /// subdivision must go about scale_bits bisections deep, whatever the
  /// precision. Adds scale_bits to the default depth limit (2 prec +
  /// scale_bits) and kEvalsPerScaleBit * scale_bits to the default eval
  /// limit (both only where those are 0), so the work grows linearly in
  /// scale_bits instead of through the precision. 0: Arb's defaults.
  long scale_bits = 0;
  /// Used in the BudgetExceeded message: what was being integrated.
  std::string what = "integral";
  /// UNCERTIFIED approximations (e.g. approximate_complex_roots) of the
  /// complex points near [a, b] where the integrand is not analytic or its
  /// enclosures blow up (poles, branch points). They only steer the choice
  /// of error bounds: a Bernstein ellipse whose bounding box (enlarged by a
  /// margin) holds a hint is not evaluated, as its bound would not be
  /// finite, and a subinterval whose smallest ellipse holds one is bisected
  /// without evaluating f (down to a depth of 12 bisections; deeper, every
  /// ellipse is tried as without hints). Wrong or missing hints cost time,
  /// never correctness: every accepted bound is still Arb's.
  std::vector<std::complex<double>> singularity_hints;
  /// Optional (empty: every node goes to the Integrand); see NodeIntegrand.
  NodeIntegrand node_fast;
};

/// Certified integral of f over [a, b] (a <= b, algebraic ends, refined as
/// needed). The ends are handled rigorously: the integral over the exact
/// dyadic midpoints of the end enclosures is computed, and the radius of each
/// end enclosure times a bound of |f| on it is added. That bound comes from
/// node_fast where it answers, else from f on the real ball of radius 2^-12
/// around the end (a superset: wide balls are cheap to bound, a narrow one
/// may need accurate local expansions built for this one point), else, where
/// that is not finite, from f on the end's enclosure.
/// f must be real on [a, b]; a == b gives exactly 0 without calling f.
/// \post the true integral lies in the returned ball, which meets the goal.
/// \throws BudgetExceeded when the goal is not met at max_prec ("could not
///         certify <what> to N bits within M bits of working precision;
///         raise --max-prec"), InvalidArgument when a > b, f is empty or an
///         option is out of range (negative goal, initial_prec or scale_bits,
///         max_prec < 2), DomainError when the enclosure proves the integral
///         is not real. An exception thrown by f propagates unchanged.
Ball integrate(const Integrand& f, const RealAlgebraic& a, const RealAlgebraic& b,
               const QuadratureOptions& opt = {});

/// Certified integrals of count functions f_0, ..., f_{count-1} over [a, b]
/// at once, sharing one subdivision and one call of f per point: f(out, z,
/// analytic, prec) must write enclosures of f_k(z) to out[k] for every
/// k < count (with the Integrand contract above for each: holomorphy
/// certified on z when `analytic`, out[k] indeterminate where it cannot be).
/// Each subinterval's Gauss-Legendre degree is the largest any f_k needs for
/// its own tolerance (so the integrals cost the evaluations of the hardest
/// one, and one call gives all values: cheaper than count calls of
/// integrate when the f_k share most of their work, e.g. sigma and sigma^2,
/// or sigma^2 times three weights).
/// \post result[k] contains the integral of f_k and meets opt's goal, for
///       every k (the goal is retried at higher precision until all do).
/// \throws as integrate; also InvalidArgument when count == 0. On a == b
///         every result is exactly 0 and f is not called.
std::vector<Ball> integrate_many(const Integrand& f, std::size_t count, const RealAlgebraic& a,
                                 const RealAlgebraic& b, const QuadratureOptions& opt = {});

}  // namespace uniparam
