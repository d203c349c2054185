// Real-root isolation in [a, b]: squarefree factorisation, the map
// [a, b] -> [0, 1], Descartes' rule of signs with bisection (Vincent-Collins-
// Akritas), exact rational roots, certified refinement (root_refine.hpp).
#include "uniparam/algebra/real_roots.hpp"

#include <arb.h>
#include <arb_fmpz_poly.h>
#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>
#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "root_refine.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace detail {
namespace {

/// Owning arb_t for local use.
struct ArbVar {
  arb_t v;
  ArbVar() { arb_init(v); }
  ~ArbVar() { arb_clear(v); }
  ArbVar(const ArbVar&) = delete;
  ArbVar& operator=(const ArbVar&) = delete;
};

bool is_dyadic(const Rational& x) {
  const fmpz* d = fmpq_denref(x.get());
  return fmpz_val2(d) + 1 == fmpz_bits(d);
}

long rational_bits(const Rational& x) {
  return static_cast<long>(fmpz_bits(fmpq_numref(x.get())) + fmpz_bits(fmpq_denref(x.get())));
}

/// floor(x / 2^s) * 2^s: the grid point of spacing 2^s at or below x.
Rational grid_floor(const Rational& x, long s) {
  const Rational y = x * pow2(-s);
  Integer f;
  fmpz_fdiv_q(f.get(), fmpq_numref(y.get()), fmpq_denref(y.get()));
  return Rational(f) * pow2(s);
}

/// Bits of the integer part of max(|lo|, |hi|) (>= 0).
long magnitude_bits(const Rational& lo, const Rational& hi) {
  Rational m = lo.sign() < 0 ? -lo : lo;
  const Rational h = hi.sign() < 0 ? -hi : hi;
  if (h > m) m = h;
  if (m <= Rational(1)) return 0;
  return floor_log2(m) + 1;
}

/// A Newton step from the midpoint of (lo, hi), computed in Arb until its
/// enclosure is narrower than 2^(s-3). Only a guess: nothing is certified.
/// `extra` is the working precision beyond the estimate that the last
/// successful call needed (raised or decayed here).
bool newton_guess(const Poly& f, const Poly& df, const Rational& lo, const Rational& hi, long s, long mag,
                  long& extra, Rational& out) {
  const Rational mid = (lo + hi) * Rational(1, 2);
  // Cancellation in Horner: the terms are up to 2^(max_bits + n mag).
  const long base = 32 + f.max_bits() + f.degree() * mag + (s < 0 ? -s : 0);
  ArbVar m, v, d, x;
  long more = extra;
  for (int tries = 0; tries < 3; ++tries, more = 2 * more + 32) {
    const long prec = base + more;
    arb_set_fmpq(m.v, mid.get(), prec);
    mag_zero(arb_radref(m.v));  // an exact point near mid is as good a start
    arb_fmpz_poly_evaluate_arb(v.v, f.get(), m.v, prec);
    arb_fmpz_poly_evaluate_arb(d.v, df.get(), m.v, prec);
    if (arb_contains_zero(d.v)) continue;
    arb_div(v.v, v.v, d.v, prec);
    arb_sub(x.v, m.v, v.v, prec);
    if (!arb_is_finite(x.v)) continue;
    if (mag_cmp_2exp_si(arb_radref(x.v), s - 3) <= 0) {
      extra = tries == 0 ? more / 2 : more;
      arf_get_fmpq(out.get(), arb_midref(x.v));
      return lo < out && out < hi;
    }
  }
  return false;
}

}  // namespace

Rational pow2(long e) {
  Rational r(1);
  if (e >= 0) fmpq_mul_2exp(r.get(), r.get(), static_cast<flint_bitcnt_t>(e));
  else fmpq_div_2exp(r.get(), r.get(), static_cast<flint_bitcnt_t>(-e));
  return r;
}

long floor_log2(const Rational& w) {
  if (w.sign() <= 0) throw InvalidArgument("floor_log2 of a nonpositive number");
  const long e = static_cast<long>(fmpz_bits(fmpq_numref(w.get()))) -
                 static_cast<long>(fmpz_bits(fmpq_denref(w.get())));
  return w >= pow2(e) ? e : e - 1;  // 2^(e-1) < w < 2^(e+1)
}

