// uniparam/core/ball_regions.hpp -- the radii at which a complex ball stops
// being treated as a point. Two thresholds, for two different questions:
//
//  * kRegionBallLog2 (2^-30): is the ball a point of the quadrature (a
//    Gauss-Legendre node, radius about 2^-100 of itself) or a region (a
//    subinterval's segment or ellipse, whose enclosure bounds the error)?
//    Point-only fast paths (double-word evaluation, core/dd_ball.hpp) take
//    balls below it; far below any region's radius and far above any
//    node's, its exact value does not matter.
//  * kCoarseBallLog2 (2^-24): may an evaluator bound a function on the ball
//    only coarsely? Above it the enclosure is as wide as the function's
//    variation on the ball, about 2^-24 of its scale or more, so LocalPoly
//    (algebra/local_poly.hpp) bounds it from expansions truncated at 2^-24
//    of their scale and from centred forms instead of at full precision.
//    Regions narrower than that (tiny subintervals near a singularity) keep
//    the accurate path; so does a ball that a caller wants bounded at full
//    precision. A caller that wants the coarse path on a narrower ball
//    widens it to 2^(kCoarseBallLog2 + 1) (the root refinement's interval
//    Newton steps do).
#pragma once

#include <acb.h>

namespace uniparam {

/// log2 of the radius from which a ball is a region, not a point (above).
constexpr long kRegionBallLog2 = -30;

/// log2 of the radius from which a ball may be bounded coarsely (above).
constexpr long kCoarseBallLog2 = -24;

/// r = an upper bound of |t - mid z| over the complex ball z.
inline void ball_radius(mag_t r, const acb_t z) {
  mag_hypot(r, arb_radref(acb_realref(z)), arb_radref(acb_imagref(z)));
}

/// True when z's radius (real or imaginary) is at least 2^kCoarseBallLog2:
/// LocalPoly's wide balls, whose enclosures only bound the polynomial.
inline bool is_wide_ball(const acb_t z) {
  return mag_cmp_2exp_si(arb_radref(acb_realref(z)), kCoarseBallLog2) >= 0 ||
         mag_cmp_2exp_si(arb_radref(acb_imagref(z)), kCoarseBallLog2) >= 0;
}

/// True when z's radius (real or imaginary) is at least 2^kRegionBallLog2:
/// a region of the quadrature rather than one of its nodes.
inline bool is_region_ball(const acb_t z) {
  return mag_cmp_2exp_si(arb_radref(acb_realref(z)), kRegionBallLog2) >= 0 ||
         mag_cmp_2exp_si(arb_radref(acb_imagref(z)), kRegionBallLog2) >= 0;
}

}  // namespace uniparam
