// uniparam/algebra/real_roots.hpp -- certified real-root isolation in a
// closed interval with rational ends.
#pragma once

#include <arb.h>

#include <functional>
#include <memory>
#include <vector>

#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// One real root of a polynomial p, isolated.
struct IsolatedRoot {
  /// Isolating interval. lo == hi exactly when the root is rational (it is
  /// then lo). Otherwise lo < hi, neither lo nor hi is a root of p, and the
  /// open interval (lo, hi) holds exactly one root of p.
  Rational lo, hi;
  /// The primitive squarefree factor of p (positive leading coefficient)
  /// this root is a simple root of; for a rational root lo = n/d it is d*t - n.
  Poly factor;
  /// Multiplicity of the root as a root of p (>= 1).
  int multiplicity = 1;
  /// True when the isolators of this header made this root: the contract
  /// above is then proven (exact signs at the ends), and RealAlgebraic's
  /// constructors from an IsolatedRoot skip their own check of the ends
  /// (two evaluations of the factor, ~10% of `radical` at low degree). A
  /// caller that sets it vouches for the contract: it is not checked.
  bool certified = false;

  /// Whether the root is the rational lo = hi exactly.
  bool is_exact() const { return lo == hi; }
};

/// How the roots of each squarefree factor, mapped to [0, 1], are isolated.
/// Every method is exact/certified and gives the same roots (the intervals
/// may differ); they differ only in cost.
enum class RootIsolationMethod {
  /// Exact below a small degree, Subdivision above it.
  Auto,
  /// Descartes' rule of signs with bisection and exact integer Taylor shifts
  /// (Vincent-Collins-Akritas) on the whole of [0, 1].
  Exact,
  /// Certified ball-arithmetic subdivision from truncated local Taylor
  /// expansions (a cell without a root: the enclosure of the factor
  /// excludes 0; a cell with exactly one: the derivative's excludes 0 and the
  /// signs at its ends differ), then Exact on the cells it leaves undecided.
  Subdivision,
};

/// Options of the isolator.
struct RootIsolationOptions {
  /// Refuse inputs of larger degree (BudgetExceeded naming this limit).
  long max_degree = 20000;
  /// The isolation method (for tests and benchmarks; Auto is the fastest).
  RootIsolationMethod method = RootIsolationMethod::Auto;
};

/// All real roots of p in the closed interval [a, b].
/// \pre p != 0, a <= b (InvalidArgument otherwise).
/// \post Sorted increasingly; the intervals [lo, hi] are pairwise disjoint and
///       contained in [a, b]; every root of p in [a, b] appears exactly once,
///       with its multiplicity; rational roots (in particular roots at a or b)
///       are exact (lo == hi).
/// Works on [a, b] only (each squarefree factor mapped to [0, 1]: Descartes'
/// rule of signs with exact Taylor shifts, from degree 300 after a certified
/// ball subdivision, see RootIsolationMethod), so its cost does not depend on
/// roots elsewhere. BudgetExceeded when the isolation does not finish within
/// its subdivision budget or the time budget.
std::vector<IsolatedRoot> isolate_real_roots(const Poly& p, const Rational& a, const Rational& b,
                                             const RootIsolationOptions& opt = {});

/// A certified evaluator of a polynomial p up to a positive constant: for
/// one constant lambda > 0, v must enclose lambda p(x), and d (when
/// non-null) lambda p'(x), at every point of the real ball x, computed at
/// working precision prec. Enclosures may be wide or non-finite, never
/// wrong. Typically p's values from its factors: far cheaper than p's power
/// basis at high degree, whose huge coefficients cancel.
using PolyEvaluator = std::function<void(arb_t v, arb_t d, const arb_t x, long prec)>;

/// An evaluator of lambda * f for a known rational lambda != 0: ev's
/// enclosures (as for PolyEvaluator) contain lambda f(x) and lambda f'(x)
/// exactly. Lets a root of f be refined without f's power basis for the
/// derivative (RealAlgebraic).
struct ScaledEvaluator {
  PolyEvaluator ev;
  Rational lambda;
  /// Left empty by callers: the refinement (root_refine.hpp) keeps here, on
  /// first use, f's basis centred at 1/2 in IEEE double, for the start of
  /// every root of f refined with this evaluator (one exact Taylor shift of
  /// f instead of one per root). Read and written with the atomic
  /// shared_ptr functions: safe across threads.
  mutable std::shared_ptr<const std::vector<double>> centred_cache;
};

/// The roots of p in [a, b] as isolate_real_roots gives them (same
/// postconditions and errors), found first by a ball subdivision of [a, b]
/// on ev's enclosures at 64 bits (an interval where p's enclosure excludes 0
/// has no root; one where p''s excludes 0 has one exactly when the exact
/// signs at its ends differ). Intervals it cannot decide within 2^-30 of
/// the width, and every p not proven squarefree (by a gcd modulo a prime),
/// go to isolate_real_roots. opt.method: Subdivision always uses ev, Auto
/// from degree 300 (below, the exact VCA is as fast), Exact never. For
/// high-degree p with cheap factored values (the critical points of a
/// speed: degree ~12d) this avoids p's own expansions.
std::vector<IsolatedRoot> isolate_real_roots(const Poly& p, const PolyEvaluator& ev, const Rational& a,
                                             const Rational& b, const RootIsolationOptions& opt = {});

/// Number of distinct real roots of p in the open interval (a, b), exact.
/// \pre p != 0, a < b.
long count_real_roots(const Poly& p, const Rational& a, const Rational& b);

/// Work counter (tests, benchmarks): the number of exact isolations
/// (isolate_real_roots on the power basis, count_real_roots) this thread
/// has started.
long exact_isolations();

}  // namespace uniparam
