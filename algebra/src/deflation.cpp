// Exact removal of a known root: multiplicity test by gcds and exact
// divisions, deflation by synthetic division in ball arithmetic.
#include "uniparam/algebra/deflation.hpp"

#include <arb_poly.h>

#include <string>
#include <vector>

#include "root_refine.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

int root_multiplicity(const Poly& p, const RealAlgebraic& gamma) {
  if (p.is_zero()) throw InvalidArgument("root_multiplicity: the zero polynomial has every root");
  if (gamma.is_rational()) {
    // By Gauss's lemma the primitive d*t - n divides p in Z[t] iff p(n/d) = 0.
    const Poly& lin = gamma.poly();
    Poly q(p);
    int m = 0;
    for (;;) {
      Poly r;  // not aliased with q: fmpz_poly_divides zeroes r on failure
      if (q.degree() < 1 || !fmpz_poly_divides(r.get(), q.get(), lin.get())) return m;
      q = std::move(r);
      ++m;
    }
  }
  // h collects the factors of p shared with gamma's polynomial; each round
  // divides q by the squarefree g = gcd(q, h), removing one copy of every
  // irreducible factor in g. gamma is a root of g iff g changes sign on
  // (lo, hi) (g divides gamma.poly(), so lo and hi are not roots of g and g
  // has at most one simple root there).
  const Poly h = gcd(p, gamma.poly());
  Poly q(p);
  int m = 0;
  for (;;) {
    const Poly g = gcd(q, h);
    if (g.degree() < 1) return m;
    if (detail::exact_sign(g, gamma.lo()) == detail::exact_sign(g, gamma.hi())) return m;
    q = divexact(q, g);
    ++m;
  }
}

BallPoly deflate(const Poly& p, const RealAlgebraic& gamma, int k, long prec) {
  if (k < 0) throw InvalidArgument("deflate: negative multiplicity " + std::to_string(k));
  if (prec < 2) throw InvalidArgument("deflate: precision must be at least 2 bits");
  if (p.is_zero() || k == 0) return BallPoly(p);
  const int m = root_multiplicity(p, gamma);
  if (m < k)
    throw DomainError("deflate: " + gamma.str() + " is a root of multiplicity " + std::to_string(m) + " of " +
                      p.str() + ", cannot divide by (t - gamma)^" + std::to_string(k));
  if (gamma.is_rational()) {
    // Exact: p / (t - n/d)^k = d^k p / (d t - n)^k.
    const Poly& lin = gamma.poly();
    const Poly q = divexact(p, lin.pow(static_cast<unsigned long>(k)));
    return BallPoly(q * Poly(std::vector<Integer>{lin.leading()}).pow(static_cast<unsigned long>(k)));
  }
  // The quotient's coefficients are polynomials in gamma of degree <= deg p
  // with integer coefficients; extra bits absorb the growth of the enclosure
  // radius through k nested Horner recursions.
  const long n = p.degree();
  const long margin = 32 + static_cast<long>(k) * (2 * static_cast<long>(FLINT_BIT_COUNT(n)) + 4);
  const long wp = prec + margin;
  const Ball g = gamma.to_ball(wp);
  BallPoly cur(p);
  for (int j = 0; j < k; ++j) {
    const slong len = arb_poly_length(cur.get());  // >= 2: gamma is a root
    BallPoly next;
    arb_poly_fit_length(next.get(), len - 1);
    arb_ptr b = next.get()->coeffs;
    arb_srcptr a = cur.get()->coeffs;
    // a(t) = (t - gamma) b(t) + r: b_{len-2} = a_{len-1}, b_{i-1} = a_i + gamma b_i.
    arb_set(b + len - 2, a + len - 1);
    for (slong i = len - 2; i >= 1; --i) {
      arb_mul(b + i - 1, b + i, g.get(), wp);
      arb_add(b + i - 1, b + i - 1, a + i, wp);
    }
    _arb_poly_set_length(next.get(), len - 1);
    _arb_poly_normalise(next.get());
    cur = std::move(next);
  }
  return cur;
}

}  // namespace uniparam
