// One Gauss-Legendre step of the quadrature: the per-thread cache of the
// rules' nodes and weights, the error bound on a Bernstein ellipse, the
// choice of the degree, and gl_step (ellipses, strips, singularity hints,
// the nodes through node_fast or the integrand).
#include <acb_calc.h>
#include <arb_hypgeom.h>
#include <arf.h>
#include <mag.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <exception>
#include <limits>
#include <vector>

#include "quadrature_internal.hpp"
#include "uniparam/core/budget.hpp"

namespace uniparam {
namespace quadrature_detail {
namespace {

/// Gauss-Legendre degrees tried (Arb's steps of about 2^(k/2)).
constexpr long kGlSteps[] = {1, 2, 4, 6, 8, 12, 16, 22, 32, 46, 64, 90, 128, 182, 256, 362, 512, 724, 1024};
constexpr int kGlStepCount = static_cast<int>(sizeof(kGlSteps) / sizeof(kGlSteps[0]));

/// Precision rungs of the node cache: 64 2^r bits, r < kGlRungCount.
constexpr int kGlRungCount = 12;

/// The nodes x_k > 0 (k < (n + 1) / 2; the others are -x_k) and weights of
/// the n-point Gauss-Legendre rule on [-1, 1], one cache per thread (the
/// pool's threads are persistent), computed at the rung 64 2^r >= the
/// precision asked (Arb's arb_hypgeom_legendre_p_ui_root: rigorous balls).
/// The rung depends on the precision alone, never on what was asked
/// before, so the nodes' balls, and with them every integral's, do not
/// depend on the thread's history (which thread ran which piece, or what
/// ran earlier in the process). gl_rule checks the time budget before each
/// node (BudgetExceeded; the rule interrupted is computed again when next
/// asked for).
struct GlRule {
  long prec = 0;
  arb_ptr x = nullptr, w = nullptr;
  slong len = 0;
  // x and w as double-word balls (for NodeIntegrand), made with them
  std::vector<DDBall> dx, dw;
  GlRule() = default;
  GlRule(const GlRule&) = delete;
  GlRule& operator=(const GlRule&) = delete;
  ~GlRule() {
    if (x) _arb_vec_clear(x, len);
    if (w) _arb_vec_clear(w, len);
  }
};

const GlRule& gl_rule(int step, long prec) {
  thread_local GlRule rules[kGlStepCount][kGlRungCount];
  int rung = 0;
  while (rung + 1 < kGlRungCount && (64L << rung) < prec) ++rung;
  const long wp = std::max(prec, 64L << rung);  // beyond the last rung: prec itself
  GlRule& r = rules[step][rung];
  if (r.prec != wp) {
    const long n = kGlSteps[step];
    if (!r.x) {
      r.len = (n + 1) / 2;
      r.x = _arb_vec_init(r.len);
      r.w = _arb_vec_init(r.len);
    }
    r.dx.assign(static_cast<std::size_t>(r.len), DDBall{});
    r.dw.assign(static_cast<std::size_t>(r.len), DDBall{});
    r.prec = 0;  // incomplete until the loop ends (an exceeded time budget leaves it so)
    for (slong k = 0; k < r.len; ++k) {
      // Thousands of nodes at thousands of bits take seconds: --timeout is
      // noticed within one node.
      check_time_budget();
      arb_hypgeom_legendre_p_ui_root(r.x + k, r.w + k, static_cast<ulong>(n), static_cast<ulong>(k), wp);
      // x in (0, 1), w in (0, 2): always representable; a failure would
      // leave a non-finite ball, which sends its node to the Integrand
      const double nan = std::numeric_limits<double>::quiet_NaN();
      if (!dd_set_arb(r.dx[k], r.x + k)) r.dx[k] = DDBall{nan, nan, nan};
      if (!dd_set_arb(r.dw[k], r.w + k)) r.dw[k] = DDBall{nan, nan, nan};
    }
    r.prec = wp;
  }
  return r;
}

/// Node evaluations that one more (larger) ellipse must be expected to save
/// before it is tried: bounding f on an ellipse (a wide complex ball: local
/// expansions at a coarse level, often the factored form) costs several node
/// evaluations.
constexpr long kEllipseCost = 4;

/// Largest Gauss-Legendre degree on the small ellipse X = 5/4 (rho = 2),
/// tried where X = 2 fails: 46 nodes reach 2^-88 there, so one such step
/// replaces a bisection (two ellipses and two rules) near a singularity.
constexpr long kSmallEllipseDegLimit = 46;

/// Smallest X of the ellipse between X = 2 and the small one (5/4) that
/// gl_step tries where X = 2 fails: the largest the singularity hints leave
/// (below that it saves too few nodes against the small ellipse's).
constexpr double kMidEllipseMin = 1.4;

/// QuadratureOptions::singularity_hints: an ellipse is skipped when a hint
/// lies in its bounding box enlarged by this factor. Arb's enclosures on a
/// wide ball blow up well before a singularity is inside it: on the radical
/// runs of the benchmark curves of degree 6 to 50 (speeds' poles and branch
/// points as hints), no ellipse with a hint within 1.5 times its box gave a
/// finite bound, and 17 of 162 within 1.5 to 2 times did. 1.75 skipped the
/// most failing ellipses without costing bisections (measured, one thread).
constexpr double kHintMargin = 1.75;

/// The error bound (64/15) M / ((rho - 1) rho^(2n - 1)) of the n-point rule
/// (an upper bound) in err.
void gl_error(mag_t err, const mag_t M, const mag_t rho, long n) {
  MagVar t, u;
  mag_pow_ui_lower(t.v, rho, static_cast<ulong>(2 * n - 1));
  mag_one(u.v);
  mag_sub_lower(u.v, rho, u.v);
  mag_mul_lower(t.v, t.v, u.v);
  mag_mul_ui_lower(t.v, t.v, 15);
  mag_div(err, M, t.v);
  mag_mul_2exp_si(err, err, 6);
}

/// Smallest Gauss-Legendre step index whose error bound is below tol[k] for
/// every k < count (M[k] = |delta| sup |f_k| on the ellipse rho), or -1
/// when no n <= deg_limit does.
int gl_degree(const std::vector<MagVar>& M, const mag_t rho, const std::vector<MagVar>& tol, long deg_limit) {
  MagVar err;
  auto in_range = [deg_limit](int j) { return j < kGlStepCount && kGlSteps[j] <= deg_limit; };
  auto meets = [&](std::size_t k, int j) {  // the rigorous test
    gl_error(err.v, M[k].v, rho, kGlSteps[j]);
    return mag_cmp(err.v, tol[k].v) < 0;
  };
  // log2 of gl_error's bound in double: only a first guess of the index
  // (saves most of the mag_t evaluations, ~12% of a low-degree run); the
  // answer is still the smallest index that meets the rigorous test, which
  // falls with n: from the guess, walk down while the index below meets it,
  // then up while it does not.
  const double r = mag_get_d(rho);
  const double lr = std::log2(r), lr1 = std::log2(r - 1);
  int i = 0;
  for (std::size_t k = 0; k < M.size(); ++k) {
    int j = i;
    const double lm = std::log2(mag_get_d(M[k].v)), lt = std::log2(mag_get_d(tol[k].v));
    if (std::isfinite(lr) && std::isfinite(lr1) && std::isfinite(lm) && std::isfinite(lt))
      while (in_range(j) &&
             lm + 6 - std::log2(15.0) - lr1 - static_cast<double>(2 * kGlSteps[j] - 1) * lr >= lt)
        ++j;
    while (j > i && in_range(j - 1) && meets(k, j - 1)) --j;
    for (;; ++j) {
      if (!in_range(j)) return -1;
      if (meets(k, j)) break;
    }
    i = j;
  }
  return i;  // the largest of the components' smallest indices (the bound falls with n)
}

}  // namespace

/// One Gauss-Legendre step on [a, b] for the count integrals at once, the
/// method of Arb's acb_calc_integrate_gl_auto_deg: |f_k| <= M_k/|delta| on
/// a Bernstein ellipse with semi-axes X, sqrt(X^2 - 1) (times
/// delta = (b - a)/2; f is bounded on the ellipse's bounding box, with
/// holomorphy certified) gives the error bound
/// (64/15) M_k / ((rho - 1) rho^(2n - 1)), rho = X + sqrt(X^2 - 1), of the
/// n-point rule; the smallest n below every tol[k] is evaluated at its nodes
/// (one call of f per node for all k). Arb tries X = 2, 4, 8, 32, ... until
/// f is not finite, and fails the step when X = 2 does. Here:
///   * the search stops once a larger ellipse could not save kEllipseCost
///     nodes even if |f| did not grow on it (so most steps do not end on a
///     failing ellipse, the costliest kind of call);
///   * where X = 2 fails, the largest X the singularity hints leave (when
///     it is at least kMidEllipseMin), then X = 5/4 (rho = 2), are tried
///     with up to kSmallEllipseDegLimit nodes before the step fails (which
///     bisects);
///   * with use_hints, an ellipse near a singularity hint is not evaluated
///     (counted as failing: QuadratureOptions::singularity_hints);
///   * nodes go to the NodeIntegrand first, when there is one, at prec <=
///     kNodeFastMaxPrec: its answers are weighted and summed in double-word
///     balls, the other nodes in Arb balls.
/// Every ellipse gives a rigorous bound, so the choice only moves the cost.
/// Returns ARB_CALC_SUCCESS with enclosures of the integrals in res[k], or
/// ARB_CALC_NO_CONVERGENCE (res indeterminate). *evals counts the calls of f.
int gl_step(acb_ptr res, long* evals, Context& ctx, const acb_t a, const acb_t b, const std::vector<MagVar>& tol,
            long deg_limit, bool use_hints, long prec) {
  const std::size_t count = ctx.count;
  AcbVar mid, delta, wide;
  AcbVec v(count), s(count);
  MagVar X, Y, rho, t, dm;
  std::vector<MagVar> M(count), best_M(count);
  *evals = 0;
  acb_sub(delta.v, b, a, prec);
  acb_mul_2exp_si(delta.v, delta.v, -1);
  acb_add(mid.v, a, b, prec);
  acb_mul_2exp_si(mid.v, mid.v, -1);
  acb_get_mag(dm.v, delta.v);
  // rho = X + sqrt(X^2 - 1), a lower bound
  auto rho_of = [&t](mag_t r, const mag_t x) {
    mag_mul_lower(r, x, x);
    mag_one(t.v);
    mag_sub_lower(r, r, t.v);
    mag_sqrt_lower(r, r);
    mag_add_lower(r, r, x);
  };
  // The singularity hints, once per step: a hint h at u = |Re h - mid| /
  // |delta|, v = |Im h| / |delta| lies in the bounding box of the ellipse X
  // enlarged kHintMargin times iff X >= u / margin and sqrt(X^2 - 1) >=
  // v / margin, i.e. X >= max(u / margin, sqrt(1 + (v / margin)^2)); x_free
  // is the least such X over the hints (infinity without hints), so the
  // ellipses X >= x_free are hinted: their bounds would not be finite, so
  // they are not evaluated, and the largest one below it is known.
  const double hm = arf_get_d(arb_midref(acb_realref(mid.v)), ARF_RND_NEAR);
  const double hd = std::fabs(arf_get_d(arb_midref(acb_realref(delta.v)), ARF_RND_NEAR));
  double x_free = std::numeric_limits<double>::infinity();
  if (use_hints && ctx.hints && hd > 0)
    for (const std::complex<double>& h : *ctx.hints) {
      const double u = std::fabs(h.real() - hm) / (kHintMargin * hd), v = std::fabs(h.imag()) / (kHintMargin * hd);
      x_free = std::min(x_free, std::max(u, std::sqrt(1 + v * v)));
    }
  auto hinted = [&](const mag_t x) { return mag_get_d(x) >= x_free; };
  // M_k = |delta| sup |f_k| on the ellipse X; false when f is not finite
  // there. f is bounded on the ellipse's bounding box first, as Arb does.
  // Where that is not finite and X <= 2, on a real interval (f real there),
  // on strips that cover the upper half of the ellipse, each up to the
  // ellipse's height over it (times delta, plus mid): by Schwarz's
  // reflection, G(z) = f(z) above the axis and conj f(conj z) below is
  // holomorphic on the ellipse, equals f on [a, b] and has the same bound,
  // which is all the Gauss-Legendre error bound asks. First the two halves
  // [-X, 0] x [0, Y] and [0, X] x [0, Y]; on the small ellipse X = 5/4,
  // where they fail, the four quarters [-X, -X/2], [-X/2, 0], [0, X/2],
  // [X/2, X] (height Y sqrt(3)/2 over the outer ones, Y over the inner
  // ones; the inner ones, the tallest and the likeliest to fail, first).
  // A strip's disc is far smaller than the bounding box's (at X = 2: 1.32
  // and 1.0 against 2.65, in units of delta), so its enclosure is far
  // tighter: one that reached a branch point's cut or a pole often no
  // longer does, and a centred form's overestimate near a nearly double
  // zero of a radicand (the space curves' sum K^2 near a branch point close
  // to the axis) shrinks with the radius. X = 2 then often serves where only
  // X = 5/4 did, with about half the nodes, and the quarters save
  // bisections where the small ellipse's halves fail: on bez-rat-space 12's
  // uniformity, 1836 nodes and 45 bisections a run with the bounding box
  // alone, 1228 and 30 with the halves at both ellipses. (The quarters at
  // X = 2 as well would take 888 nodes and 20 bisections there, with fewer
  // instructions, but cost 10% at degree 6, where the halves serve and
  // every strip is a complex centred form.) The halves are always tried: a
  // record of their failures would turn them off after the first,
  // hopeless, levels of the subdivision, where nothing serves.
  const bool real_interval = arb_is_zero(acb_imagref(mid.v)) && arb_is_zero(acb_imagref(delta.v));
  auto bound_on = [&](const mag_t x, bool quarters) {
    if (hinted(x)) return false;
    mag_mul(Y.v, x, x);  // Y = sqrt(X^2 - 1), an upper bound
    mag_one(t.v);
    mag_sub(Y.v, Y.v, t.v);
    mag_sqrt(Y.v, Y.v);
    // f on wide (a box in the ellipse's coordinates, set by the caller;
    // times delta, plus mid): the first box sets M, the others raise it
    auto on_box = [&](bool first) {
      acb_mul(wide.v, wide.v, delta.v, prec);
      acb_add(wide.v, wide.v, mid.v, prec);
      call(ctx, v.v, wide.v, true, prec);
      ++*evals;
      for (std::size_t k = 0; k < count; ++k) {
        if (!acb_is_finite(v.v + k)) return false;
        MagVar mk;
        acb_get_mag(mk.v, v.v + k);
        mag_mul(mk.v, mk.v, dm.v);
        if (first) mag_set(M[k].v, mk.v);
        else mag_max(M[k].v, M[k].v, mk.v);
      }
      return true;
    };
    acb_zero(wide.v);  // the bounding box [-X, X] x [-Y, Y]
    mag_set(arb_radref(acb_realref(wide.v)), x);
    mag_set(arb_radref(acb_imagref(wide.v)), Y.v);
    if (on_box(true)) return true;
    if (!real_interval || mag_cmp_2exp_si(x, 1) > 0) return false;
    // the m = 2 or 4 strips j = 0 .. m-1, [-X + 2jX/m, -X + 2(j+1)X/m] x
    // [0, the ellipse's height over it], the inner ones first
    MagVar h;
    auto strips = [&](int m) {
      static constexpr int kOrder2[] = {0, 1}, kOrder4[] = {1, 2, 0, 3};
      for (int i = 0; i < m; ++i) {
        const int j = m == 2 ? kOrder2[i] : kOrder4[i];
        if (m == 4 && (j == 0 || j == 3)) {
          mag_set_d(h.v, 0.86602540378445);  // >= sqrt(3)/2
          mag_mul(h.v, h.v, Y.v);
        } else {
          mag_set(h.v, Y.v);
        }
        acb_zero(wide.v);
        arf_set_mag(arb_midref(acb_realref(wide.v)), x);  // centre (2j + 1 - m) X/m (exact), radius X/m
        arb_mul_si(acb_realref(wide.v), acb_realref(wide.v), 2 * j + 1 - m, prec);
        arb_mul_2exp_si(acb_realref(wide.v), acb_realref(wide.v), m == 2 ? -1 : -2);
        mag_mul_2exp_si(arb_radref(acb_realref(wide.v)), x, m == 2 ? -1 : -2);
        arf_set_mag(arb_midref(acb_imagref(wide.v)), h.v);  // [0, h]
        arb_mul_2exp_si(acb_imagref(wide.v), acb_imagref(wide.v), -1);
        mag_mul_2exp_si(arb_radref(acb_imagref(wide.v)), h.v, -1);
        if (!on_box(i == 0)) return false;
      }
      return true;
    };
    // the halves; with `quarters` (the small ellipse, the last before a
    // bisection) the quarters where they fail
    return strips(2) || (quarters && strips(4));
  };
  // best: the fewest nodes found so far, with the M_k and rho it was found with
  int best = -1;
  MagVar best_rho;
  auto consider = [&](long deg) {
    rho_of(rho.v, X.v);
    const int i = gl_degree(M, rho.v, tol, deg);
    if (i >= 0 && (best < 0 || i < best)) {
      best = i;
      mag_set(best_rho.v, rho.v);
      for (std::size_t k = 0; k < count; ++k) mag_set(best_M[k].v, M[k].v);
    }
  };
  for (long Xexp = 0; Xexp < prec; Xexp += std::max(1L, Xexp)) {
    mag_one(X.v);
    mag_mul_2exp_si(X.v, X.v, Xexp + 1);
    if (!bound_on(X.v, false)) {
      if (Xexp == 0) {
        // X = 2 failed: first the largest ellipse the hints leave, when it
        // lies well between 5/4 and 2, then the small ellipse X = 5/4
        const double xh = x_free * (1 - 0x1p-10);  // not hinted, after mag_set_d's rounding up
        if (xh >= kMidEllipseMin && xh < 2) {
          mag_set_d(X.v, xh);
          if (bound_on(X.v, false)) consider(std::max(deg_limit, kSmallEllipseDegLimit));
        }
        if (best < 0) {
          mag_set_ui_2exp_si(X.v, 5, -2);
          if (bound_on(X.v, true)) consider(std::max(deg_limit, kSmallEllipseDegLimit));
        }
      }
      break;
    }
    consider(deg_limit);
    if (best == 0) break;
    if (best > 0) {
      // The next ellipse, optimistically with the same M: is it worth it?
      const long next = Xexp + std::max(1L, Xexp);
      if (next >= prec) break;
      mag_one(X.v);
      mag_mul_2exp_si(X.v, X.v, next + 1);
      rho_of(rho.v, X.v);
      const int j = gl_degree(M, rho.v, tol, deg_limit);
      if (j < 0 || kGlSteps[best] - kGlSteps[j] < kEllipseCost) break;
    }
  }
  if (best < 0) {
    _acb_vec_indeterminate(res, static_cast<slong>(count));
    return ARB_CALC_NO_CONVERGENCE;
  }
  const long n = kGlSteps[best];
  const GlRule* rule_ptr = nullptr;
  try {
    rule_ptr = &gl_rule(best, prec);
  } catch (...) {  // the time budget: stored like an Integrand's exception, rethrown by integrate_many
    ctx.error = std::current_exception();
  }
  if (!rule_ptr) {
    _acb_vec_zero(res, static_cast<slong>(count));
    return ARB_CALC_SUCCESS;
  }
  const GlRule& rule = *rule_ptr;
  arb_t x;
  arb_init(x);
  _acb_vec_zero(s.v, static_cast<slong>(count));
  // The nodes NodeIntegrand answers are summed in double words (dsum), the
  // others in Arb balls (s); both are rigorous and added at the end.
  DDBall dmid, ddelta;
  bool fast = ctx.node_fast && *ctx.node_fast && prec <= kNodeFastMaxPrec && arb_is_zero(acb_imagref(mid.v)) &&
              arb_is_zero(acb_imagref(delta.v)) && dd_set_arb(dmid, acb_realref(mid.v)) &&
              dd_set_arb(ddelta, acb_realref(delta.v));
  std::vector<DDBall> dsum(fast ? count : 0, DDBall{});
  bool any_fast = false;
  for (long k = 0; k < n; ++k) {
    // nodes x_0 > x_1 > ... > 0 > ... > -x_0: the rule holds the positive half
    const slong kk = 2 * k < n ? k : n - 1 - k;
    if (fast) {
      const DDBall& xk = rule.dx[static_cast<std::size_t>(kk)];
      const DDBall t = dd_add(dmid, dd_mul(ddelta, 2 * k < n ? xk : dd_neg(xk)));
      bool answered = false;
      if (!ctx.error && dd_is_finite(t)) {
        try {
          answered = (*ctx.node_fast)(ctx.dd_out.data(), t, prec);
        } catch (...) {
          ctx.error = std::current_exception();  // call() answers 0 from now on; integrate_many rethrows
        }
      }
      if (answered) {
        const DDBall& wk = rule.dw[static_cast<std::size_t>(kk)];
        bool ok = true;
        for (std::size_t j = 0; j < count; ++j) {
          ctx.dd_out[j] = dd_mul(wk, ctx.dd_out[j]);
          ok = ok && dd_is_finite(ctx.dd_out[j]);
        }
        if (ok) {  // otherwise the node goes to the Integrand
          for (std::size_t j = 0; j < count; ++j) dsum[j] = dd_add(dsum[j], ctx.dd_out[j]);
          any_fast = true;
          continue;
        }
      }
    }
    if (2 * k < n) arb_set_round(x, rule.x + kk, prec);
    else arb_neg_round(x, rule.x + kk, prec);
    acb_mul_arb(wide.v, delta.v, x, prec);
    acb_add(wide.v, wide.v, mid.v, prec);
    call(ctx, v.v, wide.v, false, prec);
    arb_set_round(x, rule.w + kk, prec);
    for (std::size_t j = 0; j < count; ++j) acb_addmul_arb(s.v + j, v.v + j, x, prec);
  }
  arb_clear(x);
  for (std::size_t j = 0; j < count && any_fast; ++j) {
    if (!dd_is_finite(dsum[j])) {  // a sum overflowed: nothing is known
      acb_indeterminate(s.v + j);
      continue;
    }
    AcbVar part;
    dd_get_arb(acb_realref(part.v), dsum[j]);
    acb_add(s.v + j, s.v + j, part.v, prec);
  }
  *evals += n;
  MagVar err;
  for (std::size_t j = 0; j < count; ++j) {
    acb_mul(res + j, s.v + j, delta.v, prec);
    gl_error(err.v, best_M[j].v, best_rho.v, n);
    acb_add_error_mag(res + j, err.v);
  }
  return ARB_CALC_SUCCESS;
}

}  // namespace quadrature_detail
}  // namespace uniparam
