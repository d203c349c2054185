// Certified ball subdivision of the real-root isolation: on G's truncated
// local expansions (local_expansion.hpp) at high degree, and on a caller's
// evaluator (isolate_real_roots with a PolyEvaluator); cells they cannot
// decide go to the exact isolation.
#include <arb.h>
#include <arb_poly.h>
#include <arb_fmpz_poly.h>
#include <flint/fmpz_poly.h>

#include <algorithm>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "real_roots_internal.hpp"
#include "root_refine.hpp"
#include "uniparam/algebra/local_expansion.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace detail {

namespace {

// ---------------------------------------------------------------------------
// Certified ball subdivision (the fast path at high degree). G(m + w) on a
// dyadic cell [m - h, m + h] of [0, 1] is held as a truncated local expansion
// sum P_k w^k (Arb balls containing the exact coefficients of the truncated
// polynomial) plus a dropped tail T with |T| <= tail0, |T'| <= tail1 on the
// real interval |w| <= h. A child's expansion is its parent's shifted by
// +-h/2 (the child's interval lies in the parent's, so the tail bounds carry
// over), then truncated again: away from G's complex roots only a few terms
// matter, so a cell costs O(K^2) with K << n instead of an O(n^2) exact shift.

/// A local expansion of G at a cell's centre (see above); its tails bound
/// the dropped terms on |w| <= h.
using Expansion = LocalExpansion;

/// Drops the top terms of e (cell half-width h = 2^log2h) while their
/// contributions sum |c_k| h^k to G and h sum k |c_k| h^(k-1) to h G' on
/// |w| <= h stay below eps, adding their bounds to the tails. Keeps >= 2 terms.
void truncate_expansion(Expansion& e, long log2h, const mag_t eps) { truncate_local_expansion(e, log2h, eps, 2); }

/// Upper bounds var0 = sum_{k>=1} |c_k| h^k and var1 = sum_{k>=2} k |c_k| h^(k-1).
void variations(const Expansion& e, long log2h, mag_t var0, mag_t var1) {
  local_expansion_variation(var0, var1, e, log2h);
}

/// Sign of G at the cell end m + side * h (side = +-1): from the expansion when
/// its enclosure excludes 0, else exactly (0 when the end is a root).
int end_sign(const Expansion& e, const Poly& G, const DyadicCell& cell, int side, long prec) {
  const long log2h = -(cell.k + 1);
  ArbVar acc;
  const slong n = arb_poly_length(e.P);
  for (slong k = n - 1; k >= 0; --k) {  // Horner with exact multiplications by +-2^log2h
    arb_mul_2exp_si(acc.v, acc.v, log2h);
    if (side < 0) arb_neg(acc.v, acc.v);
    arb_add(acc.v, acc.v, e.P->coeffs + k, prec);
  }
  arb_add_error_mag(acc.v, e.tail + 0);
  if (arb_is_positive(acc.v)) return 1;
  if (arb_is_negative(acc.v)) return -1;
  const Integer c = side < 0 ? cell.c : cell.c + Integer(1);
  return exact_sign(G, Rational(c) * pow2(-cell.k));
}

/// Direction in which the terms of the centre expansion (k >= 1) mostly
/// keep one sign pattern on the cell: +1 when nearly all c_k h^k have the sign
/// of c_1 (|G| grows to the right), -1 when nearly all (-1)^k c_k do (it grows
/// to the left), 0 otherwise. A cheap filter for end_test (no claim).
int growth_direction(const Expansion& e, long log2h, const mag_t var0) {
  const slong n = arb_poly_length(e.P);
  if (n < 3) return 0;
  const int s1 = arf_sgn(arb_midref(e.P->coeffs + 1));
  if (s1 == 0) return 0;
  MagVar a, bad_r, bad_l;
  for (slong k = 2; k < n; ++k) {
    const int sk = arf_sgn(arb_midref(e.P->coeffs + k));
    if (sk == 0) continue;
    arb_get_mag(a.v, e.P->coeffs + k);
    mag_mul_2exp_si(a.v, a.v, log2h * k);
    if (sk != s1) mag_add(bad_r.v, bad_r.v, a.v);
    if (sk * ((k & 1) ? 1 : -1) != s1) mag_add(bad_l.v, bad_l.v, a.v);
  }
  mag_mul_2exp_si(bad_r.v, bad_r.v, 3);
  mag_mul_2exp_si(bad_l.v, bad_l.v, 3);
  if (mag_cmp(bad_r.v, var0) < 0) return 1;
  if (mag_cmp(bad_l.v, var0) < 0) return -1;
  return 0;
}

/// Tests on the expansion at the cell end a = m - dir h (the end |G| grows
/// away from): G(a + dir v) = sum b_k v^k + T, v in [0, 2h]. With sigma the
/// sign of b_1 and B0, B1 the sums of |b_k| (2h)^k and k |b_k| (2h)^(k-1)
/// over the k >= 2 whose ball is not sigma-signed: sigma (G - b_0) >= -B0 -
/// tail0 and sigma dir G' >= sigma b_1 - B1 - tail1 on the cell. Returns 1
/// when the cell has no root (sigma b_0 > B0 + tail0), 2 when G is monotone
/// on it (sigma b_1 > B1 + tail1), 0 when undecided.
int end_test(const Expansion& e, long log2h, int dir, long prec) {
  arb_poly_t B;
  arb_poly_init(B);
  arb_poly_set_round(B, e.P, prec);
  taylor_shift_pow2(B, B, log2h, -dir, prec);  // shift to the end m - dir h
  const slong n = arb_poly_length(B);
  int result = 0;
  if (n >= 2) {
    if (dir < 0)  // v = -u: b_k (-1)^k
      for (slong k = 1; k < n; k += 2) arb_neg(B->coeffs + k, B->coeffs + k);
    const int sigma = arb_is_positive(B->coeffs + 1) ? 1 : arb_is_negative(B->coeffs + 1) ? -1 : 0;
    if (sigma != 0) {
      MagVar b0, b1, a, m;
      mag_set(b0.v, e.tail + 0);
      mag_set(b1.v, e.tail + 1);
      for (slong k = 2; k < n; ++k) {
        if (sigma > 0 ? arb_is_nonnegative(B->coeffs + k) : arb_is_nonpositive(B->coeffs + k)) continue;
        arb_get_mag(a.v, B->coeffs + k);
        mag_mul_2exp_si(a.v, a.v, (log2h + 1) * (k - 1));  // |b_k| (2h)^(k-1)
        mag_mul_ui(m.v, a.v, static_cast<ulong>(k));
        mag_add(b1.v, b1.v, m.v);
        mag_mul_2exp_si(a.v, a.v, log2h + 1);
        mag_add(b0.v, b0.v, a.v);
      }
      ArbVar t;
      arb_set(t.v, B->coeffs);
      if (sigma < 0) arb_neg(t.v, t.v);
      arb_add_error_mag(t.v, b0.v);
      if (arb_is_positive(t.v)) {
        result = 1;
      } else {
        arb_set(t.v, B->coeffs + 1);
        if (sigma < 0) arb_neg(t.v, t.v);
        arb_add_error_mag(t.v, b1.v);
        if (arb_is_positive(t.v)) result = 2;
      }
    }
  }
  arb_poly_clear(B);
  return result;
}

/// Tolerances of the expansions derived from one exact expansion (an anchor):
/// truncation below eps = 2^(log_v - kExtraBits), with 2^log_v the typical
/// size of G on the anchor's cell; rounding at the same level.
struct Anchor {
  long log_v = 0;
  MagVar eps;
};

/// Accuracy of the expansions below the typical size of G (bits).
constexpr long kExtraBits = 64;

long limb_bits(long bits) { return (bits + FLINT_BITS - 1) / FLINT_BITS * FLINT_BITS; }

/// The exact expansion of G at the centre m of `cell`, rounded to enough
/// precision and truncated, and its anchor (tolerances from the median of
/// |G| at 7 points of the cell: only costs depend on them, never results).
std::unique_ptr<Expansion> anchor_expansion(const Poly& G, const DyadicCell& cell, Anchor& an) {
  const slong n = G.degree();
  const long L = cell.k + 1;
  // s(x) = 2^(L n) G(x / 2^L) shifted by 2c + 1: G(m + w) = 2^(-L n) s(2^L w).
  const int level = static_cast<int>(cell.k);
  const unsigned long long index = fmpz_get_ui(cell.c.get());
  const Poly s = local_shift_exact(G, level, index);
  // The terms on the cell (|w| <= 2^-L) are s_j 2^(-L n): at most 2^log_s in all.
  long bits = 0;
  for (slong j = 0; j <= n; ++j) bits = std::max<long>(bits, static_cast<long>(fmpz_bits(s.get()->coeffs + j)));
  const long log_s = bits + static_cast<long>(FLINT_BIT_COUNT(static_cast<ulong>(n + 1))) - L * n;
  std::vector<long> logs;
  {
    ArbVar x, y;
    MagVar m;
    for (int j = 1; j <= 7; ++j) {
      arb_set_si(x.v, j - 4);
      arb_mul_2exp_si(x.v, x.v, -2);  // 2^L w at the points m + (j - 4) h / 4
      arb_fmpz_poly_evaluate_arb(y.v, s.get(), x.v, bits + 3 * n + 64);
      arb_get_mag(m.v, y.v);
      if (!mag_is_zero(m.v)) logs.push_back(fmpz_get_si(MAG_EXPREF(m.v)) - L * n);
    }
  }
  an.log_v = log_s - kExtraBits;
  if (!logs.empty()) {
    std::sort(logs.begin(), logs.end());
    an.log_v = logs[logs.size() / 2];
  }
  mag_set_ui_2exp_si(an.eps.v, 1, an.log_v - kExtraBits);
  const long wp = limb_bits(std::max(64L, log_s - an.log_v + kExtraBits + 32));
  auto e = std::make_unique<Expansion>();
  set_local_expansion(*e, s, n, level, index, wp);
  truncate_expansion(*e, -L, an.eps.v);
  return e;
}

struct SubCell {
  DyadicCell cell;
  std::unique_ptr<Expansion> e;
  std::size_t anchor;
  bool fresh;  ///< e is the anchor's exact expansion
};

}  // namespace

