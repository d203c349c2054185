// Real-root isolation in [a, b]: squarefree factorisation, the map
// [a, b] -> [0, 1], the isolation of each factor (descartes.cpp; at high
// degree after the ball subdivision of root_subdivision.cpp), exact
// rational roots, disjoint intervals (refined with root_refine.cpp).
#include "uniparam/algebra/real_roots.hpp"

#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>
#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "real_roots_internal.hpp"
#include "root_refine.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace detail {

Poly linear_poly(const Rational& q) { return Poly(std::vector<Integer>{Integer(0) - q.num(), q.den()}); }

bool provably_no_rational_root(const Poly& f) {
  if (f.degree() < 2) return false;
  // Small primes first: every residue is tried by evaluation, O(n p) each.
  for (ulong p = 3; p < 256; p = n_nextprime(p, 1)) {
    if (fmpz_fdiv_ui(f.get()->coeffs + f.degree(), p) == 0) continue;
    nmod_poly_t fp;
    nmod_poly_init(fp, p);
    fmpz_poly_get_nmod_poly(fp, f.get());
    bool no_root = true;
    for (ulong x = 0; x < p && no_root; ++x) no_root = nmod_poly_evaluate_nmod(fp, x) != 0;
    nmod_poly_clear(fp);
    if (no_root) return true;
  }
  ulong p = 1000003;
  for (int tries = 0; tries < 8; ++tries) {
    p = n_nextprime(p, 1);
    if (fmpz_fdiv_ui(f.get()->coeffs + f.degree(), p) == 0) continue;
    nmod_poly_t fp, x, xp, g;
    nmod_poly_init(fp, p);
    nmod_poly_init(x, p);
    nmod_poly_init(xp, p);
    nmod_poly_init(g, p);
    fmpz_poly_get_nmod_poly(fp, f.get());
    nmod_poly_set_coeff_ui(x, 1, 1);
    nmod_poly_powmod_ui_binexp(xp, x, p, fp);  // t^p mod f
    nmod_poly_sub(xp, xp, x);
    nmod_poly_gcd(g, xp, fp);  // product of the distinct linear factors of f mod p
    const bool no_root = nmod_poly_degree(g) == 0;
    nmod_poly_clear(fp);
    nmod_poly_clear(x);
    nmod_poly_clear(xp);
    nmod_poly_clear(g);
    if (no_root) return true;
  }
  return false;
}

/// The open interval (c/2^k, (c+1)/2^k) of [0, 1].


/// Makes r (a root of the squarefree f isolated in (lo, hi)) exact when it is
/// rational. Rational roots n/d have d | lc(f); once hi - lo < 1/lc^2 the
/// simplest rational in [lo, hi] is the only candidate. It is tried first at
/// 64 bits, so that roots with small denominators are found early. Callers
/// skip this when a prime proves that f has no rational root at all.
void exact_if_rational(const Poly& f, Found& r) {
  const long final_bits = 2 * f.leading().bits() + 1;
  for (long bits = std::min(64L, final_bits);; bits = final_bits) {
    if (detail::refine_isolating_interval(f, r.lo, r.hi, bits)) break;  // met exactly: lo == hi
    Rational q;
    fmpq_simplest_between(q.get(), r.lo.get(), r.hi.get());
    if (exact_sign(f, q) == 0) {
      r.lo = r.hi = q;
      break;
    }
    if (bits >= final_bits) return;
  }
  r.factor = linear_poly(r.lo);
}

