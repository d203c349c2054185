// uniparam/reparam/nurbs.hpp -- the reparameterized curve p o r of a Moebius
// method as a NURBS curve (docs/nurbs.md).
//
// On a piece [s_i, s_{i+1}] with local parameter u = (s - s_i) / (s_{i+1} - s_i)
// the Moebius map (2.1) is t = t_i + h (1 - a) u / (a (1 - u) + (1 - a) u),
// h = t_{i+1} - t_i. With p = (X_1, ..., X_n) / W of degree d and b_j the
// Bernstein coefficients of the homogeneous (X, W) on [t_i, t_{i+1}],
//     D(u)^d (X, W)(r(u)) = sum_j B_j^d(u) (1 - a)^j a^(d - j) b_j,
// D(u) = a (1 - u) + (1 - a) u > 0: a rational Bezier segment of degree d with
// control points X_j / W_j (independent of a) and weights (1 - a)^j a^(d - j) W_j.
// Segments with a non-positive weight are subdivided at u = 1/2 until every
// weight is positive (the Bernstein coefficients of a polynomial without zero
// on the interval converge to its values). Consecutive segments share their
// joint control point, each segment's weights scaled by a positive constant so
// that the shared weight agrees: a C0 NURBS with interior knots of
// multiplicity d.
#pragma once

#include <cstddef>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/bezier.hpp"
#include "uniparam/reparam/composite.hpp"
#include "uniparam/reparam/curve.hpp"
#include "uniparam/reparam/moebius.hpp"

namespace uniparam {

/// A NURBS curve of degree d >= 1 in R^n with clamped knot vector
/// (knots.size() == points.size() + d + 1, the first and last d + 1 knots
/// equal 0 and 1, interior knots of multiplicity d, nondecreasing) and
/// positive weights (certainly positive balls, or positive exact values).
/// The Ball fields are always set and contain the true values; the exact
/// fields are set where the data are exact:
/// * kind == Exact: knots_exact, points_exact, weights_exact (all rational);
/// * kind == Surd: knots_exact, points_exact rational, weights_surd exact in
///   Q(sqrt c) (Bezier's optimal map of an integral curve);
/// * kind == Balls: knots_exact and points_exact set only when exact (a
///   single Bezier piece), the weights balls.
struct Nurbs {
  enum class Kind { Exact, Surd, Balls };
  Kind kind = Kind::Balls;
  long degree = 0;
  std::size_t dimension = 0;
  std::vector<Ball> knots;
  std::vector<std::vector<Ball>> points;
  std::vector<Ball> weights;
  std::vector<Rational> knots_exact;
  std::vector<std::vector<Rational>> points_exact;
  std::vector<Rational> weights_exact;
  std::vector<QuadraticSurd> weights_surd;
  /// Bezier segments (points.size() == segments * degree + 1), and how many
  /// of them come from subdividing a piece whose weights were not all positive.
  std::size_t segments = 0;
  std::size_t subdivided = 0;
  /// The distinct knots 0 = k_0 < ... < k_segments = 1, balls (exact for Exact).
  std::vector<Ball> breaks() const;
};

/// p o r as a NURBS (see the file comment), exact when r.exact is set (kind
/// Exact, rational arithmetic throughout), otherwise in ball arithmetic at
/// `prec` bits (kind Balls). Before returning, the NURBS is evaluated at
/// u = 0, 1/4, 1/2, 3/4, 1 of every segment and compared with p(r(s))
/// evaluated from the map (eval_point, or exactly for a rational map):
/// equal (exact) or overlapping (balls), else std::logic_error (an internal
/// error).
/// \pre r was computed for c (not checkable); prec >= 16.
/// \throws DomainError when r has radical pieces (never: MoebiusResult pieces
///         are Moebius maps); BudgetExceeded when a weight's sign cannot be
///         certified at `prec` bits or positivity needs more than 2^12
///         segments per piece; TimeLimitExceeded when the thread's
///         TimeBudget runs out.
Nurbs moebius_nurbs(const Curve& c, const MoebiusResult& r, long prec);

/// p o r of a composite curve's Moebius map (every part a MoebiusResult) as
/// one NURBS: each segment's pieces as in moebius_nurbs, raised to the
/// largest degree of the segments (exact degree elevation), over the
/// global s (segment j's pieces in [S_j, S_{j+1}]). Exact when every part is
/// an exact rational map, balls otherwise; checked like moebius_nurbs
/// against p(r(s)) at u = 0, 1/4, ..., 1 of every NURBS segment.
/// \pre m was computed for c (not checkable); prec >= 16.
/// \throws InvalidArgument for a radical part, or a gap between segments (a
///         NURBS with interior knots of multiplicity d is continuous);
///         as moebius_nurbs otherwise.
Nurbs composite_nurbs(const CompositeCurve& c, const CompositeMap& m, long prec);

/// Bezier's optimal bilinear map (bezier_optimal) as a NURBS: one segment,
/// knots (0^(n+1), 1^(n+1)), the control points of b, the weights of r
/// (kind Surd when r.exact, else Balls). Checked like moebius_nurbs against
/// p(r(s)) (ball arithmetic).
/// \pre r == bezier_optimal(b, ...) (not checkable); prec >= 16.
/// \throws BudgetExceeded when a weight is not certainly positive at `prec`.
Nurbs bezier_nurbs(const BezierCurve& b, const BezierResult& r, long prec);

/// The NURBS at an exact s in [0, 1]: \pre n.kind == Exact; InvalidArgument
/// for s outside [0, 1]. Exact rational value of every component.
std::vector<Rational> nurbs_eval(const Nurbs& n, const Rational& s);
/// Enclosure of the NURBS at a ball s inside [0, 1] (the union over the
/// segments s may meet). InvalidArgument for s outside [0, 1].
std::vector<Ball> nurbs_eval(const Nurbs& n, const Ball& s, long prec);

}  // namespace uniparam
