// uniparam/algebra/deflation.hpp -- exact removal of a known root
// (docs/math.md section 4; Hong, Wang, Yang 2023, section 5).
#pragma once

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// q = p / (t - gamma)^k with ball coefficients, by k synthetic divisions:
/// q's coefficients are polynomials in gamma with integer coefficients
/// (no division at all), evaluated on an enclosure of gamma at `prec` bits.
/// \pre gamma is a root of p of multiplicity >= k >= 0 (checked exactly;
///      DomainError otherwise).
/// \post for every t, q(t) * (t - gamma)^k == p(t): the balls contain the
///       coefficients of the exact quotient.
BallPoly deflate(const Poly& p, const RealAlgebraic& gamma, int k, long prec);

/// Multiplicity of gamma as a root of p (0 if not a root), exact. \pre p != 0.
int root_multiplicity(const Poly& p, const RealAlgebraic& gamma);

}  // namespace uniparam
