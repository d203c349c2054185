// Descartes' rule of signs with bisection (Vincent-Collins-Akritas) on
// dyadic cells of [0, 1], the exact isolation of real_roots.cpp.
#include <flint/fmpz_poly.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "real_roots_internal.hpp"
#include "root_refine.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam::detail {

/// Bits of a lower bound of the root separation of a squarefree g of degree n
/// (Mahler): sep > sqrt(3) n^(-(n+2)/2) ||g||_2^(1-n).
long separation_bits(const Poly& g) {
  const double n = static_cast<double>(std::max(2L, g.degree()));
  const double l2 = static_cast<double>(g.max_bits()) + 0.5 * std::log2(n + 1.0);
  return static_cast<long>(std::ceil((n + 2.0) / 2.0 * std::log2(n) + (n - 1.0) * l2)) + 8;
}

namespace {

/// Degree up to which descartes_bound tries IEEE double first ((1 + 1)^n
/// times the largest coefficient stays far below the largest double).
constexpr long kDoubleDescartesDegree = 800;

/// The Descartes test of descartes_bound in IEEE double, with a rigorous
/// bound on every coefficient's error: P's coefficients scaled by one power
/// of 2 (each rounded: error <= 2^-52 of it, or below 2^-1073 when it
/// underflows), then the n (n + 1) / 2 additions of the shift by 1, each
/// adding its rounding (<= 2^-53 of its result) to the propagated bounds,
/// themselves computed with a factor 1 + 2^-50 for their own rounding. A
/// coefficient whose value exceeds its bound has a known sign. Returns 2
/// when two sign changes among the known signs are certain (the exact
/// sequence has at least as many), 0 or 1 when every sign is known (then
/// exact), and -1 when it cannot tell (the caller shifts exactly).
int descartes_bound_double(const Poly& P, int& sign_at_1) {
  const slong n = P.degree();
  // R = reverse(P): R_k = P_(n-k); |v - exact| <= 2^-52 |v| or < 2^-1073 (scaled_doubles)
  const std::vector<double> c = scaled_doubles(P);
  std::vector<double> a(c.rbegin(), c.rend()), e(static_cast<std::size_t>(n + 1));
  for (std::size_t k = 0; k < e.size(); ++k) e[k] = std::fabs(a[k]) * 0x1p-52 + 0x1p-1073;
  constexpr double u = 0x1p-53, grow = 1 + 0x1p-50;
  for (slong i = 0; i < n; ++i)
    for (slong j = n - 1; j >= i; --j) {
      const std::size_t J = static_cast<std::size_t>(j);
      a[J] += a[J + 1];
      e[J] = (e[J] + e[J + 1] + std::fabs(a[J]) * u) * grow;
    }
  int var = 0, last = 0;
  bool all = true;
  for (slong k = 0; k <= n; ++k) {
    const std::size_t K = static_cast<std::size_t>(k);
    if (!(std::isfinite(a[K]) && std::isfinite(e[K]))) return -1;
    if (!(std::fabs(a[K]) > e[K])) {
      all = false;
      continue;
    }
    const int sg = a[K] > 0 ? 1 : -1;
    if (last != 0 && sg != last && ++var >= 2) return 2;
    last = sg;
  }
  if (!all) return -1;
  sign_at_1 = a[0] > 0 ? 1 : -1;  // S_0 = R(1) = P(1)
  return var;
}

}  // namespace

/// Sign variations (capped at 2) of (x+1)^n P(1/(x+1)), whose positive roots
/// are the roots of P in (0, 1); also sets the sign of P(1), its constant
/// term, when the result is 0 or 1 (the callers use it then only). In IEEE
/// double with certified error bounds first (descartes_bound_double), exact
/// where those cannot decide.
int descartes_bound(const Poly& P, int& sign_at_1) {
  if (P.degree() >= 1 && P.degree() <= kDoubleDescartesDegree) {
    const int v = descartes_bound_double(P, sign_at_1);
    if (v >= 0) return v;
  }
  Poly R, S;
  fmpz_poly_reverse(R.get(), P.get(), P.degree() + 1);
  const Integer one(1);
  fmpz_poly_taylor_shift(S.get(), R.get(), one.get());
  sign_at_1 = fmpz_sgn(S.get()->coeffs);
  int var = 0, last = 0;
  const fmpz* c = S.get()->coeffs;
  for (slong i = 0; i < S.get()->length; ++i) {
    const int s = fmpz_sgn(c + i);
    if (s == 0) continue;
    if (last != 0 && s != last && ++var >= 2) return 2;
    last = s;
  }
  return var;
}

