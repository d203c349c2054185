// uniparam/reparam/moebius.hpp -- the C0 piecewise Moebius reparameterization
// with fixed breakpoints (ImUp's MoebiusTransformation for N = 1 and
// ReparameterizationN with the breakpoints given; docs/math.md sections 2-3).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/reparam/pieces.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

/// Result of the C0 piecewise Moebius method on fixed breakpoints T. Piece i
/// maps [s_i, s_{i+1}] onto [t_i, t_{i+1}] by the Moebius map (2.1) with
/// parameter integrals[i].alpha; the pieces join continuously (C0).
/// How the pieces of a piecewise Moebius map join.
enum class Continuity { C0, C1 };
/// "C0" / "C1".
const char* to_string(Continuity c);

struct MoebiusResult {
  SpeedKind kind;
  Continuity continuity = Continuity::C0;
  /// t_0 = 0 < ... < t_N = 1 exactly as given. Every multiplicity is 0: the
  /// rational method integrates every piece without radical ends, even where
  /// sigma vanishes at a breakpoint (see speed_vanishes).
  std::vector<Breakpoint> T;
  /// Per piece [t_i, t_{i+1}], ZeroSide::None: A, B, C = Delta t_i times
  /// ImUp's A_i, B_i, C_i; L = A + B + C; M = B + 2 sqrt(A C) (ImUp's M_i);
  /// alpha = 1 / (1 + sqrt(C / A)), the optimal Moebius parameter (2.2).
  std::vector<PieceIntegrals> integrals;
  /// s_0 = 0 < ... < s_N = 1: s_i = sum_{k<i} sqrt M_k / sum_k sqrt M_k (3.1).
  /// For an identically zero speed, s_i = t_i (r = id).
  std::vector<Ball> S;
  /// The Moebius parameter of each piece as used by the map: integrals[i].alpha
  /// for C0 (optimal per piece), the C1-constrained optimum for C1.
  std::vector<Ball> alpha;
  Ball mu;        ///< int_0^1 sigma (invariant under reparameterization)
  Ball u_before;  ///< u(p)
  Ball u_after;   ///< u(p o r) = mu^2 / (sum sqrt M)^2 (1 when identically_zero)
  bool identically_zero = false;  ///< angular speed of a line: u = 1, alpha = 1/2, r = id
  /// True when sigma has a zero in [0, 1] (Speed::zeros() not empty). Rational
  /// pieces cannot lift such a zero (docs/math.md section 3): the result is still
  /// the optimal C0 piecewise Moebius map for T, but u_after stays below 1.
  bool speed_vanishes = false;

  /// How reparam_c0's local optimiser over T ended (reparam_c0 sets it).
  struct Optimiser {
    long iterations = 0;
    Ball phi_equal;   ///< Phi = sum sqrt M_i at the equally spaced T (certified)
    Ball phi;         ///< Phi at the returned T (certified); never certainly above phi_equal
    /// max_j |dPhi/dt_j| * (t_{j+1} - t_{j-1}) / Phi at the returned T: a
    /// relative measure of how far from stationary the optimiser stopped
    /// (floating point, uncertified, for information).
    double stationarity = 0;
  };
  /// Set by reparam_c0 only.
  std::optional<Optimiser> optimiser;

  /// reparam_c1's target uniformity and whether u_after >= target is
  /// certified (u_after's lower bound is at least the target).
  struct Target {
    Rational value;
    bool reached = false;
    long rounds = 0;  ///< refinement rounds of T after the first construction
    /// The floating-point draft that chooses the breakpoints broke down
    /// (integrals beyond double's range, e.g. a huge coefficient), so the
    /// refinement stopped early; the map is still certified.
    bool draft_failed = false;
  };
  /// Set by reparam_c1 only.
  std::optional<Target> target;

  /// The exact rational data of the map: breakpoints T (t_0..t_N), joints S
  /// (s_0..s_N) and the Moebius parameter alpha of each piece.
  struct Exact {
    std::vector<Rational> T, S, alpha;
  };
  /// Set by make_rational only: r has exactly these data, and every Ball
  /// above describes this exact map.
  std::optional<Exact> exact;

  /// Set when p's weights grow geometrically (balance(p) not empty,
  /// scaling.hpp): the method ran on the balanced curve q = p o m, and this
  /// result is its map r_q composed with m exactly, r = m o r_q, described
  /// on p like any other: T = m(T_q) (exact), S the same, each piece's
  /// alpha = 1 / (1 + k K) with K = (1 - alpha_q) / alpha_q and k m's local
  /// parameter on the piece (balance_local_k; alpha is held with
  /// balance_bits extra bits so that 1 - alpha stays resolvable), the
  /// integrals A / k, B, k C (L = A + B + C, M the same), so p o r = q o r_q
  /// and u_after, mu and Phi are q's; u_before is p's (uniformity()). With
  /// exact data, exact->T and exact->alpha are m's exact images of q's
  /// rounded data. The optimiser's phi_equal and stationarity, and a C1 result's
  /// choices, refer to q's parameter. balanced->on is r_q, from which
  /// make_rational and refine_moebius_data work (then compose again).
  struct Balanced {
    std::shared_ptr<const BalancedCurve> curve;  ///< q = p o m, with m's a and b
    std::shared_ptr<const MoebiusResult> on;     ///< r_q, the map on q
  };
  /// Empty unless p's weights grow geometrically (see above).
  std::optional<Balanced> balanced;

