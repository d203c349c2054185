// uniparam/reparam/pieces.hpp -- breakpoints and the per-piece integrals
// shared by the radical and the Moebius methods (docs/math.md sections 2-4).
#pragma once

#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/reparam/speed.hpp"

namespace uniparam {

/// A breakpoint t_i with the multiplicity of sigma's zero there (0 if
/// sigma(t_i) != 0).
struct Breakpoint {
  RealAlgebraic t;
  int multiplicity = 0;
  std::size_t factor = 0;  ///< for a zero: index of its squarefree factor of g
  std::size_t zero_index = 0;  ///< for a zero: its position in Speed::zeros()

  /// The zero of sigma at this breakpoint. \pre multiplicity > 0.
  SpeedZero zero() const { return SpeedZero{t, multiplicity, factor, zero_index}; }
};

/// Which end of a piece is a zero of sigma (never both).
enum class ZeroSide { None, Left, Right };

/// The roots in [0, 1] of the critical numerator P = 2 g' Q D + g Q' D -
/// 2 g Q D' (Q = sum K^2; (sigma^2)' = g P / D^3): the zeros of sigma' that
/// are not zeros of g, increasing, rational ones exact (0 and 1 included
/// when they are roots). P has degree ~11d; it is isolated and its
/// irrational roots are refined from its values on the speed's factors
/// (Speed::eval_critical: each root carries that evaluator and a copy of the
/// speed, RealAlgebraic(IsolatedRoot, ScaledEvaluator)), never from P's
/// power basis but for one to three evaluations per interval Newton step.
/// Empty for an identically zero speed or P = 0.
std::vector<RealAlgebraic> critical_points(const Speed& s);

/// T = (0, every zero of sigma * sigma' in (0, 1), 1) in increasing order,
/// zeros of sigma marked with their multiplicities (docs/math.md section 4). Two
/// consecutive zeros of sigma get their rational midpoint inserted between
/// them. For the angular speed of a line: T = (0, 1).
std::vector<Breakpoint> critical_breakpoints(const Speed& s);

/// Attaches the zero multiplicities of sigma to given breakpoints
/// (0 = t_0 < ... < t_N = 1 checked: InvalidArgument otherwise).
std::vector<Breakpoint> mark_zeros(const Speed& s, const std::vector<RealAlgebraic>& ts);

/// The integrals of one piece [a, b] with local coordinate
/// t~ = (t - a) / (b - a), the elementary radical map's local s~(t~)
/// (t~^(mu+1) for a zero at the left end, 1 - (1 - t~)^(mu+1) at the right end,
/// t~ otherwise) and rho = Delta s / (phi^-1)'(t) (Delta t / ((mu+1) t~^mu),
/// Delta t / ((mu+1)(1 - t~)^mu), Delta t):
///     A = int sigma^2 rho (1 - s~)^2,  B = int sigma^2 rho 2 s~ (1 - s~),
///     C = int sigma^2 rho s~^2,        L = A + B + C = int sigma^2 rho.
/// These are Delta s times the A_i, B_i, C_i of Hong, Wang, Yang 2023, section 3.4 (misprints
/// corrected, docs/math.md section 5), so they do not depend on S; for a piece
/// without zeros they are Delta t times ImUp's A_i, B_i, C_i. Then
/// M = B + 2 sqrt(A C) and alpha* = 1 / (1 + sqrt(C / A)).
/// Every integrand is analytic on the closed piece: near a zero the removable
/// singularity of sigma^2 / t~^mu is removed by exact deflation.
struct PieceIntegrals {
  Ball A, B, C, L, M, alpha;
  /// int sigma^2 over the piece, computed (in the same quadrature) where a
  /// zero of sigma ends it, to square_bits bits; square_bits = 0 elsewhere
  /// (there it is L / Delta t: see piece_square_integral).
  Ball square;
  long square_bits = 0;

  /// 1 - alpha with the digits it has: 1/(1 + sqrt(A/C)), intersected with
  /// 1 - alpha from alpha's ball (which alone leaves no digits of it when
  /// alpha is within its radius of 1, next to a narrow feature).
  /// \pre alpha is the optimum 1/(1 + sqrt(C/A)) of these A and C (as
  ///      piece_integrals and every refinement of a radical map leave it;
  ///      not a C1 map's alpha); where A or C is not certainly positive, 1 -
  ///      alpha from alpha's ball alone.
  Ball one_minus_alpha(long prec) const;
};

/// The integrals above of s over the piece [a, b].
/// \pre a < b consecutive breakpoints of s (critical_breakpoints or
///      mark_zeros: no zero of sigma inside, the multiplicities of the
///      zeros at the ends marked).
/// \post every ball contains its exact value, the integrals computed to the
///       relative goal 2^-rel_goal_bits; an identically zero speed gives 0
///       and alpha* = 1/2.
/// \throws DomainError when both ends are zeros of sigma; BudgetExceeded
///         when the goal cannot be met within max_prec bits or the
///         thread's TimeBudget.
PieceIntegrals piece_integrals(const Speed& s, const Breakpoint& a, const Breakpoint& b, long rel_goal_bits,
                               long max_prec);

/// int sigma^2 over the piece [a, b] whose integrals are pi (a < b, as
/// piece_integrals): L / Delta t where no zero of sigma ends the piece
/// (rho = Delta t there, so L = Delta t int sigma^2), else its own certified
/// integral of sigma^2 (analytic on the closed piece) at rel_goal_bits: pi's
/// `square` when piece_integrals computed it to at least those bits. The
/// ends of Delta t are taken at rel_goal_bits + 32 bits (no refinement
/// beyond the integrals' own). How radical() and the Moebius methods get
/// u_before without integrating sigma^2 over [0, 1] again.
/// \post contains the integral; BudgetExceeded as piece_integrals.
Ball piece_square_integral(const Speed& s, const Breakpoint& a, const Breakpoint& b, const PieceIntegrals& pi,
                           long rel_goal_bits, long max_prec);

/// piece_integrals of every piece [T_i, T_i+1] of T (size >= 2, else
/// InvalidArgument), the pieces spread over worker_count() threads
/// (core/parallel.hpp; UNIPARAM_THREADS=1 for one thread). Each extra worker
/// gets its own copy of s and T, made before any thread starts (both keep
/// mutable caches), so s and T are only touched by the calling thread.
/// \post out[i] is exactly what piece_integrals(s, T[i], T[i+1], ...) gives;
///       the first exception of any piece is rethrown.
std::vector<PieceIntegrals> all_piece_integrals(const Speed& s, const std::vector<Breakpoint>& T,
                                                long rel_goal_bits, long max_prec);

/// One list of breakpoints and its accuracy goal, for the batched form below.
struct PieceJob {
  std::vector<Breakpoint> T;  ///< size >= 2
  long rel_goal_bits;
};

/// all_piece_integrals of several lists at once: every piece of every job in
/// one parallel loop, so that e.g. two lists of 3 pieces keep two workers
/// busy (3 pieces alone leave one idle half the time). Same copies-per-worker
/// rule as above.
/// \post out[k][i] is exactly what piece_integrals(s, jobs[k].T[i],
///       jobs[k].T[i+1], jobs[k].rel_goal_bits, max_prec) gives; the first
///       exception of any piece is rethrown; InvalidArgument when a job has
///       fewer than two breakpoints.
std::vector<std::vector<PieceIntegrals>> all_piece_integrals(const Speed& s, const std::vector<PieceJob>& jobs,
                                                             long max_prec);

}  // namespace uniparam