/// Certified subdivision of [0, 1] for a squarefree G of degree >= 2 (roots
/// at 0 and 1 are not reported: the caller tests them). Appends cells holding
/// exactly one root with non-root ends (leaves), dyadic roots met as cell
/// ends (exact), and cells it could not decide within its depth and cell
/// budgets (undecided: for the exact VCA; their ends are not roots).
/// Where the expansions lose too much accuracy (G much smaller there than
/// the anchor's typical size) a cell gets a new exact expansion (anchor).
void subdivide(const Poly& G, std::vector<DyadicCell>& leaves, std::vector<DyadicCell>& exact, std::vector<DyadicCell>& undecided) {
  const slong n = G.degree();
  const long max_depth = 40;
  const long cell_cap = 16 * n + 4096;
  const std::size_t anchor_cap = 64;
  std::vector<std::unique_ptr<Anchor>> anchors;
  std::vector<SubCell> stack;
  {
    anchors.push_back(std::make_unique<Anchor>());
    DyadicCell root{Integer(0), 0};
    auto e = anchor_expansion(G, root, *anchors.back());
    stack.push_back({std::move(root), std::move(e), 0, true});
  }
  long cells = 0;
  MagVar var0, var1, lo, err, rad;
  while (!stack.empty()) {
    SubCell sc = std::move(stack.back());
    stack.pop_back();
    check_time_budget();
    ++cells;
    const Expansion& e = *sc.e;
    const Anchor& an = *anchors[sc.anchor];
    const long log2h = -(sc.cell.k + 1);
    variations(e, log2h, var0.v, var1.v);
    const slong len = arb_poly_length(e.P);
    // Working precision of what is derived from this expansion (children, end
    // values): its rounding error, relative to the terms on the cell (at most
    // 2^log_scale), must stay below eps.
    if (len > 0) arb_get_mag(rad.v, e.P->coeffs);
    else mag_zero(rad.v);
    mag_max(rad.v, rad.v, var0.v);
    const long log_scale = mag_is_finite(rad.v) && !mag_is_zero(rad.v) ? fmpz_get_si(MAG_EXPREF(rad.v)) : an.log_v;
    const long cwp = limb_bits(std::max(64L, log_scale - an.log_v + kExtraBits + 32));
    // G on the cell: P_0 +- (var0 + tail0)
    mag_add(err.v, var0.v, e.tail + 0);
    if (len > 0) arb_get_mag_lower(lo.v, e.P->coeffs);
    else mag_zero(lo.v);
    if (mag_cmp(lo.v, err.v) > 0) continue;  // no root in the closed cell
    // G' on the cell: P_1 +- (var1 + tail1)
    mag_add(err.v, var1.v, e.tail + 1);
    if (len > 1) arb_get_mag_lower(lo.v, e.P->coeffs + 1);
    else mag_zero(lo.v);
    if (mag_cmp(lo.v, err.v) > 0) {  // G monotone: at most one root
      const int sl = end_sign(e, G, sc.cell, -1, cwp), sr = end_sign(e, G, sc.cell, 1, cwp);
      if (sl != 0 && sr != 0 && sl != sr) leaves.push_back(std::move(sc.cell));
      continue;  // a root at an end is reported by the bisection that made it
    }
    // Cells where |G| grows steeply one way (the centred form above fails):
    // the expansion at the other end, O(K^2) like a bisection.
    if (const int dir = growth_direction(e, log2h, var0.v)) {
      const int t = end_test(e, log2h, dir, cwp);
      if (t == 1) continue;
      if (t == 2) {
        const int sl = end_sign(e, G, sc.cell, -1, cwp), sr = end_sign(e, G, sc.cell, 1, cwp);
        if (sl != 0 && sr != 0 && sl != sr) leaves.push_back(std::move(sc.cell));
        continue;
      }
    }
    // Bisecting helps only while the rounding error and the tail stay well
    // below G's variation on the cell; else a new anchor, or the exact VCA.
    mag_zero(rad.v);
    if (len > 0) mag_set(rad.v, arb_radref(e.P->coeffs));
    mag_add(rad.v, rad.v, e.tail + 0);
    mag_mul_2exp_si(rad.v, rad.v, 16);
    const bool inaccurate = mag_cmp(rad.v, var0.v) > 0;
    if (sc.cell.k >= max_depth || cells > cell_cap || (inaccurate && (sc.fresh || anchors.size() >= anchor_cap))) {
      undecided.push_back(std::move(sc.cell));
      continue;
    }
    if (inaccurate) {
      anchors.push_back(std::make_unique<Anchor>());
      auto ne = anchor_expansion(G, sc.cell, *anchors.back());
      stack.push_back({std::move(sc.cell), std::move(ne), anchors.size() - 1, true});
      continue;
    }
    Integer c2;
    fmpz_mul_2exp(c2.get(), sc.cell.c.get(), 1);
    const long k2 = sc.cell.k + 1;
    // the midpoint: a dyadic root is reported here, once (G(m) = P_0 + T(0))
    bool mid_may_vanish = len == 0;
    if (!mid_may_vanish) {
      ArbVar g;
      arb_set(g.v, e.P->coeffs);
      arb_add_error_mag(g.v, e.tail + 0);
      mid_may_vanish = arb_contains_zero(g.v);
    }
    if (mid_may_vanish) {
      const Rational m = Rational(c2 + Integer(1)) * pow2(-k2);
      if (exact_sign(G, m) == 0) exact.push_back({c2 + Integer(1), k2});
    }
    for (int side : {1, -1}) {  // the right child first: the left is processed first
      auto ch = std::make_unique<Expansion>();
      local_expansion_child(*ch, e, side, cwp);
      truncate_expansion(*ch, log2h - 1, an.eps.v);
      stack.push_back({{side < 0 ? c2 : c2 + Integer(1), k2}, std::move(ch), sc.anchor, false});
    }
  }
}

}  // namespace detail

