// uniparam/reparam/scaling.hpp -- an exact change of parameter that balances
// a rational curve whose weights grow geometrically, for the integrals of
// the uniformity (docs/math.md §1, (1.1) and (1.2)).
#pragma once

#include <optional>

#include "uniparam/core/number.hpp"
#include "uniparam/reparam/curve.hpp"

namespace uniparam {

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

}  // namespace uniparam
