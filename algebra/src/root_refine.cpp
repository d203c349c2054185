// Certified refinement of isolating intervals (root_refine.hpp): exact signs
// at rational points, interval Newton steps with a double-precision start,
// quadratic interval refinement with exact sign tests, bisection.
#include "root_refine.hpp"

#include <arb.h>
#include <arb_fmpz_poly.h>
#include <flint/fmpq.h>
#include <flint/fmpz_poly.h>

#include <algorithm>
#include <memory>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "real_roots_internal.hpp"
#include "uniparam/core/ball_regions.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace detail {

namespace {

bool is_dyadic(const Rational& x) {
  const fmpz* d = fmpq_denref(x.get());
  return fmpz_val2(d) + 1 == fmpz_bits(d);
}

long rational_bits(const Rational& x) {
  return static_cast<long>(fmpz_bits(fmpq_numref(x.get())) + fmpz_bits(fmpq_denref(x.get())));
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
/// lambda on a wide ball, of radius >= 2^-23, holding it). c is the dyadic middle m, or,
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
    // Coarse bounds: a ball narrower than 2^kCoarseBallLog2 (not a wide
    // ball, core/ball_regions.hpp) would make the evaluator build
    // full-precision expansions, for ~24 more bits of F than this needs.
    if (mag_cmp_2exp_si(arb_radref(X.v), kCoarseBallLog2 + 1) < 0)
      mag_set_ui_2exp_si(arb_radref(X.v), 1, kCoarseBallLog2 + 1);
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

}  // namespace detail

}  // namespace uniparam
