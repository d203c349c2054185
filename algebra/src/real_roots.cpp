// Real-root isolation in [a, b]: squarefree factorisation, the map
// [a, b] -> [0, 1], Descartes' rule of signs with bisection (Vincent-Collins-
// Akritas), exact rational roots, certified refinement (root_refine.hpp).
#include "uniparam/algebra/real_roots.hpp"

#include <arb.h>
#include <arb_poly.h>
#include <arb_fmpz_poly.h>
#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>
#include <flint/nmod_poly.h>
#include <flint/ulong_extras.h>

#include <algorithm>
#include <map>
#include <memory>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "root_refine.hpp"
#include "uniparam/algebra/local_expansion.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace detail {

/// Owning arb_t for local use (also used by the subdivision below).
struct ArbVar {
  arb_t v;
  ArbVar() { arb_init(v); }
  ~ArbVar() { arb_clear(v); }
  ArbVar(const ArbVar&) = delete;
  ArbVar& operator=(const ArbVar&) = delete;
};

namespace {

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

/// Bits of the largest Horner term of f on [lo, hi]: an estimate (IEEE
/// double logarithms, rounded up by a bit) of max_k log2(|f_k| X^k), X =
/// max(|lo|, |hi|), so that the sum of |f_k| X^k, which bounds every partial
/// sum of Horner's scheme, is below 2^(result + log2(n + 1)). Only sets
/// working precisions: a low estimate costs a retry or a slower path, never
/// a wrong result. f.max_bits() + n magnitude_bits(lo, hi), the bound for
/// X = 2^magnitude, when X is not a normal double. On [0, 1] it is far
/// smaller: a root at 0.05 of the critical numerator of a degree-150 curve
/// (degree 1633) has terms of 250 bits against coefficients of 2500.
long horner_bits(const Poly& f, const Rational& lo, const Rational& hi) {
  const long n = f.degree();
  if (n < 0) return 0;
  arf_t a, b;
  arf_init(a);
  arf_init(b);
  arf_set_fmpq(a, lo.get(), 64, ARF_RND_UP);
  arf_set_fmpq(b, hi.get(), 64, ARF_RND_UP);
  arf_abs(a, a);
  arf_abs(b, b);
  if (arf_cmp(b, a) > 0) arf_swap(a, b);
  const double X = arf_get_d(a, ARF_RND_UP);
  arf_clear(a);
  arf_clear(b);
  if (!(X >= 1e-300 && X <= 1e300)) return f.max_bits() + n * magnitude_bits(lo, hi);
  const double l = std::log2(X) + 1e-9;
  double best = 0;
  bool any = false;
  for (long k = 0; k <= n; ++k) {
    const fmpz* c = f.get()->coeffs + k;
    if (fmpz_is_zero(c)) continue;
    const double t = static_cast<double>(fmpz_bits(c)) + static_cast<double>(k) * l;
    if (!any || t > best) best = t;
    any = true;
  }
  return any ? static_cast<long>(std::ceil(best)) + 1 : 0;
}

/// A Newton step from the midpoint of (lo, hi), computed in Arb until its
/// enclosure is narrower than 2^(s-3). Only a guess: nothing is certified.
/// `extra` is the working precision beyond the estimate that the last
/// successful call needed (raised or decayed here).
bool newton_guess(const Poly& f, const Poly& df, const Rational& lo, const Rational& hi, long s,
                  long& extra, Rational& out) {
  const Rational mid = (lo + hi) * Rational(1, 2);
  // Cancellation in Horner: the terms are up to 2^horner_bits.
  const long base = 32 + horner_bits(f, lo, hi) + (s < 0 ? -s : 0);
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

/// Width (log2) below which an interval Newton step first takes a Newton
/// guess from f'(m) in the power basis (one more evaluation, and a second
/// f at the guess): the guess is off by ~(f''/f') w^2, so the step gains
/// about twice the bits, which pays for the two evaluations once w is small.
constexpr long kQuadraticNewtonBits = 24;

/// Degree of f' up to which an interval Newton step bounds f' on the
/// interval from the power basis instead of the evaluator (measured: bez-plane
/// d = 6 `radical` -8% instructions, d = 12 -1%; at degree 250, bez-plane
/// d = 50, the power basis was 2% slower).
constexpr long kDirectDerivativeDegree = 64;

/// Bisections refine_isolating_interval makes between failed interval
/// Newton steps before it leaves them for the exact steps (the interval
/// then lost a factor 2^8 of its width; a root where f' is tiny stays
/// with the exact steps).
constexpr int kNewtonBisections = 8;

/// Width (log2) above which refine_isolating_interval first looks for the
/// root in double precision (centred_start) and tries to prove a narrow
/// interval around it with one interval Newton step; and the degree from
/// which it does (one exact Taylor shift of f per polynomial, see
/// ScaledEvaluator::centred_cache).
constexpr long kStartBits = 24;
constexpr long kStartMinDegree = 16;

/// The root of f in (lo, hi) to about double precision, from Newton's
/// iteration in IEEE double on f's basis centred at 1/2,
/// q(s) = 2^n f((1 + s) / 2) (an exact Taylor shift): on [0, 1] its Horner
/// terms are far smaller than the power basis's (the critical numerators of
/// Bezier curves of degree 12, degree 114, lose 44-162 bits at their roots
/// in the power basis, 25-48 in this one). Only a guess, nothing certified:
/// on success g is a short dyadic with [g - d, g + d] inside (lo, hi) and d
/// a power of 2 of at least 8 times the guess's estimated error (Horner's
/// rounding over |f'|, and the last Newton step) and at most w / 8; false
/// when the iteration leaves (lo, hi), does not settle, or d would be
/// too wide to gain anything. c: scaled_doubles(centred_at_half(f)).
bool centred_start(const std::vector<double>& c, const Rational& lo, const Rational& hi, Rational& g, Rational& d) {
  const long n = static_cast<long>(c.size()) - 1;
  const double slo = 2 * fmpq_get_d(lo.get()) - 1, shi = 2 * fmpq_get_d(hi.get()) - 1;
  double sx = 0.5 * (slo + shi), err = 1, step = 1;
  for (int it = 0; it < 40; ++it) {
    double v = c[static_cast<std::size_t>(n)], dv = 0, a = std::fabs(v);
    const double as = std::fabs(sx);
    for (long k = n - 1; k >= 0; --k) {
      dv = dv * sx + v;
      v = v * sx + c[static_cast<std::size_t>(k)];
      a = a * as + std::fabs(c[static_cast<std::size_t>(k)]);
    }
    if (!(std::isfinite(v) && std::isfinite(dv)) || dv == 0) return false;
    step = v / dv;
    err = 2 * 0x1p-53 * a / std::fabs(dv);  // |s - root| from Horner's typical rounding
    // damped where the step leaves the interval (a far start)
    for (int damp = 0; damp < 8 && !(sx - step > slo && sx - step < shi); ++damp) step *= 0.5;
    sx -= step;
    if (!(sx > slo && sx < shi)) return false;
    if (std::fabs(step) <= err) break;
  }
  if (!(std::fabs(step) <= 2 * err)) return false;
  // in x = (1 + s) / 2: the error halves
  const double ex = 0.5 * std::max(err, std::fabs(step)) + 0x1p-60;
  int k = 0;
  std::frexp(8.0 * ex, &k);  // 8 ex < 2^k
  const Rational w = hi - lo;
  if (k > floor_log2(w) - 3) return false;
  d = pow2(k);
  Rational x;
  {
    arf_t a;
    arf_init(a);
    arf_set_d(a, 0.5 * (1.0 + sx));  // exact
    arf_get_fmpq(x.get(), a);
    arf_clear(a);
  }
  g = grid_floor(x, k - 4);
  return lo < g - d && g + d < hi;
}

/// One interval Newton step on the isolating interval (lo, hi) of a simple
/// root r of f (see refine_isolating_interval): for a dyadic c in (lo, hi),
/// f(c) = f'(xi) (c - r) with xi in (lo, hi), so r lies in N = c - f(c) / F,
/// F an enclosure of f' on (lo, hi) (up to kDirectDerivativeDegree, f' on a
/// ball holding [lo, hi] from the power basis; above, sev's derivative over
/// lambda on a ball of radius >= 2^-23 holding it). c is the dyadic middle m, or,
/// once w < 2^-kQuadraticNewtonBits, the Newton guess m - f(m) / f'(m) from
/// the power basis (only a choice of c: nothing relies on its accuracy).
/// N is rounded outward to the grid 2^-(b+8) and widened by one grid
/// step (r is then strictly inside, so the new ends are not roots, and there
/// is one root between them, on the side of each end where it was), where
/// b = min(bits, 2 |log2 w| + 32): a step gains at most about that much
/// (quadratic convergence), so f(c) is evaluated at the precision this step
/// can use, not at the final one (the early steps of a refinement to 133
/// bits from 2^-3 took ~200-bit evaluations for gains of a few bits). Returns
/// true when (lo, hi) was replaced by an interval at most half as wide;
/// false (interval unchanged or narrowed less) when F holds 0 or the step
/// gains less.
/// With `centre` (a short dyadic in (lo, hi)), c is that point (no guess)
/// and `inside` tells whether N, rounded and widened as above, lies
/// strictly inside (lo, hi) before the clipping. Then f has a root in
/// (lo, hi) even if none was known there (Moore's existence test: say F > 0
/// and f(c) > 0; lo < c - f(c) / F_lo gives f(lo) <= f(c) - F_lo (c - lo)
/// < 0 by the mean value theorem), which is in N.
bool interval_newton_step(const Poly& f, const Poly& df, const ScaledEvaluator& sev, Rational& lo, Rational& hi,
                          long target_bits, long mag, const Rational* centre = nullptr, bool* inside = nullptr) {
  if (inside) *inside = false;
  const Rational w = hi - lo;
  const long ew = floor_log2(w);
  const long bits = std::min(target_bits, 2 * std::max(0L, -ew) + 32);  // what this step can gain
  const Rational m = centre ? *centre : grid_floor((lo + hi) * Rational(1, 2), ew - 4);
  ArbVar X, M, v, F, lam, fm, N;
  {
    const Ball xb = interval_ball(lo, hi, 64);
    arb_set(X.v, xb.get());
  }
  if (df.degree() <= kDirectDerivativeDegree) {
    // Low degree: f' on X from the power basis, at the bits Horner's terms
    // need plus 32 (doubled while the enclosure holds 0); the evaluator
    // would build local expansions at each new place (~0.1 M instructions a
    // step on bez-plane d = 6's critical numerator).
    const long hb = horner_bits(df, lo, hi);
    long p = std::max(64L, hb + 32);
    for (int tries = 0; tries < 3; ++tries, p *= 2) {
      arb_fmpz_poly_evaluate_arb(F.v, df.get(), X.v, p);  // holds f'(xi) for every xi in [lo, hi]
      if (arb_is_finite(F.v) && !arb_contains_zero(F.v)) break;
    }
  } else {
    // Coarse bounds: a ball narrower than 2^-24 would make the evaluator
    // build full-precision expansions, for ~24 more bits of F than this needs.
    if (mag_cmp_2exp_si(arb_radref(X.v), -23) < 0) mag_set_ui_2exp_si(arb_radref(X.v), 1, -23);
    sev.ev(v.v, F.v, X.v, 64);
    arb_set_fmpq(lam.v, sev.lambda.get(), 64);
    arb_div(F.v, F.v, lam.v, 64);  // holds f'(xi) for every xi in [lo, hi]
  }
  if (!arb_is_finite(F.v) || arb_contains_zero(F.v)) return false;
  // f(m) from the power basis (m exactly: a short dyadic), to an absolute
  // error below 2^-(bits + 10) |f'|: Horner's n + 1 terms are up to
  // 2^horner_bits on [lo, hi].
  const long n = f.degree();
  const long terms = horner_bits(f, lo, hi) + static_cast<long>(FLINT_BIT_COUNT(static_cast<ulong>(n + 1))) + 8;
  mag_t lower;
  mag_init(lower);
  arb_get_mag_lower(lower, F.v);
  const long e = fmpz_get_si(MAG_EXPREF(lower)) - 1;  // |f'| >= 2^e on [lo, hi]
  mag_clear(lower);
  const long s = -(bits + 8);  // the grid of the new ends (and of c)
  const long prec = std::max({64L, terms + bits + 10 - e, rational_bits(m) + 8, bits + 16 + mag});
  arb_set_fmpq(M.v, m.get(), prec);  // exact: a short dyadic
  arb_fmpz_poly_evaluate_arb(fm.v, f.get(), M.v, prec);
  if (!centre && ew < -kQuadraticNewtonBits) {
    ArbVar fpm, g;
    arb_fmpz_poly_evaluate_arb(fpm.v, df.get(), M.v, terms + 2 * static_cast<long>(FLINT_BIT_COUNT(static_cast<ulong>(n))) + 64);
    if (arb_is_finite(fpm.v) && !arb_contains_zero(fpm.v)) {
      arb_div(g.v, fm.v, fpm.v, prec);
      arb_sub(g.v, M.v, g.v, prec);
      Rational c;
      arf_get_fmpq(c.get(), arb_midref(g.v));
      c = grid_floor(c, s);
      if (lo < c && c < hi) {
        arb_set_fmpq(M.v, c.get(), prec);  // exact: bits + 8 bits below the point
        arb_fmpz_poly_evaluate_arb(fm.v, f.get(), M.v, prec);
      }
    }
  }
  arb_div(fm.v, fm.v, F.v, prec);
  arb_sub(N.v, M.v, fm.v, prec);
  if (!arb_is_finite(N.v)) return false;
  arf_t a, b;
  arf_init(a);
  arf_init(b);
  arb_get_interval_arf(a, b, N.v, prec);  // outward
  Rational ql, qh;
  arf_get_fmpq(ql.get(), a);
  arf_get_fmpq(qh.get(), b);
  arf_clear(a);
  arf_clear(b);
  ql = grid_floor(ql, s) - pow2(s);
  qh = grid_floor(qh, s) + pow2(s + 1);  // >= the ceiling plus one step
  if (inside) *inside = lo < ql && qh < hi;
  Rational nl = lo < ql ? ql : lo, nh = qh < hi ? qh : hi;
  if (!(nl < nh)) return false;  // r is in both: only an evaluator breaking its contract gets here
  lo = std::move(nl);
  hi = std::move(nh);
  return (hi - lo) * Rational(2) <= w;
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
  // Horner's terms are up to 2^horner_bits: start above that.
  const long start = 64 + xb + horner_bits(f, x, x);
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

namespace {

/// prove_root_near with f' given (refine_isolating_interval has it).
bool prove_root_near(const Poly& f, const Poly& df, const ScaledEvaluator& sev, const Rational& g, const Rational& d,
                     long bits, Rational& lo, Rational& hi) {
  if (!(d.sign() > 0)) throw InvalidArgument("prove_root_near: the radius must be positive");
  Rational l2 = g - d, h2 = g + d;
  bool inside = false;
  interval_newton_step(f, df, sev, l2, h2, bits, magnitude_bits(l2, h2), &g, &inside);
  if (!inside) return false;
  lo = std::move(l2);
  hi = std::move(h2);
  return true;
}

}  // namespace

bool prove_root_near(const Poly& f, const ScaledEvaluator& sev, const Rational& g, const Rational& d, long bits,
                     Rational& lo, Rational& hi) {
  return prove_root_near(f, f.derivative(), sev, g, d, bits, lo, hi);
}

bool refine_isolating_interval(const Poly& f, Rational& lo, Rational& hi, long bits, long* newton_log,
                               const ScaledEvaluator* sev) {
  if (lo == hi) return true;
  if (hi < lo) throw InvalidArgument("refine: empty interval");
  const Rational target = pow2(-bits);
  Rational w = hi - lo;
  if (w <= target) return false;
  const long mag = magnitude_bits(lo, hi);
  const Poly df = f.derivative();
  int s_lo = 0;  // the sign of f at lo, once asked
  // One bisection by the exact sign at a short dyadic in the middle half of
  // (lo, hi): true when that dyadic is the root (lo = hi = it).
  auto bisect = [&]() {
    if (s_lo == 0) s_lo = exact_sign(f, lo);
    if (s_lo == 0) throw InvalidArgument("refine: the lower end " + lo.str() + " is a root of " + f.str());
    const Rational m = grid_floor((lo + hi) * Rational(1, 2), floor_log2(hi - lo) - 2);
    const int sm = exact_sign(f, m);
    if (sm == 0) {
      lo = hi = m;
      return true;
    }
    if (sm == s_lo) lo = m; else hi = m;
    return false;
  };
  if (sev && sev->ev) {
    // Where a step fails (f' on a wide isolating interval holds 0: the
    // interval may hold a zero of f', or the bound is loose there), a
    // bisection by the sign at a short dyadic midpoint (cheap: few bits)
    // narrows it, and the interval Newton steps resume; after
    // kNewtonBisections bisections the exact steps below take over. Not at
    // low degree, where f' comes from Horner's rule on the ball and holds 0
    // until the interval is narrow, which the exact steps reach sooner.
    const int max_bisections = df.degree() > kDirectDerivativeDegree ? kNewtonBisections : 0;
    int bisections = 0;
    // A start near the root, when it is far: a double-precision guess g
    // and an interval (g - d, g + d) inside (lo, hi) that one interval
    // Newton step proves holds a root (the one of (lo, hi)), and narrows.
    // Where either fails, nothing changed.
    if (f.degree() >= kStartMinDegree && floor_log2(w) > -kStartBits && bits + floor_log2(w) > kStartBits) {
      // f's centred basis: one per polynomial, kept by the evaluator
      std::shared_ptr<const std::vector<double>> c = std::atomic_load(&sev->centred_cache);
      if (!c) {
        c = std::make_shared<const std::vector<double>>(scaled_doubles(centred_at_half(f)));
        std::atomic_store(&sev->centred_cache, c);  // a racing copy computed the same
      }
      Rational g, d;
      if (c->size() == static_cast<std::size_t>(f.degree() + 1) && centred_start(*c, lo, hi, g, d) &&
          prove_root_near(f, df, *sev, g, d, bits, lo, hi))
        w = hi - lo;
    }
    while (w > target) {
      check_time_budget();
      if (!interval_newton_step(f, df, *sev, lo, hi, bits, mag)) {
        if (++bisections > max_bisections) break;
        if (bisect()) return true;
      }
      w = hi - lo;
    }
    if (w <= target) return false;
  }
  if (s_lo == 0) s_lo = exact_sign(f, lo);
  if (s_lo == 0) throw InvalidArgument("refine: the lower end " + lo.str() + " is a root of " + f.str());
  const long start = floor_log2(w);
  // Every accepted Newton bracket or bisection at least halves the width;
  // failed Newton tries are at most logarithmically many per success.
  const long cap = 8 * (std::max(0L, bits + start) + 64) + 1000;
  // a Newton proposal is a subinterval of width ~ w / 2^log_n; a caller's
  // state continues the quadratic rate of its last call
  long log_n = newton_log ? std::max(2L, *newton_log) : 2;
  long extra = 0;  // precision the Newton steps needed beyond the estimate
  for (long it = 0;; ++it) {
    if (newton_log) *newton_log = log_n;
    if (w <= target) return false;
    check_time_budget();
    if (it > cap)
      throw BudgetExceeded("could not refine the root of " + f.str() + " to 2^-" + std::to_string(bits) +
                           " within " + std::to_string(cap) + " steps");
    const long ew = floor_log2(w);  // 2^ew <= w < 2^(ew+1)
    bool halve = log_n < 2;
    if (!halve) {
      const long s = std::max(ew - log_n, -bits - 1);  // grid spacing 2^s
      Rational guess;
      if (!newton_guess(f, df, lo, hi, s, extra, guess)) {
        log_n /= 2;
        halve = true;
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
    if (halve) {
      if (bisect()) return true;
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
using ArbVar = detail::ArbVar;

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
struct Cell {
  Integer c;
  long k;
};

struct Node {
  Poly P;  ///< 2^(k n) G((c + x) / 2^k) up to a positive power of 2
  Cell cell;
};

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
/// Same on the cell (c/2^k, (c+1)/2^k) of [0, 1], from P(x) = 2^(k n) G((c + x) / 2^k)
/// up to a positive factor (roots at the cell's ends are not reported).
void vca_from(const Poly& G, Node start, std::vector<Cell>& leaves, std::vector<Cell>& exact) {
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

void vca(const Poly& G, std::vector<Cell>& leaves, std::vector<Cell>& exact) {
  vca_from(G, {G, {Integer(0), 0}}, leaves, exact);
}

/// 2^(k n) G((c + x) / 2^k) exactly: G on the cell (c/2^k, (c+1)/2^k) mapped to (0, 1).
Poly cell_poly(const Poly& G, const Cell& cell) {
  const slong n = G.degree();
  Poly H(G);
  fmpz* h = H.get()->coeffs;
  for (slong i = 0; i <= n; ++i) fmpz_mul_2exp(h + i, h + i, static_cast<ulong>(cell.k * (n - i)));
  Poly P;
  fmpz_poly_taylor_shift(P.get(), H.get(), cell.c.get());
  return P;
}

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

/// Owning mag_t for local use.
struct MagVar {
  mag_t v;
  MagVar() { mag_init(v); }
  ~MagVar() { mag_clear(v); }
  MagVar(const MagVar&) = delete;
  MagVar& operator=(const MagVar&) = delete;
};

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
int end_sign(const Expansion& e, const Poly& G, const Cell& cell, int side, long prec) {
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
std::unique_ptr<Expansion> anchor_expansion(const Poly& G, const Cell& cell, Anchor& an) {
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
  Cell cell;
  std::unique_ptr<Expansion> e;
  std::size_t anchor;
  bool fresh;  ///< e is the anchor's exact expansion
};

/// Certified subdivision of [0, 1] for a squarefree G of degree >= 2 (roots
/// at 0 and 1 are not reported: the caller tests them). Appends cells holding
/// exactly one root with non-root ends (leaves), dyadic roots met as cell
/// ends (exact), and cells it could not decide within its depth and cell
/// budgets (undecided: for the exact VCA; their ends are not roots).
/// Where the expansions lose too much accuracy (G much smaller there than
/// the anchor's typical size) a cell gets a new exact expansion (anchor).
void subdivide(const Poly& G, std::vector<Cell>& leaves, std::vector<Cell>& exact, std::vector<Cell>& undecided) {
  const slong n = G.degree();
  const long max_depth = 40;
  const long cell_cap = 16 * n + 4096;
  const std::size_t anchor_cap = 64;
  std::vector<std::unique_ptr<Anchor>> anchors;
  std::vector<SubCell> stack;
  {
    anchors.push_back(std::make_unique<Anchor>());
    Cell root{Integer(0), 0};
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

/// Below this degree the exact VCA is faster than the subdivision (measured
/// on random dense and Bernstein polynomials of degree 20..400).
constexpr long kSubdivisionDegree = 300;

bool use_subdivision(const Poly& G, RootIsolationMethod method) {
  if (G.degree() < 2 || method == RootIsolationMethod::Exact) return false;
  return method == RootIsolationMethod::Subdivision || G.degree() >= kSubdivisionDegree;
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
  if (use_subdivision(G, method)) {
    // One Descartes test first: it settles factors with no root (or one) in
    // (0, 1) for the price of one exact shift.
    int g1_sign = 0;
    const int v = descartes_bound(G, g1_sign);
    std::vector<Cell> undecided;
    if (v == 1 && !fmpz_is_zero(G.get()->coeffs) && g1_sign != 0) leaves.push_back({Integer(0), 0});
    else if (v >= 1) subdivide(G, leaves, exact, undecided);
    for (Cell& cl : undecided) vca_from(G, {cell_poly(G, cl), cl}, leaves, exact);
  } else {
    vca(G, leaves, exact);
  }
  auto to_t = [&](const Integer& c, long e) { return a2 + w * Rational(c) * pow2(-e); };
  for (const Cell& e : exact) {
    const Rational r = to_t(e.c, e.k);
    raw.push_back({r, r, Poly(), mult});
  }
  for (const Cell& cl : leaves) raw.push_back({to_t(cl.c, cl.k), to_t(cl.c + Integer(1), cl.k), Poly(), mult});
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
          const Rational q = detail::grid_floor((r.lo + r.hi) * Rational(1, 2), detail::floor_log2(r.hi - r.lo) - 2);
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

namespace {

/// Depth of the evaluator's subdivision (cells of 2^-30 of [a, b]) before a
/// cell goes to the exact isolation.
constexpr long kEvaluatorDepth = 30;

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
    const Ball z = detail::interval_ball(iv.l, iv.r, 64);  // holds the closed [l, r]
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

long count_real_roots(const Poly& p, const Rational& a, const Rational& b) {
  if (p.is_zero()) throw InvalidArgument("count_real_roots: the zero polynomial");
  if (!(a < b)) throw InvalidArgument("count_real_roots: needs a < b, got [" + a.str() + ", " + b.str() + "]");
  long n = 0;
  for (const IsolatedRoot& r : isolate_real_roots(p, a, b))
    if (!(r.is_exact() && (r.lo == a || r.lo == b))) ++n;
  return n;
}

namespace detail {

int descartes_test(const Poly& P, int& sign_at_1) { return descartes_bound(P, sign_at_1); }

}  // namespace detail

}  // namespace uniparam
