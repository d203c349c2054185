// Private helpers of the algebra layer (not installed): exact signs of integer
// polynomials at rational points and certified refinement of an isolating
// interval. Implemented in root_refine.cpp (descartes_test in
// descartes.cpp); used by the root isolation, algebraic.cpp and deflation.cpp.
#pragma once

#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::detail {

/// Exact sign (-1, 0, 1) of f(x). Evaluates in Arb at increasing precision
/// and falls back to exact rational evaluation when the ball contains 0.
int exact_sign(const Poly& f, const Rational& x);

/// Refines an isolating interval of a simple root.
/// \pre f squarefree (or at least: the root in (lo, hi) is simple), lo < hi,
///      f(lo) != 0, f(hi) != 0 with opposite signs, exactly one root of f in
///      (lo, hi).
/// \post (lo, hi) only shrinks and keeps all these properties, and
///       hi - lo <= 2^-bits; or an exact (dyadic) root r was met, in which
///       case lo = hi = r and the function returns true.
/// Newton steps in Arb propose a subinterval (quadratic interval refinement,
/// Abbott), every accepted bracket is certified by exact sign tests;
/// bisection is the fallback. Throws BudgetExceeded after a generous
/// iteration cap. newton_log, when non-null, is the Newton rate (log2 of
/// the width a step aims to gain) to start from, and receives the rate
/// reached: successive calls on one root then keep the quadratic rate
/// instead of restarting at 2. A hint only; the result's guarantees do not
/// depend on it.
/// sev, when non-null, evaluates lambda f (real_roots.hpp). Interval
/// Newton steps then come first: the root lies in c - f(c) / F, with f(c)
/// from f's power basis at a short dyadic c and F an enclosure of f' on
/// (lo, hi) from sev at 64 bits, on a ball of radius at least 2^-23 (a
/// wide ball, core/ball_regions.hpp: the evaluator's cheap coarse bounds,
/// see local_poly.hpp). No exact sign.
/// c is the middle (one power-basis evaluation a step, a gain of ~10-20
/// bits) while the width is above 2^-24, then the power-basis Newton guess
/// (three evaluations, the width roughly squared). Where a step does not
/// halve the width, a bisection by the sign of f at a short dyadic midpoint
/// comes next and the steps resume (F holds 0 on a wide interval that holds
/// a zero of f' or where its bound is loose); after 8 such bisections, or at
/// once where deg f' <= 64 (F from the power basis), the exact steps above
/// take over. Same postconditions.
bool refine_isolating_interval(const Poly& f, Rational& lo, Rational& hi, long bits, long* newton_log = nullptr,
                               const ScaledEvaluator* sev = nullptr);

/// Moore's existence test: one interval Newton step on X = [g - d, g + d]
/// with centre g (a short dyadic), f' bounded on X by sev (as in the
/// refinement's steps). When the step's interval N lies strictly inside X,
/// X holds a root of f (f' keeps one sign on X and, say for f' > 0 and
/// f(g) > 0, g - d < g - f(g) / F_lo gives f(g - d) <= f(g) - F_lo d < 0
/// by the mean value theorem), that root lies in N, and the function sets
/// (lo, hi) to N, rounded outward to a grid of 2^-(min(bits, 2 |log2 2d| +
/// 32) + 8) and widened by a step (ends not roots, one sign change between
/// them) and returns true. Otherwise, false with lo, hi unchanged (no root
/// proven, not: no root). When (g - d, g + d) lies in an isolating interval
/// of f, the root proven is that interval's. d > 0 (InvalidArgument
/// otherwise); sev's contract is trusted.
bool prove_root_near(const Poly& f, const ScaledEvaluator& sev, const Rational& g, const Rational& d, long bits,
                     Rational& lo, Rational& hi);

/// Descartes' test of the root isolation: the sign variations, capped at 2,
/// of (x + 1)^n P(1 / (x + 1)) (an upper bound, of the parity of the
/// number of P's roots in (0, 1)); when the result is 0 or 1, sign_at_1 is
/// the sign of P(1). IEEE double with certified error bounds first, the
/// exact Taylor shift where those cannot decide. \pre deg P >= 1.
int descartes_test(const Poly& P, int& sign_at_1);

/// floor(log2(w)) for a rational w > 0 (InvalidArgument otherwise).
long floor_log2(const Rational& w);

}  // namespace uniparam::detail
