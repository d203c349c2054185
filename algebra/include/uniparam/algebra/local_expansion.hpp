// uniparam/algebra/local_expansion.hpp -- truncated local Taylor expansions
// of an exact integer polynomial at the centres of the dyadic cells of
// [0, 1], with rigorous bounds of the dropped tail.
//
// The one expansion engine of the algebra layer: LocalPoly's cached cells
// (local_poly.hpp: evaluation on balls) and the certified ball subdivision
// of the real-root isolation (root_subdivision.cpp) both build, shift and
// truncate their expansions here. It depends on core/ only (no
// RealAlgebraic), so root isolation can use it; deflation by a root takes
// an enclosure of the root.
//
// Why: the power-basis coefficients of a high-degree polynomial on [0, 1]
// (a Bezier curve of degree 150 has coefficients near 2^150 times its
// values) cancel; an expansion at a nearby dyadic centre has coefficients
// of the size of the polynomial's values there, and away from its complex
// zeros only K << n terms matter.
#pragma once

#include <arb_poly.h>

#include "uniparam/core/poly.hpp"

namespace uniparam {

/// Deepest level of the dyadic cells (cells of width 2^-kMaxExpansionLevel).
constexpr int kMaxExpansionLevel = 48;

/// An expansion of a polynomial G at the centre c = (2j + 1) 2^-(level+1) of
/// the dyadic cell [j 2^-level, (j + 1) 2^-level] of [0, 1] (half-width
/// h = 2^-(level+1)): G(c + w) = P(w) + T(w), where the coefficients of P are
/// balls and |T^(i)(w)| <= tail[i] (i = 0, 1, 2) for |w| <= rho, the radius
/// that its maker chose (truncate_local_expansion's log2_rho; LocalPoly
/// 2h, the subdivision h). Zero tails: P's balls contain G's exact Taylor
/// coefficients at c.
struct LocalExpansion {
  int level = 0;
  unsigned long long j = 0;
  arf_t centre;
  arb_poly_t P;
  mag_struct tail[3];
  LocalExpansion();
  ~LocalExpansion();
  LocalExpansion(const LocalExpansion&) = delete;
  LocalExpansion& operator=(const LocalExpansion&) = delete;
};

/// The exact expansion of G at the cell (level, j), scaled to integers:
/// s(x) = 2^(L n) G((J + x) / 2^L) with L = level + 1, J = 2j + 1 and
/// n = deg G, so that G(c + w) = 2^(-L n) s(2^L w) (one exact Taylor shift
/// of n^2 operations on integers of about (level + 1) n bits).
/// \pre 0 <= level <= kMaxExpansionLevel, j < 2^level (InvalidArgument
///      otherwise). The zero polynomial gives 0.
Poly local_shift_exact(const Poly& G, int level, unsigned long long j);

/// Sets e to the expansion of G at the cell (level, j) from
/// s = local_shift_exact(G, level, j) and n = deg G: each coefficient
/// s_k 2^(L (k - n)) rounded to wp bits (a ball containing the exact one),
/// zero tails. \pre as local_shift_exact, and s is its result for G.
void set_local_expansion(LocalExpansion& e, const Poly& s, long n, int level, unsigned long long j, long wp);

/// Both steps: e = G's expansion at the cell (level, j), coefficients
/// rounded to wp bits, zero tails. \pre as local_shift_exact.
void local_expansion_exact(LocalExpansion& e, const Poly& G, int level, unsigned long long j, long wp);

/// The expansion of the child cell (parent.level + 1, 2 parent.j + (side >
/// 0)) from its parent's: P rounded to wp bits and shifted by side
/// 2^-(level+2) (taylor_shift_pow2), the parent's tails kept (the child's
/// disc |t - c'| <= r/2 lies in the parent's |t - c| <= r, so the bounds,
/// valid for rho <= r/2 in the child, still hold). \pre side = +-1,
/// parent.level < kMaxExpansionLevel (InvalidArgument). child may not be
/// parent.
void local_expansion_child(LocalExpansion& child, const LocalExpansion& parent, int side, long wp);

/// Drops the highest terms of e.P (k >= orders) while their contributions
/// sum_{k >= K} k!/(k-i)! |c_k| rho^(k-i) to the i-th derivative on the disc
/// |w| <= rho = 2^log2_rho, times rho^i, stay at most eps for every
/// i < orders, and adds those sums to tail[i]. Keeps at least `orders`
/// terms. \pre orders is 2 or 3 (InvalidArgument).
/// \post G(c + w) = P(w) + T(w) with the tails bounding T^(i) on |w| <= rho
///       (as before, plus the dropped terms).
void truncate_local_expansion(LocalExpansion& e, long log2_rho, const mag_t eps, int orders);

/// Upper bounds var0 = sum_{k >= 1} |c_k| r^k and (when non-null) var1 =
/// sum_{k >= 2} k |c_k| r^(k-1) of e.P on |w| <= r = 2^log2_r: with c_0 and
/// c_1, the centred-form bounds of P - c_0 and P' - c_1 there.
void local_expansion_variation(mag_t var0, mag_t var1, const LocalExpansion& e, long log2_r);

/// Deflation in the local basis: for a root gamma of the expanded polynomial
/// G with zero tails, replaces P by Q with P(w) = (w - (gamma - c)) Q(w) +
/// remainder, by synthetic division from the top at wp bits by an
/// enclosure of gamma - c (gamma's enclosure minus the centre at wp + 32
/// bits); the remainder, exactly 0 for exact coefficients, is dropped. Q's
/// balls then contain the Taylor coefficients of G(t) / (t - gamma) at c.
/// Stable for gamma within the cell's disc.
/// \pre gamma (a ball) contains a root of G; e has zero tails and is not
///      truncated (an exact expansion).
void deflate_local_expansion(LocalExpansion& e, const arb_t gamma, long wp);

}  // namespace uniparam
