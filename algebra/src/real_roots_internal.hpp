// Private to the algebra layer (not installed): the pieces the real-root
// isolation's files share. real_roots.cpp drives them; descartes.cpp holds
// the exact isolation (Descartes' rule with bisection), root_subdivision.cpp
// the certified ball subdivisions, root_refine.cpp the refinement.
#pragma once

#include <arb.h>

#include <vector>

#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/arb_holders.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::detail {

/// d*t - n for q = n/d.
Poly linear_poly(const Rational& q);

/// Bits of a lower bound of the root separation of a squarefree g of degree n
/// (Mahler): sep > sqrt(3) n^(-(n+2)/2) ||g||_2^(1-n).
long separation_bits(const Poly& g);

/// True when f (degree >= 2) provably has no rational root: for some prime
/// p not dividing lc(f), f mod p has no root in F_p (a root n/d of f, with
/// d | lc(f), would reduce to one). A few primes; false means "unknown".
bool provably_no_rational_root(const Poly& f);

/// The open interval (c/2^k, (c+1)/2^k) of [0, 1].
struct DyadicCell {
  Integer c;
  long k;
};

/// A node of the exact isolation: G on `cell` mapped to (0, 1).
struct Node {
  Poly P;  ///< 2^(k n) G((c + x) / 2^k) up to a positive power of 2
  DyadicCell cell;
};

/// Sign variations (capped at 2) of (x+1)^n P(1/(x+1)), whose positive roots
/// are the roots of P in (0, 1); also sets the sign of P(1), its constant
/// term, when the result is 0 or 1 (the callers use it then only). In IEEE
/// double with certified error bounds first, exact where those cannot decide.
int descartes_bound(const Poly& P, int& sign_at_1);

/// Vincent-Collins-Akritas on the cell start.cell of [0, 1] for a squarefree
/// G, from start.P = 2^(k n) G((c + x) / 2^k) up to a positive factor (roots
/// at the cell's ends are not reported). Appends cells holding exactly one
/// root, whose ends are not roots (leaves), and dyadic roots met as
/// bisection midpoints (exact). BudgetExceeded past its depth and node caps.
void vca_from(const Poly& G, Node start, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact);

/// vca_from on the whole of (0, 1).
void vca(const Poly& G, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact);

/// 2^(k n) G((c + x) / 2^k) exactly: G on the cell (c/2^k, (c+1)/2^k) mapped to (0, 1).
Poly cell_poly(const Poly& G, const DyadicCell& cell);

/// Certified subdivision of [0, 1] for a squarefree G of degree >= 2 on its
/// local expansions (roots at 0 and 1 are not reported: the caller tests
/// them). Appends cells holding exactly one root with non-root ends
/// (leaves), dyadic roots met as cell ends (exact), and cells it could not
/// decide within its depth and cell budgets (undecided: for the exact VCA;
/// their ends are not roots).
void subdivide(const Poly& G, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact,
               std::vector<DyadicCell>& undecided);

/// Below this degree the exact VCA is faster than the subdivision (measured
/// on random dense and Bernstein polynomials of degree 20..400).
constexpr long kSubdivisionDegree = 300;

inline bool use_subdivision(const Poly& G, RootIsolationMethod method) {
  if (G.degree() < 2 || method == RootIsolationMethod::Exact) return false;
  return method == RootIsolationMethod::Subdivision || G.degree() >= kSubdivisionDegree;
}

/// A root being assembled: exact (lo == hi) or isolated by `factor`.
struct Found {
  Rational lo, hi;
  Poly factor;
  int multiplicity;
};

/// Makes r (a root of the squarefree f isolated in (lo, hi)) exact when it is
/// rational (see real_roots.cpp).
void exact_if_rational(const Poly& f, Found& r);

/// Refines overlapping closed intervals until pairwise disjoint
/// (BudgetExceeded after `cap` passes).
void make_disjoint(std::vector<Found>& roots, long cap);

}  // namespace uniparam::detail
