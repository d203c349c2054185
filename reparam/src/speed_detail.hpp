// speed_detail.hpp -- the double-word path's data, shared by Speed's
// construction (speed.cpp) and its evaluation (speed_dd.cpp). Internal to
// uniparam_reparam.
#pragma once

#include <memory>
#include <vector>

#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/ratfunc.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {
namespace detail {

/// Speed::eval_dd's components over one common denominator, x_i = M_i / L.
struct SpeedDD {
  std::vector<DDPoly> M;
  DDPoly L;
  bool unit_den = false;  // L == 1 (a polynomial curve)
  // The angular speed with L != 1: A_i = M_i' L - M_i L' as polynomials
  // (B_i = A_i'), where they are double words losing few bits: one Horner
  // pass for A_i and A_i' instead of M_i and L with two derivatives each and
  // four products. Empty otherwise; where it is not, M and L are empty
  // (they only had to pass the path's checks).
  std::vector<DDPoly> A;
};

/// The double-word path's data for the evaluation curve's components comps
/// (exact) and speed kind, or null where the path does not apply: more than
/// 3 components, the common denominator L or some M_i = N_i L / Q_i of
/// degree above 64, or not double words losing at most 24 bits in Horner's
/// rule on [0, 1] (high-degree Bezier curves' power bases lose more; the
/// local expansions serve them).
std::shared_ptr<const SpeedDD> make_speed_dd(const std::vector<RatFunc>& comps, SpeedKind kind);

}  // namespace detail
}  // namespace uniparam