/// Roots of the squarefree f (degree >= 1) in [a, b], a < b: exact ones as
/// lo == hi, others as intervals (lo, hi) in [a, b] with exactly one root
/// and f(lo), f(hi) != 0.
void isolate_factor(const Poly& f, int mult, const Rational& a, const Rational& b, RootIsolationMethod method,
                    std::vector<Found>& out) {
  if (f.degree() == 1) {
    const Rational r = -Rational(f.coeff(0)) / Rational(f.coeff(1));
    if (a <= r && r <= b) out.push_back({r, r, linear_poly(r), mult});
    return;
  }
  // Work on a dyadic hull [a2, b2] of [a, b], at most twice as wide: the
  // map to [0, 1] then involves only powers of 2, however large the
  // denominators of a and b are.
  const long k = detail::floor_log2(b - a) - 1;
  const Rational a2 = grid_floor(a, k), b2 = -grid_floor(-b, k);
  const Rational w = b2 - a2;
  const Poly G = mapped_to_unit_interval(f, a2, b2);
  std::vector<Found> raw;
  // Roots at the ends, exactly. G keeps them: Descartes' rule counts roots
  // in the open (0, 1) only, and a leaf never has a root of G at an end.
  if (fmpz_is_zero(G.get()->coeffs)) raw.push_back({a2, a2, Poly(), mult});
  Integer g1;
  for (slong i = 0; i < G.get()->length; ++i) fmpz_add(g1.get(), g1.get(), G.get()->coeffs + i);
  if (g1.sign() == 0) raw.push_back({b2, b2, Poly(), mult});
  std::vector<DyadicCell> leaves, exact;
  if (use_subdivision(G, method)) {
    // One Descartes test first: it settles factors with no root (or one) in
    // (0, 1) for the price of one exact shift.
    int g1_sign = 0;
    const int v = descartes_bound(G, g1_sign);
    std::vector<DyadicCell> undecided;
    if (v == 1 && !fmpz_is_zero(G.get()->coeffs) && g1_sign != 0) leaves.push_back({Integer(0), 0});
    else if (v >= 1) subdivide(G, leaves, exact, undecided);
    for (DyadicCell& cl : undecided) vca_from(G, {cell_poly(G, cl), cl}, leaves, exact);
  } else {
    vca(G, leaves, exact);
  }
  auto to_t = [&](const Integer& c, long e) { return a2 + w * Rational(c) * pow2(-e); };
  for (const DyadicCell& e : exact) {
    const Rational r = to_t(e.c, e.k);
    raw.push_back({r, r, Poly(), mult});
  }
  for (const DyadicCell& cl : leaves) raw.push_back({to_t(cl.c, cl.k), to_t(cl.c + Integer(1), cl.k), Poly(), mult});
  // Back to [a, b]: an interval holding a (or b) keeps the side of the root,
  // decided by the exact sign of f at a.
  const int s_a = a == a2 ? 0 : exact_sign(f, a), s_b = b == b2 ? 0 : exact_sign(f, b);
  bool rational_test = true, rational_test_decided = false;
  for (Found& r : raw) {
    if (r.lo == r.hi) {
      if (a <= r.lo && r.lo <= b) out.push_back({r.lo, r.lo, linear_poly(r.lo), mult});
      continue;
    }
    if (r.hi <= a || b <= r.lo) continue;  // the root is outside [a, b]
    if (r.lo < a) {  // a in (lo, hi)
      if (s_a == 0) { out.push_back({a, a, linear_poly(a), mult}); continue; }
      if (s_a != exact_sign(f, r.lo)) continue;  // root in (lo, a)
      r.lo = a;
    }
    if (b < r.hi) {
      if (s_b == 0) { out.push_back({b, b, linear_poly(b), mult}); continue; }
      if (s_b != exact_sign(f, r.hi)) continue;  // root in (b, hi)
      r.hi = b;
    }
    if (!rational_test_decided) {  // only when some interval needs it
      rational_test = !provably_no_rational_root(f);
      rational_test_decided = true;
    }
    r.factor = f;
    r.multiplicity = mult;
    if (rational_test) exact_if_rational(f, r);
    out.push_back(std::move(r));
  }
}

/// Degree from which make_disjoint separates touching cells of one factor
/// by signs compared with the shared end's (below, halving both costs about
/// as much, and the narrower intervals serve the refinements that follow:
/// bez-plane 12 radical, degrees 10 and 31, took 4% more instructions).
constexpr long kTouchingSignsDegree = 48;

