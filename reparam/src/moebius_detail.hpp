// reparam/src/moebius_detail.hpp -- shared internals of the Moebius methods.
#pragma once

#include <memory>
#include <vector>

#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/scaling.hpp"

namespace uniparam::detail {

/// The breakpoints the Moebius methods integrate for T (validated as
/// mark_zeros does: 0 = t_0 < ... < t_N = 1): every piece as if free of
/// zeros (sigma^2 is analytic on each; no radical substitution here).
std::vector<Breakpoint> moebius_breakpoints(const Speed& s, const std::vector<RealAlgebraic>& T);

/// The accuracy goal (bits) of moebius_c0's first round of piece integrals.
long moebius_first_bits(const Options& opt);

/// A UniformityResult with mu alone (mean_speed at digits_to_bits(digits)
/// bits, the uniformity's first goal): moebius_c0 and the C1 construction
/// take only mu and identically_zero from their base; mean_square and u stay
/// indeterminate, and speed_squared empty (the exact sigma^2 is built only
/// when asked for, Speed::squared).
UniformityResult mu_only(const Speed& s, const Options& opt);

/// moebius_c0 for an already built speed and mu (base.mu, from uniformity()
/// or mu_only()), so that callers trying several T compute it once. Same
/// contract. u_before comes from the pieces: every piece is integrated
/// without zeros, so L_i = Delta t_i int sigma^2 over it, and int_0^1
/// sigma^2 = sum L_i / Delta t_i; mu is recomputed at the loop's accuracy
/// where u_before (or u_after) falls short of the digits.
/// `first`, when given, must be all_piece_integrals(s,
/// moebius_breakpoints(s, T), moebius_first_bits(opt), opt.max_prec) (e.g.
/// from a batch with other lists); it replaces the first round's
/// computation, so the result is the same.
MoebiusResult moebius_c0(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T,
                         const Options& opt, const std::vector<PieceIntegrals>* first = nullptr);

/// Phi = sum sqrt M_i of a result's pieces (certified).
Ball phi_of(const MoebiusResult& r, long prec);

/// Certified Phi(T) = sum sqrt M_i to about `bits` relative bits.
Ball certified_phi(const Speed& s, const std::vector<RealAlgebraic>& T, long bits, long max_prec);
/// The same from the piece integrals computed with that goal `bits`.
Ball certified_phi(const std::vector<PieceIntegrals>& integrals, long bits);

/// The C1 data of a piecewise Moebius map with breakpoints T and S: rho_i =
/// dt_i / ds_i, k_i = (1 - alpha_i) / alpha_i from the C1 condition
/// rho_i / k_i = rho_{i+1} k_{i+1} with the free parameter chosen optimally
/// (x = sqrt(Q/P) closes the one-parameter family), each piece's F_i =
/// (k_i A_i + B_i + C_i / k_i) / ds_i (its int sigma_{p o m}^2 ds, with the
/// PieceIntegrals convention of dt_i times the integrals over dt) and u =
/// mu^2 / sum F_i. All certified balls.
struct C1Data {
  std::vector<Ball> rho, k, alpha, F;
  Ball u;
};
C1Data c1_from_pieces(const std::vector<RealAlgebraic>& T, const std::vector<Ball>& S,
                      const std::vector<PieceIntegrals>& I, const Ball& mu, long prec);

/// The balanced curve the methods run on instead of c (scaling.hpp), or
/// null: balance(c) where c's speed s is not identically zero.
std::shared_ptr<const BalancedCurve> balanced_for(const Curve& c, const Speed& s);

/// The working precision that keeps the parameters of m's composition
/// resolvable: that of `digits` twice, plus twice balance_bits.
long balanced_prec(const BalancedCurve& bal, long digits);

/// 1 / (1 + k K), K = (1 - alpha) / alpha: the parameter of the Moebius
/// piece alpha composed with m's local piece k (balance_local_k), without
/// cancellation (1 - alpha of the result keeps its relative accuracy).
Ball compose_alpha(const Ball& alpha, const Ball& k, long prec);

/// rq, a result of the Moebius methods for bal.q, composed with m: the same
/// map described on p (MoebiusResult::balanced), with p's u_before; its balls
/// meet `digits` where rq's meet digits + 1.
MoebiusResult compose_balanced(const std::shared_ptr<const BalancedCurve>& bal, const MoebiusResult& rq,
                               const Ball& u_before, long digits);

}  // namespace uniparam::detail
