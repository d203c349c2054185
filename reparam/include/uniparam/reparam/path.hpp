// uniparam/reparam/path.hpp -- exact inputs of composite curves: SVG path
// data and NURBS / B-spline descriptions turned into chains of Bezier
// segments with exact rational data (docs/inputs.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "uniparam/core/json.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/bezier.hpp"

namespace uniparam {

/// A composite curve's exact input: segments in order, each a BezierCurve
/// on its own parameter [0, 1]; knots 0 = k_0 < ... < k_m = 1 (exact
/// rationals, m = segments.size()) give segment j the global parameter
/// interval [k_j, k_{j+1}]; labels name each segment for messages
/// ("segment 3: C at column 17").
/// Invariants of every PathInput returned below: m >= 1, knots.size() == m + 1,
/// labels.size() == m, all segments of one dimension, no segment constant
/// (all control points equal), the end point of segment j equal to the start
/// point of segment j + 1 (the path is continuous).
struct PathInput {
  std::vector<BezierCurve> segments;
  std::vector<Rational> knots;
  std::vector<std::string> labels;
};

/// Bounds of the SVG reader.
struct SvgLimits {
  std::size_t max_length = std::size_t(1) << 20;  ///< characters of the path data
  std::size_t max_segments = 100000;              ///< segments over all subpaths
};

/// Parses SVG path data (SVG 1.1 section 8.3 / SVG 2 "d" grammar): commands
/// M m L l H h V v C c S s Q q T t Z z A a, absolute and relative, implicit
/// repetition of a command's parameters (after M/m the repeats are L/l),
/// numbers in the SVG grammar ("10-5" is 10 then -5, ".5.5" is .5 then .5,
/// exponents "1e-3"; a decimal exponent of 1000 or more is refused) read
/// exactly as decimals, arc flags as single '0'/'1' characters (also
/// unseparated: "a1 1 0 00 1 1"), separators of whitespace and at most one
/// comma between parameters.
///
/// One subpath (from a moveto to the next moveto or the end; a command after
/// Z starts a new subpath at the closed subpath's start) is one PathInput,
/// with uniform knots j/m. Lines (L, H, V, Z) become degree-1 segments,
/// Q/T quadratics, C/S cubics (S and T reflect the previous C/S resp. Q/T
/// control point, else use the current point). Z adds a line back to the
/// subpath's start when the current point differs from it. Segments whose
/// control points are all equal are dropped.
///
/// Elliptical arcs (SVG implementation notes F.6) become exact rational
/// quadratic Beziers, pieces of sweep at most 90 degrees in the ellipse's
/// own angle, split at its axis points, when the data allow it: the rotation
/// a multiple of 90 degrees and the center rational (the radicand of F.6.5.2
/// the square of a rational, or radii too small so that the center is the
/// chord's midpoint, F.6.6). Each piece has weights (1, 1, 1 / cos^2(delta/2)),
/// delta its sweep: the exact conic arc, parameterized up to a Moebius map.
/// Zero radius: a line; equal end points: omitted (F.6.2).
///
/// \throws ParseError (1-based column) for malformed path data: a missing or
///         malformed number or flag, a command letter that is not one of the
///         above, a path not starting with M/m, parameters after Z.
/// \throws InvalidArgument for an arc whose rotation is not a multiple of 90
///         degrees or whose center is irrational ("arc 2 at column 31: ...;
///         uniparam does not approximate"), a subpath with no segment left
///         ("subpath 2 at column 12 has no segment"), path data longer than
///         limits.max_length or with more than limits.max_segments segments,
///         or an empty path.
std::vector<PathInput> parse_svg_path(const std::string& d, const SvgLimits& limits = {});

/// Bounds of the NURBS reader.
struct NurbsLimits {
  long max_degree = 64;            ///< the conversion costs O(p^3) per span
  std::size_t max_points = 100000;  ///< control points
};

/// A NURBS or B-spline curve from JSON: {"degree": p, "knots": [u_0, ...],
/// "control": [[x, y, ...], ...], "weights": [w_0, ...]} ("weights"
/// optional; no other keys). Entries are exact rationals: JSON numbers read
/// as decimals, or strings "1/3", "0.25". With n + 1 control points the knot
/// vector has n + p + 2 entries, and the curve's domain is [u_p, u_{n+1}]
/// (clamped or not). The result has one Bezier segment per nonempty knot
/// span of the domain (exact blossoming in homogeneous coordinates: the
/// segment of [u_j, u_{j+1}] has the control points f(u_j^(p-k), u_{j+1}^k),
/// k = 0..p, of the blossom f), and the knots are the distinct domain knots
/// mapped exactly onto [0, 1] by u -> (u - u_p) / (u_{n+1} - u_p). Weights
/// all equal give integral (unweighted) segments. Labels read
/// "span [u_j, u_{j+1}] (knots j and j+1)".
/// \throws InvalidArgument with a message naming the field (and entry) for:
///         a missing or unknown key, a value of the wrong kind, degree < 1 or
///         above limits.max_degree, fewer than p + 1 or more than
///         limits.max_points control points, control points of unequal
///         dimension or of dimension < 2, a knot count other than n + p + 2,
///         decreasing knots, an empty domain, a knot inside the domain of
///         multiplicity above p or any knot of multiplicity above p + 1, a
///         weight count other than n + 1, a non-positive weight, and a span
///         of the domain whose segment is a single point (uniparam does not
///         drop it: that would change the parameterization the knots give).
PathInput parse_nurbs_json(const JsonValue& j, const NurbsLimits& limits = {});

/// parse_nurbs_json(parse_json(text, json_limits), limits).
/// \throws ParseError for malformed JSON; as parse_nurbs_json otherwise.
PathInput parse_nurbs(const std::string& text, const NurbsLimits& limits = {}, const JsonLimits& json_limits = {});

}  // namespace uniparam