  std::size_t pieces() const { return T.size() - 1; }
};

/// The optimal C0 piecewise Moebius reparameterization for the fixed
/// breakpoints T (in t): on each piece the optimal alpha_i of (2.2), and the
/// optimal S of (3.1).
/// \pre T = (0 = t_0 < t_1 < ... < t_N = 1), N >= 1 (checked).
/// \post T of the result is the given T (multiplicities 0); every Ball of the
///       result (mu, u_before, u_after, S, and each piece's A, B, C, L, M,
///       alpha) contains the true value and meets Options::digits;
///       u_after >= u_before mathematically (the Moebius map with alpha = 1/2
///       and s_i = t_i is the identity, and the result is optimal).
/// \throws InvalidArgument for a bad T or bad options; DomainError for a
///         non-regular curve or a speed infinite in [0, 1]; BudgetExceeded
///         for a curve above Options::max_degree, or if the accuracy cannot be
///         reached within Options::max_prec or the thread's TimeBudget.
MoebiusResult moebius_c0(const Curve& c, SpeedKind kind, const std::vector<RealAlgebraic>& T,
                         const Options& opt = {});

/// The single optimal Moebius transformation (N = 1): moebius_c0 with
/// T = (0, 1). Same contract.
MoebiusResult moebius_optimal(const Curve& c, SpeedKind kind, const Options& opt = {});

/// ImUp's ReparameterizationN: the C0 piecewise Moebius map with N pieces,
/// its breakpoints T chosen by a local optimiser of Phi(T) = sum sqrt M_i
/// started from the equally spaced T, then the optimal alpha and S for that T.
/// \pre 1 <= N <= 1000 (checked: InvalidArgument).
/// \post as moebius_c0 for the returned T (rational breakpoints); u_after is
///       at least the u_after of the equally spaced T up to the balls' radii;
///       optimiser is set.
/// \throws as moebius_c0.
MoebiusResult reparam_c0(const Curve& c, SpeedKind kind, long N, const Options& opt = {});

/// ImUp's ReparameterizationU: a C1 piecewise Moebius map. T starts as 0,
/// the zeros of sigma' in (0, 1), and 1; S_i = int_0^{t_i} sigma / mu; the
/// alpha_i satisfy the C1 condition at every joint,
///     (dt_i / ds_i) alpha_i / (1 - alpha_i) = (dt_{i+1} / ds_{i+1}) (1 - alpha_{i+1}) / alpha_{i+1},
/// with the one free parameter chosen to minimise int sigma_{p o m}^2. While
/// u < target and pieces remain, T is refined by the roots of
/// sigma' dt_i [alpha_i t~ + (1 - alpha_i)(1 - t~)] - 2 sigma (1 - 2 alpha_i)
/// on each piece (the critical points of the reparameterized speed); when
/// that adds nothing, the piece with the largest excess is bisected.
/// \pre 0 < target < 1, 1 <= max_pieces <= 1000 (checked: InvalidArgument).
/// \post continuity == C1; target is set; the result is the best map found
///       (largest u); target->reached iff u_after >= target is certified.
///       The balls meet Options::digits. Not reaching the target is not an
///       error here: callers decide (the CLI exits with status 4).
/// \throws as moebius_c0.
MoebiusResult reparam_c1(const Curve& c, SpeedKind kind, const Rational& target, const Options& opt = {},
                         long max_pieces = 64);

namespace detail {

/// Test hook, not part of the public API: what reparam_c1's refinement
/// rounds chose. Everything here comes from the UNCERTIFIED floating-point
/// draft (the choices), nothing in it is certified.
struct C1Trace {
  /// One round: its T and the draft's (double, uncertified) alpha per piece.
  struct Round {
    std::vector<RealAlgebraic> T;
    std::vector<double> alpha;
  };
  /// A breakpoint added by the slides' rule (not by the bisection fallback):
  /// in round `round`, the root `t` of the slides' equation
  ///   sigma' (b - a) [alpha t~ + (1 - alpha)(1 - t~)] - 2 sigma (1 - 2 alpha) = 0,
  /// t~ = (t - a) / (b - a), on the piece [a, b] = [T_piece, T_piece+1] of that
  /// round's T, with the rational `alpha` the rule used (the draft's alpha
  /// rounded to within 10^-12).
  struct SlidesBreakpoint {
    std::size_t round = 0, piece = 0;
    RealAlgebraic a, b;
    Rational alpha;
    Rational t;
  };
  std::vector<Round> rounds;
  std::vector<SlidesBreakpoint> slides;
  std::vector<Rational> bisections;  ///< breakpoints added by the fallback rule
};

/// reparam_c1 recording its refinement in *trace (if non-null; cleared
/// first). Same contract, same result as reparam_c1. For a balanced curve
/// (MoebiusResult::balanced) the rounds are those on q, in q's parameter.
MoebiusResult reparam_c1_traced(const Curve& c, SpeedKind kind, const Rational& target, const Options& opt,
                                long max_pieces, C1Trace* trace);

}  // namespace detail

