#include "uniparam/algebra/squarefree.hpp"

#include <flint/fmpz_poly_factor.h>

#include <algorithm>

#include "uniparam/core/error.hpp"

namespace uniparam {

SquarefreeFactorization squarefree_factorization(const Poly& p) {
  SquarefreeFactorization out;
  if (p.is_zero()) return out;  // content 0, no factors
  fmpz_poly_factor_t fac;
  fmpz_poly_factor_init(fac);
  fmpz_poly_factor_squarefree(fac, p.get());
  out.content = Integer(&fac->c);
  for (slong i = 0; i < fac->num; ++i) {
    Poly f(fac->p + i);
    if (f.degree() < 1) continue;
    Integer lc = f.leading();
    if (lc.sign() < 0) {  // keep p = content * prod f^m with positive leading coefficients
      f = -f;
      if (fac->exp[i] % 2 == 1) fmpz_neg(out.content.get(), out.content.get());
    }
    out.factors.push_back({std::move(f), static_cast<int>(fac->exp[i])});
  }
  fmpz_poly_factor_clear(fac);
  std::sort(out.factors.begin(), out.factors.end(), [](const SquarefreeFactor& a, const SquarefreeFactor& b) {
    return a.multiplicity != b.multiplicity ? a.multiplicity < b.multiplicity : a.factor.degree() < b.factor.degree();
  });
  return out;
}

Poly squarefree_part(const Poly& p) {
  if (p.is_zero()) throw DomainError("the squarefree part of the zero polynomial is undefined");
  Poly r(1);
  for (const auto& f : squarefree_factorization(p).factors) r = r * f.factor;
  return r;
}

}  // namespace uniparam
