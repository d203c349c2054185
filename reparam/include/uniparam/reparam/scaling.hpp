// uniparam/reparam/scaling.hpp -- an exact change of parameter that balances
// a rational curve whose speed is concentrated next to one end of [0, 1]
// (weights growing geometrically, or huge coefficients such as (t, C t^2)),
// for the integrals of the uniformity and every method (docs/math.md §1,
// (1.1) and (1.2)).
#pragma once

#include <optional>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"

namespace uniparam {

class Speed;  // speed.hpp

/// The Moebius map of [0, 1] onto itself t = m(s) = a s / (a s + b (1 - s))
/// (a, b > 0 integers; m(0) = 0, m(1) = 1, increasing) and the curve
/// q = p o m. With lambda = b / a, a rational Bezier curve p with weights
/// w_i becomes q with weights proportional to w_i lambda^-i.
/// Since sigma_q(s) = sigma_p(m(s)) m'(s) for either speed:
///     int_0^1 sigma_p dt   = int_0^1 sigma_q ds                     (mu)
///     int_0^1 sigma_p^2 dt = int_0^1 sigma_q(s)^2 / m'(s) ds,
///     1 / m'(s) = (a s + b (1 - s))^2 / (a b),
/// so u(p) is computed exactly from q's speed and that polynomial weight.
struct BalancedCurve {
  Curve q;
  Integer a, b;
};

/// Where the common denominator W of p's components (degree n >= 1) has
/// |W(1) / W(0)| = lambda^n with |log2 lambda| >= 16 (weights growing or
/// falling by at least 2^16 per degree: p's speed is then concentrated on a
/// part of [0, 1] of width about 1 / lambda next to one end), the balanced
/// curve q = p o m with lambda the power of 2 nearest (|W(1)/W(0)|)^(1/n),
/// for which q's W has W(1) / W(0) within a factor 2^n of 1; empty
/// otherwise (including polynomial curves). Exact: q's components are
/// p's composed with m in Q(s).
/// \throws nothing beyond allocation (q is a curve: m is a bijection of
///         [0, 1], so q has p's poles, none in [0, 1]).
std::optional<BalancedCurve> balance(const Curve& p);

/// balance(p) where that balances; otherwise, where the speed s of p has its
/// mass concentrated within 2^-16 of one end of [0, 1] and not of the other
/// (e.g. the angular speed of (t, C t^2) for a huge C, a peak of width
/// 1/(2C) at t = 0), the balanced curve q = p o m with lambda = b / a = 2^k
/// (k > 0 for the end t = 0, k < 0 for t = 1) putting that mass near
/// s = 1/2. The mass's place is a tropical estimate from the sizes of the
/// coefficients of s's factored form g, K_k, D (speed.hpp) about the end,
/// exact input and no evaluation: sigma(2^-x) ~ 2^(T_g(x) + max_k T_K_k(x)
/// - T_D(x)) with T_P(x) = max_i (log2 |P_i| - i x), the mass of the band
/// [2^-x-1, 2^-x] about 2^(that - x), and |k| the smallest x >= 0 maximising
/// it, rounded (the same in 1 - t with the Taylor shifts of g, K_k, D about
/// 1). Empty where |k| < 16 at both ends, where both ends are concentrated
/// (one Moebius map cannot spread both), for an identically zero speed, and
/// where q's speed would have a pole or branch point (a root of D or sum
/// K_k^2, a certified bound at both ends as in Speed::scale_bits; the roots
/// of g are zeros of a polynomial factor, which cost a quadrature nothing)
/// not at least 2^16 times farther from 0 and 1 than p's: m brings t = infinity within
/// 2^-|k| of an end, and with it p's far singularities (a space curve such
/// as (t, C t^2, t^3) has some at |t| ~ C), which would make q costlier to
/// integrate than p.
/// Which m is chosen only affects the cost, never a result's correctness:
/// every use composes with m exactly.
/// \pre s is the speed of p (not checkable).
/// \throws nothing beyond allocation.
std::optional<BalancedCurve> balance(const Curve& p, const Speed& s);

/// The coefficient size from which peak_knots looks for features inside
/// (0, 1): kPeakCoefficientBitsPerDegree * d + kPeakCoefficientBits bits,
/// d the largest degree of g, D and sum K_k^2 (a pair of complex roots
/// within e of the real line needs coefficients of about (1/e)^(1/(d-1))
/// at least; Bezier curves of degree n have power-basis coefficients of
/// about 2^(2n) in D, of degree 2n - 2, and are not searched unless their
/// control points have several times n bits).
constexpr long kPeakCoefficientBitsPerDegree = 4;
constexpr long kPeakCoefficientBits = 64;

/// Whether peak_split looks for features in s at all: where the
/// coefficients reach kPeakCoefficientBitsPerDegree * d + kPeakCoefficientBits
/// bits (from the degrees and sizes alone; builds nothing).
bool peak_split_searched(const Speed& s);

/// Knots 0 = k_0 < ... < k_m = 1 (m >= 2) for a speed's integrals part by
/// part, and which knots hold a concentration of sigma (feature[i] for
/// knots[i]): each part has one at one end at most.
struct PeakSplit {
  std::vector<Rational> knots;
  std::vector<char> feature;
};

/// Where the speed s of a curve has narrow features inside (0, 1) (a pole,
/// branch point or zero of sigma within 2^-16 of a point c of the real
/// line, e.g. the angular speed of (t, C (t - 1/2)^2) for a huge C: a peak
/// of width 1/(2C) at 1/2), or its mass concentrated next to both ends,
/// which one Moebius map cannot spread: the split of [0, 1] whose parts,
/// each run from its feature's end (restrict_to(p, k, k') from the knot k
/// with the feature) and balanced by its own map where balance() does,
/// integrate at a cost independent of the feature's width. The features are
/// the real critical points of g, D and sum K_k^2 in (0, 1) about which one
/// of them has a root within 2^-16 (root_depth_bits of its Taylor shift
/// there, the point taken within 2^-(depth + 8) of the critical point, so
/// that the feature sits at a part's end on its own scale), none within
/// 2^(8 - depth) of an end; the knots are those points, the midpoints
/// between two of them, and the midpoint between an end concentrated as in
/// balance() and its nearest point. Searched only where the coefficients
/// reach kPeakCoefficientBitsPerDegree * d + kPeakCoefficientBits bits;
/// empty where nothing is found, including every curve below that size.
/// Which knots are chosen only affects the cost, never a result: the
/// integrals over [0, 1] are the sums over the parts.
/// \throws BudgetExceeded from the root isolation's budgets only.
std::optional<PeakSplit> peak_split(const Speed& s);

/// The curve u -> p(a + (b - a) u) on [0, 1], exact, for a != b (b < a
/// runs backwards): p restricted to the interval between a and b. Both
/// speeds of the restriction are |b - a| times p's at the corresponding t.
/// \throws InvalidArgument for a == b.
Curve restrict_to(const Curve& p, const Rational& a, const Rational& b);

/// t = m(s) = a s / (a s + b (1 - s)) exactly, for s in [0, 1]: a rational
/// for a rational s; else the root of the Moebius transform of s's
/// polynomial, f(b t / (b t + a (1 - t))) (b t + a (1 - t))^deg f, in the
/// image of s's isolating interval (m is increasing, so it isolates).
RealAlgebraic balance_map(const BalancedCurve& bal, const RealAlgebraic& s);
/// The inverse s = m^-1(t) = b t / (b t + a (1 - t)) the same way, for t in
/// [0, 1].
RealAlgebraic balance_unmap(const BalancedCurve& bal, const RealAlgebraic& t);

/// An enclosure of m over the ball s clipped to [0, 1]: m is increasing,
/// so the hull of m at s's clipped ends, each computed as a s / (a s + b
/// (1 - s)), a quotient of sums of non-negative terms (relative accuracy
/// about 2^-prec, however small m(s) or 1 - m(s) is).
/// \pre s finite and meeting [0, 1] (DomainError otherwise).
Ball balance_map_ball(const BalancedCurve& bal, const Ball& s, long prec);

/// The restriction of m to a piece [s0, s1] (0 <= s0 < s1 <= 1) in local
/// coordinates is the Moebius map t~ = k s~ / (k s~ + 1 - s~) of [0, 1]
/// onto itself, with k = D(s1) / D(s0), D(s) = a s + b (1 - s) > 0: an
/// enclosure of that k (relative accuracy about 2^-prec; no cancellation).
/// Composing the piece x -> K x / (K x + 1 - x) with it gives the parameter
/// k K, so a Moebius piece with alpha = 1 / (1 + K) on q becomes one with
/// alpha = 1 / (1 + k K) on p.
Ball balance_local_k(const BalancedCurve& bal, const RealAlgebraic& s0, const RealAlgebraic& s1, long prec);
/// The same k exactly, for rational s0 and s1.
Rational balance_local_k(const BalancedCurve& bal, const Rational& s0, const Rational& s1);

/// |log2 (b / a)|: the bits by which m's local parameters k may differ from
/// 1 (k lies in [min(a, b) / max(a, b), max(a, b) / min(a, b)]), so the
/// extra working precision that keeps 1 - alpha resolvable when alpha is
/// within 2^-bits of 1.
long balance_bits(const BalancedCurve& bal);

}  // namespace uniparam