int exact_sign(const Poly& f, const Rational& x) {
  if (f.is_zero()) return 0;
  const long n = f.degree();
  if (n == 0) return f.coeff(0).sign();
  const long xb = rational_bits(x);
  // Horner's terms are up to 2^(max_bits + n * xmag): start above that.
  const long xmag = std::max(0L, static_cast<long>(fmpz_bits(fmpq_numref(x.get()))) -
                                     static_cast<long>(fmpz_bits(fmpq_denref(x.get()))) + 1);
  const long start = 64 + xb + f.max_bits() + n * xmag;
  ArbVar xv, y;
  if (is_dyadic(x)) {
    // At precision >= exact_bits Horner in Arb is exact; stop a little
    // earlier and evaluate exactly instead.
    const long exact_bits = n * (xb + 1) + f.max_bits() + 64;
    for (long prec = start; prec <= exact_bits / 2; prec *= 2) {
      arb_set_fmpq(xv.v, x.get(), prec);
      arb_fmpz_poly_evaluate_arb(y.v, f.get(), xv.v, prec);
      if (arb_is_positive(y.v)) return 1;
      if (arb_is_negative(y.v)) return -1;
      if (arb_is_zero(y.v)) return 0;  // x exact and every operation exact
    }
  } else {
    for (long prec = start; prec <= 4 * start; prec *= 2) {
      arb_set_fmpq(xv.v, x.get(), prec);
      arb_fmpz_poly_evaluate_arb(y.v, f.get(), xv.v, prec);
      if (arb_is_positive(y.v)) return 1;
      if (arb_is_negative(y.v)) return -1;
    }
  }
  return f.sign_at(x);  // exact rational evaluation
}

bool refine_isolating_interval(const Poly& f, Rational& lo, Rational& hi, long bits) {
  if (lo == hi) return true;
  if (hi < lo) throw InvalidArgument("refine: empty interval");
  const Rational target = pow2(-bits);
  Rational w = hi - lo;
  if (w <= target) return false;
  const int s_lo = exact_sign(f, lo);
  if (s_lo == 0) throw InvalidArgument("refine: the lower end " + lo.str() + " is a root of " + f.str());
  const Poly df = f.derivative();
  const long mag = magnitude_bits(lo, hi);
  const long start = floor_log2(w);
  // Every accepted Newton bracket or bisection at least halves the width;
  // failed Newton tries are at most logarithmically many per success.
  const long cap = 8 * (std::max(0L, bits + start) + 64) + 1000;
  long log_n = 2;  // a Newton proposal is a subinterval of width ~ w / 2^log_n
  long extra = 0;  // precision the Newton steps needed beyond the estimate
  for (long it = 0;; ++it) {
    if (w <= target) return false;
    check_time_budget();
    if (it > cap)
      throw BudgetExceeded("could not refine the root of " + f.str() + " to 2^-" + std::to_string(bits) +
                           " within " + std::to_string(cap) + " steps");
    const long ew = floor_log2(w);  // 2^ew <= w < 2^(ew+1)
    bool bisect = log_n < 2;
    if (!bisect) {
      const long s = std::max(ew - log_n, -bits - 1);  // grid spacing 2^s
      Rational guess;
      if (!newton_guess(f, df, lo, hi, s, mag, extra, guess)) {
        log_n /= 2;
        bisect = true;
      } else {
        // Candidate [g - 2^s, g + 2^s] around the grid point g nearest to the
        // guess, clipped to (lo, hi); certified by exact signs at its ends.
        const Rational g = grid_floor(guess + pow2(s - 1), s);
        Rational l2 = g - pow2(s), h2 = g + pow2(s);
        const bool lclip = l2 <= lo, hclip = h2 >= hi;
        if (lclip) l2 = lo;
        if (hclip) h2 = hi;
        const int sl = lclip ? s_lo : exact_sign(f, l2);
        if (sl == 0) { lo = hi = l2; return true; }
        if (sl != s_lo) {
          hi = l2;  // root in (lo, l2)
          log_n /= 2;
        } else {
          const int sh = hclip ? -s_lo : exact_sign(f, h2);
          if (sh == 0) { lo = hi = h2; return true; }
          if (sh == s_lo) {
            lo = h2;  // root in (h2, hi)
            log_n /= 2;
          } else {
            lo = l2;
            hi = h2;
            log_n = std::min(2 * log_n, 1L << 24);
          }
        }
      }
    }
    if (bisect) {
      // A short dyadic in the middle half of (lo, hi).
      const Rational m = grid_floor((lo + hi) * Rational(1, 2), ew - 2);
      const int sm = exact_sign(f, m);
      if (sm == 0) { lo = hi = m; return true; }
      if (sm == s_lo) lo = m; else hi = m;
      if (log_n < 2) log_n = 2;
    }
    w = hi - lo;
  }
}

