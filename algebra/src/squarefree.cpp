#include "uniparam/algebra/squarefree.hpp"

#include <flint/fmpz_poly_factor.h>
#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include <algorithm>

#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

/// Degree from which squarefree_factorization tries provably_squarefree
/// first: below, FLINT's gcd over Z costs less than the modular test.
constexpr long kModularTestDegree = 48;

}  // namespace

bool provably_squarefree(const Poly& p) {
  if (p.degree() < 1) return false;
  ulong q = UWORD(1) << 62;
  for (int tries = 0; tries < 3; ++tries) {
    q = n_nextprime(q, 1);
    if (fmpz_fdiv_ui(p.get()->coeffs + p.degree(), q) == 0) continue;
    nmod_poly_t f, df, g;
    nmod_poly_init(f, q);
    nmod_poly_init(df, q);
    nmod_poly_init(g, q);
    fmpz_poly_get_nmod_poly(f, p.get());
    nmod_poly_derivative(df, f);
    nmod_poly_gcd(g, f, df);
    const bool one = nmod_poly_degree(g) == 0;
    nmod_poly_clear(f);
    nmod_poly_clear(df);
    nmod_poly_clear(g);
    if (one) return true;
  }
  return false;
}

SquarefreeFactorization squarefree_factorization(const Poly& p) {
  SquarefreeFactorization out;
  if (p.is_zero()) return out;  // content 0, no factors
  if (p.degree() >= kModularTestDegree && provably_squarefree(p)) {
    // p = content * primitive part, one factor of multiplicity 1 (the gcd
    // over Z, which dominated the isolation of high-degree critical
    // numerators, is not needed)
    fmpz_poly_content(out.content.get(), p.get());
    Poly f;
    fmpz_poly_scalar_divexact_fmpz(f.get(), p.get(), out.content.get());
    if (f.leading().sign() < 0) {
      f = -f;
      fmpz_neg(out.content.get(), out.content.get());
    }
    out.factors.push_back({std::move(f), 1});
    return out;
  }
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