namespace {

/// Depth of the evaluator's subdivision (cells of 2^-30 of [a, b]) before a
/// cell goes to the exact isolation.
constexpr long kEvaluatorDepth = 30;

using detail::exact_if_rational;
using detail::Found;
using detail::kSubdivisionDegree;
using detail::linear_poly;
using detail::make_disjoint;
using detail::provably_no_rational_root;
using detail::separation_bits;

}  // namespace

std::vector<IsolatedRoot> isolate_real_roots(const Poly& p, const PolyEvaluator& ev, const Rational& a,
                                             const Rational& b, const RootIsolationOptions& opt) {
  // Errors, a == b, the methods that do not subdivide (Exact; Auto below
  // kSubdivisionDegree, where the exact VCA is as fast) and p not proven
  // squarefree: the exact path.
  const bool subdivide_here = opt.method == RootIsolationMethod::Subdivision ||
                              (opt.method == RootIsolationMethod::Auto && p.degree() >= kSubdivisionDegree);
  if (!ev || !subdivide_here || p.is_zero() || !(a < b) || p.degree() < 2 || p.degree() > opt.max_degree ||
      !provably_squarefree(p))
    return isolate_real_roots(p, a, b, opt);
  const Poly f = p.primitive();  // the squarefree factor of every root (positive leading coefficient)
  std::map<Rational, int> signs;  // exact signs at cell ends (shared by neighbours)
  auto end_sign = [&](const Rational& x) {
    auto it = signs.find(x);
    if (it == signs.end()) it = signs.emplace(x, detail::exact_sign(p, x)).first;
    return it->second;
  };
  std::vector<Found> found, settled;  // leaves here; the exact path's roots (final)
  std::vector<Rational> exact;
  struct Interval {
    Rational l, r;
    long depth;
  };
  std::vector<Interval> stack{{a, b, 0}};
  const long cell_cap = 16 * p.degree() + 4096;
  long cells = 0;
  ArbVar v, d;
  while (!stack.empty()) {
    const Interval iv = stack.back();
    stack.pop_back();
    check_time_budget();
    ++cells;
    const Ball z = interval_ball(iv.l, iv.r, 64);  // holds the closed [l, r]
    ev(v.v, d.v, z.get(), 64);
    if (arb_is_finite(v.v) && !arb_contains_zero(v.v)) continue;  // no root in [l, r]
    if (arb_is_finite(d.v) && !arb_contains_zero(d.v)) {
      // p strictly monotone on [l, r]: one root there exactly when the
      // exact signs at the ends differ, or an end is a (rational) root.
      const int sl = end_sign(iv.l), sr = end_sign(iv.r);
      if (sl == 0) exact.push_back(iv.l);
      if (sr == 0) exact.push_back(iv.r);
      if (sl != 0 && sr != 0 && sl != sr) found.push_back({iv.l, iv.r, f, 1});
      continue;
    }
    if (iv.depth >= kEvaluatorDepth || cells > cell_cap) {  // undecided: exactly
      for (IsolatedRoot& r : isolate_real_roots(p, iv.l, iv.r, opt)) {
        if (r.is_exact()) exact.push_back(r.lo);
        else settled.push_back({std::move(r.lo), std::move(r.hi), std::move(r.factor), r.multiplicity});
      }
      continue;
    }
    const Rational m = (iv.l + iv.r) * Rational(1, 2);
    stack.push_back({m, iv.r, iv.depth + 1});
    stack.push_back({iv.l, m, iv.depth + 1});
  }
  // Rational roots are exact (isolate_real_roots' contract), as there.
  bool rational_test = true, rational_test_decided = false;
  for (Found& r : found) {
    if (!rational_test_decided) {
      rational_test = !provably_no_rational_root(f);
      rational_test_decided = true;
    }
    if (rational_test) exact_if_rational(f, r);
  }
  for (Found& r : settled) found.push_back(std::move(r));
  // A rational root at a shared end is met by both cells.
  std::sort(exact.begin(), exact.end(), [](const Rational& x, const Rational& y) { return x < y; });
  exact.erase(std::unique(exact.begin(), exact.end()), exact.end());
  for (const Rational& q : exact) found.push_back({q, q, linear_poly(q), 1});
  // Neighbouring cells' intervals share an end: separate them.
  make_disjoint(found, separation_bits(p) + p.degree() + 64);
  std::vector<IsolatedRoot> out;
  out.reserve(found.size());
  for (Found& r : found) out.push_back({std::move(r.lo), std::move(r.hi), std::move(r.factor), r.multiplicity, true});
  return out;
}

}  // namespace uniparam