Ball interval_ball(const Rational& lo, const Rational& hi, long prec) {
  Ball a(lo, prec), b(hi, prec), r;
  arb_union(r.get(), a.get(), b.get(), prec);
  return r;
}

}  // namespace detail

namespace {

using detail::exact_sign;
using detail::pow2;

/// d*t - n for q = n/d.
Poly linear_poly(const Rational& q) { return Poly(std::vector<Integer>{Integer(0) - q.num(), q.den()}); }

/// Bits of a lower bound of the root separation of a squarefree g of degree n
/// (Mahler): sep > sqrt(3) n^(-(n+2)/2) ||g||_2^(1-n).
long separation_bits(const Poly& g) {
  const double n = static_cast<double>(std::max(2L, g.degree()));
  const double l2 = static_cast<double>(g.max_bits()) + 0.5 * std::log2(n + 1.0);
  return static_cast<long>(std::ceil((n + 2.0) / 2.0 * std::log2(n) + (n - 1.0) * l2)) + 8;
}

/// True when f (degree >= 2) provably has no rational root: for some prime
/// p not dividing lc(f), f mod p has no root in F_p (a root n/d of f, with
/// d | lc(f), would reduce to one). A few primes; false means "unknown".
bool provably_no_rational_root(const Poly& f) {
  if (f.degree() < 2) return false;
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
struct Cell {
  Integer c;
  long k;
};

struct Node {
  Poly P;  ///< 2^(k n) G((c + x) / 2^k) up to a positive power of 2
  Cell cell;
};

/// Sign variations (capped at 2) of (x+1)^n P(1/(x+1)), whose positive roots
/// are the roots of P in (0, 1); also sets P(1), its constant term.
int descartes_bound(const Poly& P, Integer& p_at_1) {
  Poly R, S;
  fmpz_poly_reverse(R.get(), P.get(), P.degree() + 1);
  const Integer one(1);
  fmpz_poly_taylor_shift(S.get(), R.get(), one.get());
  p_at_1 = S.coeff(0);
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

/// Vincent-Collins-Akritas on (0, 1) for a squarefree G (roots at 0 and 1 are
/// not reported: the caller tests them).
/// Leaves: cells holding exactly one root, whose ends are not roots. Exact:
/// dyadic roots met as bisection midpoints.
void vca(const Poly& G, std::vector<Cell>& leaves, std::vector<Cell>& exact) {
  if (G.degree() < 1) return;
  const long depth_cap = separation_bits(G) + 4;
  const long node_cap = 4 * (G.degree() + 1) * (depth_cap + 1) + 1000;
  long nodes = 0;
  std::vector<Node> stack;
  stack.push_back({G, {Integer(0), 0}});
  Integer p1;
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
    if (v == 1 && !fmpz_is_zero(nd.P.get()->coeffs) && p1.sign() != 0) {
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

/// A root being assembled: exact (lo == hi) or isolated by `factor`.
struct Found {
  Rational lo, hi;
  Poly factor;
  int multiplicity;
};

/// G(x) = L^n f((A + W x) / L) / content with a = A/L, b - a = W/L: the
/// roots of G in [0, 1] are those of f in [a, b].
Poly map_to_unit_interval(const Poly& f, const Rational& a, const Rational& b) {
  const Rational w = b - a;
  const Integer L = a.den() * w.den();
  const Integer A = a.num() * w.den();
  const Integer W = w.num() * a.den();
  const slong n = f.degree();
  Poly H(f);
  {
    Integer Lp(1);
    fmpz* c = H.get()->coeffs;
    for (slong i = n; i >= 0; --i) {  // c_i * L^(n-i)
      fmpz_mul(c + i, c + i, Lp.get());
      fmpz_mul(Lp.get(), Lp.get(), L.get());
    }
  }
  Poly G;
  fmpz_poly_taylor_shift(G.get(), H.get(), A.get());
  {
    Integer Wp(1);
    fmpz* c = G.get()->coeffs;
    for (slong i = 0; i <= n; ++i) {
      fmpz_mul(c + i, c + i, Wp.get());
      fmpz_mul(Wp.get(), Wp.get(), W.get());
    }
  }
  return G.primitive();
}

/// Roots of the squarefree f (degree >= 1) in [a, b], a < b: exact ones as
/// lo == hi, others as intervals (lo, hi) in [a, b] with exactly one root
/// and f(lo), f(hi) != 0.
void isolate_factor(const Poly& f, int mult, const Rational& a, const Rational& b, std::vector<Found>& out) {
  if (f.degree() == 1) {
    const Rational r = -Rational(f.coeff(0)) / Rational(f.coeff(1));
    if (a <= r && r <= b) out.push_back({r, r, linear_poly(r), mult});
    return;
  }
  // Work on a dyadic hull [a2, b2] of [a, b], at most twice as wide: the
  // map to [0, 1] then involves only powers of 2, however large the
  // denominators of a and b are.
  const long k = detail::floor_log2(b - a) - 1;
  const Rational a2 = detail::grid_floor(a, k), b2 = -detail::grid_floor(-b, k);
  const Rational w = b2 - a2;
  const Poly G = map_to_unit_interval(f, a2, b2);
  std::vector<Found> raw;
  // Roots at the ends, exactly. G keeps them: Descartes' rule counts roots
  // in the open (0, 1) only, and a leaf never has a root of G at an end.
  if (fmpz_is_zero(G.get()->coeffs)) raw.push_back({a2, a2, Poly(), mult});
  Integer g1;
  for (slong i = 0; i < G.get()->length; ++i) fmpz_add(g1.get(), g1.get(), G.get()->coeffs + i);
  if (g1.sign() == 0) raw.push_back({b2, b2, Poly(), mult});
  std::vector<Cell> leaves, exact;
  vca(G, leaves, exact);
  auto to_t = [&](const Integer& c, long e) { return a2 + w * Rational(c) * pow2(-e); };
  for (const Cell& e : exact) {
    const Rational r = to_t(e.c, e.k);
    raw.push_back({r, r, Poly(), mult});
  }
  for (const Cell& cl : leaves) raw.push_back({to_t(cl.c, cl.k), to_t(cl.c + Integer(1), cl.k), Poly(), mult});
  // Back to [a, b]: an interval holding a (or b) keeps the side of the root,
  // decided by the exact sign of f at a.
  const int s_a = a == a2 ? 0 : exact_sign(f, a), s_b = b == b2 ? 0 : exact_sign(f, b);
  // Rational roots n/d have d | lc(f); once hi - lo < 1/lc^2 the simplest
  // rational in [lo, hi] is the only candidate. Try it first at 64 bits, so
  // that roots with small denominators are found early. Skipped when a
  // prime proves that f has no rational root at all.
  const long final_bits = 2 * f.leading().bits() + 1;
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
    bool is_exact = false;
    for (long bits = std::min(64L, final_bits); rational_test; bits = final_bits) {
      if (detail::refine_isolating_interval(f, r.lo, r.hi, bits)) { is_exact = true; break; }
      Rational q;
      fmpq_simplest_between(q.get(), r.lo.get(), r.hi.get());
      if (exact_sign(f, q) == 0) { r.lo = r.hi = q; is_exact = true; break; }
      if (bits >= final_bits) break;
    }
    out.push_back({r.lo, r.hi, is_exact ? linear_poly(r.lo) : f, mult});
  }
}

/// Refines overlapping closed intervals until pairwise disjoint.
void make_disjoint(std::vector<Found>& roots, long cap) {
  auto by_lo = [](const Found& x, const Found& y) { return x.lo < y.lo; };
  for (long pass = 0;; ++pass) {
    std::sort(roots.begin(), roots.end(), by_lo);
    bool clean = true;
    for (std::size_t i = 0; i + 1 < roots.size(); ++i) {
      if (roots[i].hi < roots[i + 1].lo) continue;
      clean = false;
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

}  // namespace

std::vector<IsolatedRoot> isolate_real_roots(const Poly& p, const Rational& a, const Rational& b,
                                             const RootIsolationOptions& opt) {
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
    for (const auto& fm : sf.factors) isolate_factor(fm.factor, fm.multiplicity, a, b, found);
    make_disjoint(found, separation_bits(p) + p.degree() + 64);
  }
  std::vector<IsolatedRoot> out;
  out.reserve(found.size());
  for (Found& r : found) out.push_back({std::move(r.lo), std::move(r.hi), std::move(r.factor), r.multiplicity});
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