/// Refines overlapping closed intervals until pairwise disjoint.
void make_disjoint(std::vector<Found>& roots, long cap) {
  auto by_lo = [](const Found& x, const Found& y) { return x.lo < y.lo; };
  for (long pass = 0;; ++pass) {
    std::sort(roots.begin(), roots.end(), by_lo);
    bool clean = true;
    for (std::size_t i = 0; i + 1 < roots.size(); ++i) {
      if (roots[i].hi < roots[i + 1].lo) continue;
      clean = false;
      Found& x = roots[i];
      Found& y = roots[i + 1];
      if (x.lo < x.hi && y.lo < y.hi && x.hi == y.lo && x.factor == y.factor &&
          x.factor.degree() >= kTouchingSignsDegree) {
        // Neighbouring cells of one factor's isolation, touching at m (not
        // a root): the sign at m, then bisections at the cells' short
        // dyadic middles, each compared with it, until one root is proven
        // away from m (~2.5 exact signs; refining both by halves took ~5).
        const Rational m = x.hi;
        const int sm = exact_sign(x.factor, m);
        for (long step = 0, side = 0; x.hi == y.lo; ++step, side ^= 1) {
          check_time_budget();
          if (step > 2 * cap)  // each step halves a cell: the roots are 2^-cap apart at least
            throw BudgetExceeded("could not separate two touching isolating intervals within " +
                                 std::to_string(2 * cap) + " bisections");
          Found& r = side == 0 ? x : y;
          const Rational q = grid_floor((r.lo + r.hi) * Rational(1, 2), detail::floor_log2(r.hi - r.lo) - 2);
          const int sq = exact_sign(r.factor, q);
          if (sq == 0) {
            r.lo = r.hi = q;
            r.factor = linear_poly(q);
          } else if ((sq == sm) == (side == 0)) {
            // f has m's sign between the roots: left, the root is below q
            // (done); right, above q is the other sign, the root below q
            r.hi = q;
          } else {
            r.lo = q;  // left: the root above q (still touching); right: above q (done)
          }
        }
        continue;
      }
      for (Found* r : {&roots[i], &roots[i + 1]}) {
        if (r->lo == r->hi) continue;
        const long bits = 1 - detail::floor_log2(r->hi - r->lo);  // halve the width
        if (detail::refine_isolating_interval(r->factor, r->lo, r->hi, bits)) r->factor = linear_poly(r->lo);
      }
    }
    if (clean) return;
    check_time_budget();
    if (pass > cap)
      throw BudgetExceeded("could not separate the isolating intervals within " + std::to_string(cap) +
                           " refinement passes");
  }
}

}  // namespace detail

namespace {

using detail::exact_sign;
using detail::Found;
using detail::linear_poly;
using detail::separation_bits;

}  // namespace

namespace {
thread_local long t_exact_isolations = 0;
}  // namespace

long exact_isolations() { return t_exact_isolations; }

std::vector<IsolatedRoot> isolate_real_roots(const Poly& p, const Rational& a, const Rational& b,
                                             const RootIsolationOptions& opt) {
  ++t_exact_isolations;
  if (p.is_zero()) throw InvalidArgument("real-root isolation of the zero polynomial (every number is a root)");
  if (b < a) throw InvalidArgument("real-root isolation in [" + a.str() + ", " + b.str() + "]: empty interval");
  if (p.degree() > opt.max_degree)
    throw BudgetExceeded("root isolation of a polynomial of degree " + std::to_string(p.degree()) +
                         " (derived from the curve: its speed or critical points) exceeds the root-isolation " +
                         "degree limit of " + std::to_string(opt.max_degree) +
                         " (RootIsolationOptions::max_degree; no option raises it: lower the curve's degree)");
  const SquarefreeFactorization sf = squarefree_factorization(p);
  std::vector<Found> found;
  if (a == b) {
    for (const auto& fm : sf.factors)
      if (fm.factor.sign_at(a) == 0) found.push_back({a, a, linear_poly(a), fm.multiplicity});
  } else {
    for (const auto& fm : sf.factors) isolate_factor(fm.factor, fm.multiplicity, a, b, opt.method, found);
    make_disjoint(found, separation_bits(p) + p.degree() + 64);
  }
  std::vector<IsolatedRoot> out;
  out.reserve(found.size());
  for (Found& r : found) out.push_back({std::move(r.lo), std::move(r.hi), std::move(r.factor), r.multiplicity, true});
  return out;
}

long count_real_roots(const Poly& p, const Rational& a, const Rational& b) {
  if (p.is_zero()) throw InvalidArgument("count_real_roots: the zero polynomial");
  if (!(a < b)) throw InvalidArgument("count_real_roots: needs a < b, got [" + a.str() + ", " + b.str() + "]");
  long n = 0;
  for (const IsolatedRoot& r : isolate_real_roots(p, a, b))
    if (!(r.is_exact() && (r.lo == a || r.lo == b))) ++n;
  return n;
}

}  // namespace uniparam
