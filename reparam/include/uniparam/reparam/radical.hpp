// uniparam/reparam/radical.hpp -- piecewise radical reparameterization
// (Hong, Wang, Yang 2023, Algorithm 1; docs/math.md section 4): r = phi o m, with phi the
// elementary piecewise radical map that lifts the zeros of the speed and m
// the optimal piecewise Moebius map on top.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "uniparam/reparam/pieces.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

struct RadicalResult {
  SpeedKind kind;
  std::vector<Breakpoint> T;             ///< t_0 = 0 < ... < t_N = 1, zeros marked
  std::vector<PieceIntegrals> integrals; ///< per piece: L, A, B, C (times Delta s), M, alpha
  std::vector<Ball> S;                   ///< s_0 = 0 < ... < s_N = 1 (eq. 9: cumulative sqrt L)
  std::vector<Ball> Z;                   ///< z_0 = 0 < ... < z_N = 1 (cumulative sqrt M)
  std::vector<Ball> A, B, C;             ///< Hong, Wang, Yang 2023: A_k, B_k, C_k (the integrals / Delta s_k)
  Ball mu;                               ///< int_0^1 sigma (invariant)
  Ball u_before;                         ///< u(p)
  Ball u_radical;                        ///< u(p o phi) = mu^2 / (sum sqrt L)^2
  Ball u_after;                          ///< u(p o phi o m) = mu^2 / (sum sqrt M)^2
  bool identically_zero = false;         ///< angular speed of a line: nothing to do, r = id

  /// Set when p's weights grow geometrically (balance(p) not empty,
  /// scaling.hpp): the method ran on the balanced curve q = p o m and r is
  /// m o r_q. T = m(T_q) exactly, with the zeros of p's speed marked
  /// (mark_zeros; m maps the zeros of sigma_q onto those of sigma_p, with
  /// their multiplicities); S, Z, A, B, C, the integrals and u_radical,
  /// u_after are r_q's (they describe the same pieces in s and z); u_before
  /// is p's. Piece i of r is then t = t_i + Delta t_i k_i y / (k_i y + 1 - y)
  /// with y the local value of r_q's piece (in q's parameter) and k_i =
  /// outer_k[i] (balance_local_k on [T_q,i, T_q,i+1]): m restricted to the
  /// piece. outer_k is empty otherwise (k_i = 1). balanced->on is r_q, from
  /// which refine_radical_data works.
  std::vector<Ball> outer_k;
  struct Balanced {
    std::shared_ptr<const BalancedCurve> curve;  ///< q = p o m, with m's a and b
    std::shared_ptr<const RadicalResult> on;     ///< r_q, the map on q
  };
  /// Empty unless p's weights grow geometrically (see above).
  std::optional<Balanced> balanced;

  std::size_t pieces() const { return T.size() - 1; }
  /// Exponent of the radical in piece i: mu + 1 when one end is a zero of
  /// multiplicity mu, 1 otherwise; and which end.
  int root_index(std::size_t i) const;
  ZeroSide side(std::size_t i) const;
};

/// Runs Algorithm 1 of Hong, Wang, Yang 2023 with certified numbers.
/// \post every Ball meets Options::digits; T exact.
/// \throws as uniformity().
RadicalResult radical(const Curve& c, SpeedKind kind, const Options& opt = {});

/// The same map r with its data recomputed to `digits`: S, Z and every
/// alpha meet `digits` (A, B, C and the integrals follow), as radical()
/// computes them for r's breakpoints T; each refined ball therefore lies in
/// r's (up to rounding). mu and the uniformities are kept; an identically
/// zero map is returned as is. A balanced result (r.balanced) refines
/// r.balanced->on on q's speed and composes it with m again.
/// \pre r was computed for the speed sp (not checkable); digits >= 1
///      (InvalidArgument).
/// \throws BudgetExceeded when `digits` cannot be met within max_prec bits or
///         the thread's TimeBudget.
RadicalResult refine_radical_data(const Speed& sp, const RadicalResult& r, long digits, long max_prec);

/// Evaluation of a piecewise radical map (the overloads for a MoebiusResult
/// are in moebius.hpp).
/// Enclosure of r(z) for z in [0, 1] (the ball may straddle a joint: both
/// pieces are evaluated and the union returned). An exact z equal to an exact
/// joint z_i (z = 0, z = 1) gives t_i's ball, exact for a dyadic t_i. The
/// accuracy is limited by r's data (Z, alpha: balls); see
/// Reparameterization::refined. InvalidArgument if z misses [0, 1].
Ball eval_r(const RadicalResult& r, const Ball& z, long prec);
/// Enclosure of sigma_{p o r}(z) = sigma_p(r(z)) r'(z), the reparameterized
/// speed, evaluated from the formulas of the pieces; `s` must be the speed r
/// was computed for (not checkable). InvalidArgument if z misses [0, 1].
Ball eval_speed(const RadicalResult& r, const Speed& s, const Ball& z, long prec);

/// Enclosures of the components of p(r(z)), the reparameterized curve's
/// point at z in [0, 1] (c must be the curve r was computed for); for a
/// balanced r, evaluated as q(r_q(z)), the same point. InvalidArgument if z
/// misses [0, 1].
std::vector<Ball> eval_point(const Curve& c, const RadicalResult& r, const Ball& z, long prec);

/// Independent check of the whole chain: mu^2 / int_0^1 sigma_{p o r}(z)^2 dz,
/// integrating the reparameterized speed built from the pieces of r directly
/// in z (certified quadrature, `digits` digits). For a balanced r the
/// integrand evaluates p's speed through the pieces' outer Moebius maps,
/// whose poles lie within about a / b of the pieces: the quadrature then
/// needs about balance_bits bisections and may be slow.
Ball radical_direct_uniformity(const RadicalResult& r, const Speed& s, long digits, long max_prec);

}  // namespace uniparam
