// Private to reparam: SVG elliptical arcs as exact rational quadratic Bezier
// pieces (path.hpp's arc rule; docs/inputs.md).
#pragma once

#include <string>
#include <vector>

#include "uniparam/core/number.hpp"
#include "uniparam/reparam/bezier.hpp"

namespace uniparam::detail {

/// The SVG arc from (x1, y1) to (x2, y2) with radii rx, ry, x-axis rotation
/// `phi` degrees and flags (SVG implementation notes F.6), exactly:
/// * equal end points: no piece (the arc is omitted, F.6.2);
/// * rx = 0 or ry = 0: one degree-1 piece, the chord;
/// * otherwise rational quadratic pieces [X(a), X(T), X(b)] with weights
///   (1, 1, 2 / (1 + cos delta)), where X(c, s) = center + c u + s J u,
///   u = p1 - center, J the quarter turn of the ellipse in the sweep
///   direction (J = R diag(rx, ry) rot90 diag(rx, ry)^-1 R^T, rational for a
///   rotation R by a multiple of 90 degrees), a and b consecutive points of
///   (1, 0), (0, 1), (-1, 0), (0, -1), (cos Delta, sin Delta) on the unit
///   circle (Delta the arc's sweep), T the intersection of their tangents.
///   Every point of every piece lies on the ellipse; the first piece starts
///   at p1, the last ends at p2; the pieces follow the sweep direction.
/// \throws InvalidArgument "<name>: ... uniparam does not approximate" when
///         phi is not a multiple of 90 or the center is irrational.
std::vector<BezierCurve> svg_arc(const Rational& x1, const Rational& y1, const Rational& rx, const Rational& ry,
                                 const Rational& phi, bool large_arc, bool sweep, const Rational& x2,
                                 const Rational& y2, const std::string& name);

/// sqrt(q) when it is rational (q >= 0 a square of a rational), else false.
bool rational_sqrt(const Rational& q, Rational& root);

}  // namespace uniparam::detail
