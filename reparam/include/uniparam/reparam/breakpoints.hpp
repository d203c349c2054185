// uniparam/reparam/breakpoints.hpp -- the floating-point (UNCERTIFIED) choice
// of the breakpoints of a C0 piecewise Moebius map (docs/math.md section 3).
//
// *** Nothing here is certified. *** reparam_c0 uses this optimiser to
// *choose* T and then certifies everything it reports on the chosen T (a bad
// choice costs optimality, never correctness). It is public so that the same
// search can run on other evaluations of the speed: the double-precision
// benchmark baseline runs it on its own quadrature, and a user can run it on
// a speed the engine does not model.
#pragma once

#include <functional>
#include <vector>

namespace uniparam {

/// The piece integrals of [a, b] over dt, with t~ = (t - a)/(b - a):
///   A = int sigma^2 (1 - t~)^2,  B = int sigma^2 2 t~ (1 - t~),  C = int sigma^2 t~^2.
/// The optimal Moebius piece's contribution is M = (b - a)(B + 2 sqrt(AC))
/// (docs/math.md (2.2)), and Phi(T) = sum_i sqrt M_i.
struct PieceMoments {
  double A = 0, B = 0, C = 0;
};

/// How the search ended.
struct BreakpointChoice {
  std::vector<double> t;  ///< 0 = t_0 < t_1 < ... < t_N = 1
  double phi = 0;         ///< Phi at t (from the callbacks' values)
  double phi_equal = 0;   ///< Phi at the equally spaced breakpoints
  /// max_j |dPhi/dt_j| (t_{j+1} - t_{j-1}) / Phi at t: how far from
  /// stationary the search stopped (0 at a stationary point).
  double stationarity = 0;
  long iterations = 0;    ///< accepted BFGS steps
};

/// A local minimum of Phi(T) = sum sqrt M_i over the interior breakpoints,
/// started from the equally spaced T: BFGS on the logits of the gaps (so the
/// order 0 < t_1 < ... < 1 holds at every step), Armijo backtracking with
/// extrapolation where Phi is not convex along the direction, the gradient in
/// closed form by the envelope theorem:
///   dM_left/dt_j  =   sqrt(C/A) B + 2C + h sigma(t_j)^2 sqrt(A/C)   (piece ending at t_j)
///   dM_right/dt_j = -(sqrt(A/C) B + 2A + h sigma(t_j)^2 sqrt(C/A))  (piece starting at t_j).
/// Stops at stationarity < 1e-9, after 200 steps, when a step moves nothing
/// by 1e-12 and lowers Phi by < 1e-15 Phi, or when no decreasing step is
/// found.
/// \param N        number of pieces, N >= 1 (N = 1 returns t = (0, 1)).
/// \param moments  the piece integrals of [a, b], 0 <= a < b <= 1; called
///                 O(N) times per step.
/// \param sigma2   sigma(t)^2 at t in (0, 1); called N - 1 times per step.
/// \post t is strictly increasing from 0 to 1 with gaps > 1e-12; phi <=
///       phi_equal up to the callbacks' own consistency (every accepted step
///       lowers Phi as the callbacks evaluate it).
/// \throws InvalidArgument if N < 1; otherwise only what the callbacks throw.
BreakpointChoice optimise_breakpoints(long N, const std::function<PieceMoments(double a, double b)>& moments,
                                      const std::function<double(double t)>& sigma2);

}  // namespace uniparam