namespace {

/// 2^n P(x/2) with the common power of 2 removed: the left half.
Poly left_half(const Poly& P) {
  Poly L(P);
  const slong n = L.degree();
  fmpz* c = L.get()->coeffs;
  for (slong i = 0; i < n; ++i) fmpz_mul_2exp(c + i, c + i, static_cast<ulong>(n - i));
  ulong v = ~0UL;
  for (slong i = 0; i <= n; ++i)
    if (!fmpz_is_zero(c + i)) v = std::min<ulong>(v, fmpz_val2(c + i));
  if (v != ~0UL && v > 0) fmpz_poly_scalar_fdiv_2exp(L.get(), L.get(), v);
  return L;
}

}  // namespace

/// Vincent-Collins-Akritas on (0, 1) for a squarefree G (roots at 0 and 1 are
/// not reported: the caller tests them).
/// Leaves: cells holding exactly one root, whose ends are not roots. Exact:
/// dyadic roots met as bisection midpoints.
/// Same on the cell (c/2^k, (c+1)/2^k) of [0, 1], from P(x) = 2^(k n) G((c + x) / 2^k)
/// up to a positive factor (roots at the cell's ends are not reported).
void vca_from(const Poly& G, Node start, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact) {
  if (G.degree() < 1) return;
  const long depth_cap = separation_bits(G) + 4;
  const long node_cap = 4 * (G.degree() + 1) * (depth_cap + 1) + 1000;
  long nodes = 0;
  std::vector<Node> stack;
  stack.push_back(std::move(start));
  int p1 = 0;
  while (!stack.empty()) {
    Node nd = std::move(stack.back());
    stack.pop_back();
    check_time_budget();
    if (++nodes > node_cap || nd.cell.k > depth_cap)
      throw BudgetExceeded("root isolation of a degree-" + std::to_string(G.degree()) +
                           " polynomial did not finish within " + std::to_string(node_cap) + " subdivisions (depth " +
                           std::to_string(depth_cap) + ")");
    const int v = descartes_bound(nd.P, p1);
    if (v == 0) continue;
    if (v == 1 && !fmpz_is_zero(nd.P.get()->coeffs) && p1 != 0) {
      leaves.push_back(std::move(nd.cell));
      continue;
    }
    Poly L = left_half(nd.P);
    Poly R;
    const Integer one(1);
    fmpz_poly_taylor_shift(R.get(), L.get(), one.get());
    Integer c2;
    fmpz_mul_2exp(c2.get(), nd.cell.c.get(), 1);
    const long k2 = nd.cell.k + 1;
    if (fmpz_is_zero(R.get()->coeffs)) exact.push_back({c2 + Integer(1), k2});
    stack.push_back({std::move(R), {c2 + Integer(1), k2}});
    stack.push_back({std::move(L), {c2, k2}});
  }
}

void vca(const Poly& G, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact) {
  vca_from(G, {G, {Integer(0), 0}}, leaves, exact);
}

/// 2^(k n) G((c + x) / 2^k) exactly: G on the cell (c/2^k, (c+1)/2^k) mapped to (0, 1).
Poly cell_poly(const Poly& G, const DyadicCell& cell) {
  const slong n = G.degree();
  Poly H(G);
  fmpz* h = H.get()->coeffs;
  for (slong i = 0; i <= n; ++i) fmpz_mul_2exp(h + i, h + i, static_cast<ulong>(cell.k * (n - i)));
  Poly P;
  fmpz_poly_taylor_shift(P.get(), H.get(), cell.c.get());
  return P;
}

int descartes_test(const Poly& P, int& sign_at_1) { return descartes_bound(P, sign_at_1); }

}  // namespace uniparam::detail
