// uniparam/algebra/approx_roots.hpp -- UNCERTIFIED approximations of all
// complex roots of an integer polynomial, in IEEE double. For choices only
// (e.g. which error bounds the quadrature tries first, near the integrand's
// singularities), never for a reported number: nothing here is proven.
#pragma once

#include <complex>
#include <vector>

#include "uniparam/core/poly.hpp"

namespace uniparam {

/// UNCERTIFIED: approximations of the complex roots of p, with
/// multiplicity, by the Aberth-Ehrlich iteration in IEEE double on p's
/// coefficients scaled to double range (Horner's rule on p for |z| <= 1, on
/// its reversal beyond). Roots at 0 (p's trailing zero coefficients) are
/// returned exactly.
/// \pre p is not the zero polynomial (InvalidArgument otherwise).
/// \post out.size() == p.degree(), or out is empty when the scaled
///       coefficients do not fit a double (the leading or the lowest nonzero
///       coefficient underflows after scaling to the largest) or the iteration produced a non-finite number: the
///       caller must always accept having no approximations. *converged
///       (when given) is true when every root settled within max_sweeps
///       sweeps (its last correction below 2^-30 max(|z|, 1)). Settled,
///       well separated roots are typically accurate to 1e-9 relative to
///       the cancellation of Horner's rule at them; clusters and multiple
///       roots (which may not settle) to about the multiplicity-th root of
///       that. Deterministic: the same p gives the same doubles.
/// Costs O(degree^2) per sweep: meant for degrees up to a few hundred.
std::vector<std::complex<double>> approximate_complex_roots(const Poly& p, bool* converged = nullptr,
                                                            int max_sweeps = 60);

}  // namespace uniparam
