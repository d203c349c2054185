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
  // Bezier input (make_speed_dd_bernstein; then M, L and A are empty): for
  // each polynomial P of N_1, ..., N_d, Q (Q last), side (0: s = t / (1 - t),
  // 1: s = (1 - t) / t) and order j <= 2, the polynomial H in s with
  // P^(j)(t) = (1 - t)^(n - j) H(s) (side 0) or t^(n - j) H(s) (side 1),
  // at index (3 P + j) * 2 + side. bern_n = n, or -1 off this path.
  std::vector<DDPoly> bern;
  // upper bounds of the absolute coefficients of each bern[i]'s derivative
  // H' (the slope of H over s's ball)
  std::vector<std::vector<double>> bern_slope;
  // bern[i] holds H's coefficients cut to double words; bern_drop[i][k]
  // bounds what was cut from the k-th (0 where nothing)
  std::vector<std::vector<double>> bern_drop;
  long bern_n = -1;
};

/// The double-word path's data for the evaluation curve's components comps
/// (exact) and speed kind, or null where the path does not apply: more than
/// 3 components, the common denominator L or some M_i = N_i L / Q_i of
/// degree above 64, or not double words losing at most 24 bits in Horner's
/// rule on [0, 1] (high-degree Bezier curves' power bases lose more:
/// make_speed_dd_bernstein serves Bezier input, the local expansions the
/// rest).
std::shared_ptr<const SpeedDD> make_speed_dd(const std::vector<RatFunc>& comps, SpeedKind kind);

/// The double-word path's data for a Bezier curve's Bernstein form b (its
/// components N_i / Q, every row of one length n + 1), evaluated as
/// Bernstein sums (SpeedDD::bern), or null where the path does not apply:
/// more than 3 components, degree n < 2 or n > 160 (where the local
/// expansions cost less), or some H (its coefficients c_k binom(n - j, k)
/// cut to 88 significant bits, SpeedDD::bern_drop bounding the rest) not a
/// double-word polynomial losing at most 24 bits in Horner's rule on
/// [0, 1]. Bernstein sums lose few bits where the power basis loses ~n.
std::shared_ptr<const SpeedDD> make_speed_dd_bernstein(const BernsteinForm& b);

}  // namespace detail
}  // namespace uniparam
