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

/// UNCERTIFIED estimate of the bits Horner's rule loses on p's power basis
/// over [0, 1]: horner_loss_bits(p, 0, 1, 0) (core/horner_loss.hpp; log2
/// of sum |a_k| over the largest |p| on 33 points of [0, 1], infinity when
/// p vanishes at all of them). A choice of basis only.
/// \pre p is not the zero polynomial (InvalidArgument otherwise).
double power_basis_loss(const Poly& p);

/// UNCERTIFIED: approximate_complex_roots of the centred and scaled
/// q(s) = 2^n p((1 + s) / 2) (exact integers, n = deg p; its roots are
/// s = 2t - 1 for p's roots t), mapped back to t = (1 + s) / 2: the roots
/// near [0, 1] as q's power basis sees them near [-1, 1], where Horner's
/// rule on it often loses far fewer bits than p's on [0, 1] (a Bezier
/// curve's power basis loses ~n bits there: its coefficients are binomials
/// of alternating signs). *loss (when given) is the estimate that decides:
/// log2 of sum |q_k| over the largest |q| on 33 points of [-1, 1], in
/// double (power_basis_loss's on q and [-1, 1]). The iteration settles a
/// root also once its correction is below 2^-12 of its distance from
/// [0, 1]: roots far out, where the centred basis is not made for them, may
/// never reach the 2^-30 of approximate_complex_roots.
/// \pre p is not the zero polynomial (InvalidArgument otherwise).
/// \post empty when that estimate exceeds max_loss (the roots would be
///       only as good as Horner's rule there, which misleads more than it
///       helps), else as approximate_complex_roots (out.size() == deg p, or
///       empty). Deterministic.
std::vector<std::complex<double>> approximate_roots_near_unit_interval(const Poly& p, double max_loss,
                                                                       double* loss = nullptr,
                                                                       bool* converged = nullptr);

}  // namespace uniparam
