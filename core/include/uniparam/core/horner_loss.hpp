// uniparam/core/horner_loss.hpp -- the one estimate of the bits Horner's
// rule loses to cancellation on a polynomial's power basis over an interval.
#pragma once

#include "uniparam/core/poly.hpp"

namespace uniparam {

/// UNCERTIFIED estimate, for choosing a path only (never for a reported
/// number): the most, over p^(j) for j = 0 .. max_order, of
///     log2( sum_k |c_k| / max_i |p^(j)(t_i)| ),
/// where c_k are the coefficients of p^(j) and t_i = lo + i (hi - lo) / 32,
/// i = 0 .. 32, in IEEE double on scaled_doubles(p) (the common power-of-2
/// scale cancels in the ratio), the derivatives' coefficients formed in
/// double. For |t| <= 1 the sum bounds every partial sum of Horner's rule,
/// so this is about how far the values sit below the coefficients (the
/// Bezier curves' power bases lose ~10 bits from degree 12, dense random
/// coefficients ~2).
/// \pre p != 0 (InvalidArgument), 0 <= max_order <= 2 (InvalidArgument),
///      lo < hi finite.
/// \post >= 0 up to rounding; +infinity when some p^(j) (j <= max_order,
///       not identically 0) vanishes on every t_i or a sum is not finite.
double horner_loss_bits(const Poly& p, double lo, double hi, int max_order);

}  // namespace uniparam