/// Exact rational output: rounds T, S and the alphas of r to the simplest
/// rationals within the relative accuracy tol = 10^-rational_digits and
/// certifies the u of *that* map, which has rational coefficients. T and S:
/// within tol times the smaller neighbouring gap. T is rounded when a method
/// chose it (reparam_c0, reparam_c1); rational breakpoints given to
/// moebius_c0 stay exact (irrational ones are rounded). C0: each alpha is the
/// simplest rational certainly within tol * min(alpha, 1 - alpha) of the
/// optimal alpha of r's T (its ball refined until that window is certain), so
/// 0 < alpha < 1 however close alpha is to 0 or 1. C1: the free parameter
/// k_0 > 0 rounded within tol * k_0 the same way, the other alphas solved
/// exactly from the C1 condition on the rational T and S, so r' is
/// continuous exactly. For a balanced result (r.balanced) all this happens
/// on r.balanced->on and q, and the rounded map is composed with m exactly:
/// exact->T = m(T_q rounded), exact->alpha from alpha_q rounded with one more
/// digit (the T and S windows hold in q's parameter; composing with m keeps
/// the map exact, C1 where r_q is, and alpha within tol * min(alpha,
/// 1 - alpha), within twice that for rational_digits = 100).
/// \pre r was computed for c; 1 <= rational_digits <= 100 (InvalidArgument).
/// \post exact is set: exact->T, exact->S, exact->alpha are the map's data;
///       T, S, alpha, integrals and u_after describe that exact map (u_after
///       meets Options::digits); target->reached re-checked (if target is
///       set); optimiser->phi is cleared (it described the unrounded map).
/// \throws as moebius_c0 (BudgetExceeded also when alpha or k_0 cannot be
///         certified to the relative accuracy within Options::max_prec).
MoebiusResult make_rational(const Curve& c, const MoebiusResult& r, long rational_digits = 8,
                            const Options& opt = {});

/// The same map r with its data recomputed to `digits`: S and alpha (and the
/// integrals) meet `digits`. The map is the one r's method defines for r's
/// breakpoints: for C0 the optimal alpha and S (moebius_c0), for C1 the S of
/// the arc length and the C1 optimum (reparam_c1), for an exact rational map
/// (exact set) its exact S and alpha as balls of matching precision; so
/// each refined ball lies in r's (up to rounding) and meets `digits`. Every
/// other field is kept; an identically zero map is returned as is.
/// A balanced result (r.balanced) refines r.balanced->on on q's speed and
/// composes it with m again.
/// \pre r was computed for the speed sp (not checkable); digits >= 1
///      (InvalidArgument).
/// \throws BudgetExceeded when `digits` cannot be met within max_prec bits or
///         the thread's TimeBudget.
MoebiusResult refine_moebius_data(const Speed& sp, const MoebiusResult& r, long digits, long max_prec);

/// Evaluation of a piecewise Moebius map (the overloads for a RadicalResult
/// are in radical.hpp).
/// Enclosure of r(s) for s in [0, 1] (a real ball; where s overlaps a joint
/// s_i, the union of both pieces' values). An exact s equal to an exact joint
/// s_i (s = 0, s = 1) gives t_i's ball, exact for a dyadic t_i: r(0) = 0 and
/// r(1) = 1 exactly. The accuracy is limited by r's data (S, alpha: balls);
/// see Reparameterization::refined. InvalidArgument if s misses [0, 1].
Ball eval_r(const MoebiusResult& r, const Ball& s, long prec);
/// Enclosure of r'(s) (the union of one-sided values at a C0 joint).
/// InvalidArgument if s misses [0, 1].
Ball eval_dr(const MoebiusResult& r, const Ball& s, long prec);
/// Enclosure of sigma_{p o r}(s) = sigma_p(r(s)) r'(s); `sp` must be the speed
/// r was computed for (not checkable). InvalidArgument if s misses [0, 1].
Ball eval_speed(const MoebiusResult& r, const Speed& sp, const Ball& s, long prec);
/// Enclosures of the components of p(r(s)) (c must be the curve of r); for
/// a balanced r, evaluated as q(r_q(s)), the same point. InvalidArgument if
/// s misses [0, 1].
std::vector<Ball> eval_point(const Curve& c, const MoebiusResult& r, const Ball& s, long prec);

}  // namespace uniparam
