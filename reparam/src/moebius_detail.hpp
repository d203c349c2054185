// reparam/src/moebius_detail.hpp -- shared internals of the Moebius methods.
#pragma once

#include <vector>

#include "uniparam/reparam/moebius.hpp"

namespace uniparam::detail {

/// moebius_c0 for an already built speed and its uniformity (mu, u_before),
/// so that callers trying several T compute them once. Same contract.
MoebiusResult moebius_c0(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T,
                         const Options& opt);

/// Phi = sum sqrt M_i of a result's pieces (certified).
Ball phi_of(const MoebiusResult& r, long prec);

/// Certified Phi(T) = sum sqrt M_i to about `bits` relative bits.
Ball certified_phi(const Speed& s, const std::vector<RealAlgebraic>& T, long bits, long max_prec);

}  // namespace uniparam::detail
