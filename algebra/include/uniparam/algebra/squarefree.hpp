// uniparam/algebra/squarefree.hpp -- squarefree factorisation over Z.
#pragma once

#include <vector>

#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

struct SquarefreeFactor {
  Poly factor;       ///< primitive, positive leading coefficient, degree >= 1, squarefree
  int multiplicity;  ///< >= 1
};

/// p = unit_content * prod factor_i ^ multiplicity_i.
struct SquarefreeFactorization {
  Integer content;                        ///< signed integer content of p (0 iff p = 0)
  std::vector<SquarefreeFactor> factors;  ///< pairwise coprime; sorted by multiplicity, then degree
};

/// True when p (degree >= 1) is proven squarefree: gcd(p, p') = 1 modulo a
/// prime q (one of three near 2^62) not dividing lc(p). (A primitive common
/// factor h over Z has lc(h) | lc(p), so it keeps its degree modulo q and
/// divides both there.) False means unknown, or p constant.
bool provably_squarefree(const Poly& p);

/// Squarefree factorisation of p (p itself, made primitive, when
/// provably_squarefree(p); FLINT's otherwise).
/// \post content * prod f_i^{m_i} == p exactly; the f_i are squarefree,
///       pairwise coprime, primitive, with positive leading coefficient, and
///       the multiplicities are distinct (one factor per multiplicity).
/// p = 0 gives content 0 and no factors; a constant gives no factors.
SquarefreeFactorization squarefree_factorization(const Poly& p);

/// The product of the distinct factors (primitive, positive leading
/// coefficient); 1 for a nonzero constant. \pre p != 0 (DomainError otherwise).
Poly squarefree_part(const Poly& p);

}  // namespace uniparam
