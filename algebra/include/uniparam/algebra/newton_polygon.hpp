// uniparam/algebra/newton_polygon.hpp -- the sizes of a polynomial's
// coefficients as a tropical polynomial (the upper Newton polygon of the
// points (i, log2 |c_i|)), and the certified bound on how close to 0 its
// nonzero complex roots may lie that follows from it.
#pragma once

#include <vector>

#include "uniparam/core/poly.hpp"

namespace uniparam {

/// The tropical polynomial T(x) = max_i (log2 |c_i| - i x) of a nonzero
/// integer polynomial sum c_i t^i, kept as the vertices of the upper convex
/// hull of the points (i, log2 |c_i|), i increasing (log2 in double, for
/// exponents of any size). T is convex and piecewise linear; its breakpoints
/// are the slopes of the hull's edges, and about 2^-x for a breakpoint x is
/// the modulus of some of the polynomial's roots (within a factor depending
/// on the degree: estimates only, except root_depth_bits below).
/// Thread-compatible (operator() moves a cursor).
class NewtonPolygon {
 public:
  /// \pre none (the zero polynomial has no vertices: T = -infinity).
  explicit NewtonPolygon(const Poly& p);
  /// The edges' slopes that are >= 0, appended to out: where the maximising
  /// index changes for x >= 0.
  void breakpoints(std::vector<double>& out) const;
  /// The first edge's slope, max_i (log2 |c_{v+i}| - log2 |c_v|) / i with
  /// c_v the lowest nonzero coefficient (0 when none or negative): about
  /// -log2 of the smallest modulus of the nonzero roots.
  double deepest() const;
  /// T(x), for x not below the previous call's x (amortised O(1)).
  double operator()(double x);

 private:
  std::vector<double> i_, l_;  // hull vertices
  std::size_t at_ = 0;         // the vertex maximising at the last x asked
};

/// A certified d >= 0 with |r| >= 2^-d for every nonzero complex root r of
/// p: Fujiwara's bound on the reversed polynomial, |r| >= (1/2) min_i
/// |c_v / c_{v+i}|^(1/i) (c_v the lowest nonzero coefficient), rounded up
/// with a margin for the double logarithms: at most 2 where that bound
/// keeps every root outside the unit disc (and for a constant or a
/// monomial, which have no nonzero roots). Roots of p at 0 are not counted.
long root_depth_bits(const Poly& p);

/// The larger of root_depth_bits(p) and root_depth_bits(p(1 + t)): no root
/// of p other than 0 and 1 lies within 2^-d of 0 or of 1 (p's features
/// next to the ends of [0, 1]).
long end_root_depth_bits(const Poly& p);

}  // namespace uniparam
