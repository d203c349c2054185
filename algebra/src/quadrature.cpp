#include "uniparam/algebra/quadrature.hpp"

#include <acb_calc.h>
#include <arb_hypgeom.h>
#include <arf.h>
#include <mag.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <deque>
#include <exception>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

/// RAII holders for the few Arb temporaries, so that an exception thrown by
/// the integrand (rethrown below) leaks nothing.
struct AcbVar {
  acb_t v;
  AcbVar() noexcept { acb_init(v); }
  ~AcbVar() { acb_clear(v); }
  AcbVar(const AcbVar&) = delete;
  AcbVar& operator=(const AcbVar&) = delete;
};
struct MagVar {
  mag_t v;
  MagVar() noexcept { mag_init(v); }
  ~MagVar() { mag_clear(v); }
  MagVar(const MagVar&) = delete;
  MagVar& operator=(const MagVar&) = delete;
};

/// count enclosures (an acb vector), freed on scope exit.
struct AcbVec {
  acb_ptr v;
  slong n;
  explicit AcbVec(std::size_t count) : v(_acb_vec_init(static_cast<slong>(count))), n(static_cast<slong>(count)) {}
  ~AcbVec() { _acb_vec_clear(v, n); }
  AcbVec(const AcbVec&) = delete;
  AcbVec& operator=(const AcbVec&) = delete;
};

/// The integrand and its state during one attempt.
struct Context {
  const Integrand* f;
  std::size_t count;         ///< values f writes per call
  std::exception_ptr error;  ///< first exception thrown by *f, rethrown after the attempt
  long wide_prec;            ///< precision for wide balls (see integrate)
  const std::vector<std::complex<double>>* hints = nullptr;  ///< QuadratureOptions::singularity_hints
  const NodeIntegrand* node_fast = nullptr;                  ///< QuadratureOptions::node_fast (may be empty)
  std::vector<DDBall> dd_out;                                ///< node_fast's outputs
};

/// True for the balls of the error bounds (a subinterval's segment or
/// ellipse), as opposed to the Gauss-Legendre nodes: radius >= 2^-30.
bool is_wide(const acb_t z) {
  return mag_cmp_2exp_si(arb_radref(acb_realref(z)), -30) >= 0 || mag_cmp_2exp_si(arb_radref(acb_imagref(z)), -30) >= 0;
}

/// out[0 .. count) = f(z). No exception leaves: the first one is stored, and
/// from then on every call answers exact 0s without calling f, so that
/// every subinterval is accepted at once (indeterminate answers would make
/// the subdivision bisect up to eval_limit); the enclosure of that attempt
/// is discarded and integrate_many() rethrows. `analytic`: f must also
/// certify holomorphy on z (the ellipses of the error bounds).
void call(Context& ctx, acb_ptr out, const acb_t z, bool analytic, long prec) {
  if (!ctx.error) {
    try {
      check_time_budget();  // --timeout, noticed within one evaluation
      // A wide ball's enclosure is as wide as f's variation on it: the bits
      // of the goal buy nothing there (only those lost to cancellation do).
      (*ctx.f)(out, z, analytic, is_wide(z) ? std::min(prec, ctx.wide_prec) : prec);
      return;
    } catch (...) {
      ctx.error = std::current_exception();
    }
  }
  _acb_vec_zero(out, static_cast<slong>(ctx.count));
}

// Guard bits of the relative goal over the caller's goal: the
// per-subinterval tolerances add up over at most a few thousand
// subintervals (~12 bits). More only raises the Gauss-Legendre degrees.
constexpr long kGoalGuardBits = 12;

/// f on the whole segment [a, b] (a ball) times b - a: the direct
/// enclosure of each integral, crude but rigorous for any f that answers
/// finite enclosures on the segment.
void direct_estimate(acb_ptr res, Context& ctx, const acb_t a, const acb_t b, long prec) {
  AcbVar mid, delta, wide;
  MagVar m;
  acb_sub(delta.v, b, a, prec);
  acb_mul_2exp_si(delta.v, delta.v, -1);  // (b - a) / 2
  acb_add(mid.v, a, b, prec);
  acb_mul_2exp_si(mid.v, mid.v, -1);
  acb_set(wide.v, mid.v);
  arb_get_mag(m.v, acb_realref(delta.v));
  arb_add_error_mag(acb_realref(wide.v), m.v);
  arb_get_mag(m.v, acb_imagref(delta.v));
  arb_add_error_mag(acb_imagref(wide.v), m.v);
  call(ctx, res, wide.v, false, prec);
  for (std::size_t k = 0; k < ctx.count; ++k) {
    acb_mul(res + k, res + k, delta.v, prec);
    acb_mul_2exp_si(res + k, res + k, 1);
  }
}

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

/// Depth from which a subinterval where Gauss-Legendre failed is also tried
/// with the direct enclosure (accepted when its radius is below the
/// tolerance). Above it the interval is at least 2^-kDirectDepth of the
/// whole, and a direct enclosure (width times |f|) cannot meet a tolerance
/// of 2^-goal of the integral unless f is tiny there.
constexpr long kDirectDepth = 12;

/// Raises tol[k] to 2^-goal times a lower bound of |u[k]| (Arb's rule: the
/// tolerance follows the largest piece seen).
void raise_tolerances(std::vector<MagVar>& tol, acb_srcptr u, long goal) {
  MagVar lower;
  for (std::size_t k = 0; k < tol.size(); ++k) {
    acb_get_mag_lower(lower.v, u + k);
    mag_mul_2exp_si(lower.v, lower.v, -goal);
    mag_max(tol[k].v, tol[k].v, lower.v);
  }
}

/// Adaptive Gauss-Legendre quadrature of count integrals at once: Arb's
/// acb_calc_integrate without its direct evaluation of f on every
/// subinterval before the Gauss-Legendre attempt. Arb uses that evaluation
/// to skip hopeless attempts and to accept tiny subintervals; on the
/// quadrature of a speed it is the costliest kind of call (a wide real
/// segment: new local expansions of every factor, and often the factored
/// form), and it is wasted on every subinterval where Gauss-Legendre
/// succeeds. Here each subinterval goes to gl_step (which bounds f on
/// ellipses and evaluates it at its nodes) first; where that fails it is
/// bisected, and from depth kDirectDepth on the direct enclosure is tried
/// first. Every accepted piece is a rigorous enclosure (Arb's error bound
/// included), so the sums are. The tolerances follow Arb, per integral: an
/// absolute tolerance `tol` per subinterval, raised to 2^-goal times the
/// largest lower bound of an accepted piece (or of the direct enclosure on
/// [a, b]); a subinterval is accepted when every integral meets its own.
/// Returns ARB_CALC_SUCCESS, or ARB_CALC_NO_CONVERGENCE when eval_limit or
/// depth_limit stopped the subdivision (the remaining subintervals then hold
/// their direct enclosures: still rigorous, maybe wide or not finite).
int adaptive_integrate(acb_ptr res, Context& ctx, const acb_t a, const acb_t b, long goal, const mag_t tol,
                       long eval_limit, long depth_limit, long prec) {
  const std::size_t count = ctx.count;
  goal = std::max(goal, 0L);
  const long deg_limit = static_cast<long>(0.5 * static_cast<double>(goal) + 10);  // Arb's default
  if (depth_limit <= 0) depth_limit = 2 * prec;
  if (eval_limit <= 0) eval_limit = 1000 * prec + prec * prec;

  struct Interval {
    AcbVar a, b;
    long depth = 0;
  };
  std::vector<std::unique_ptr<Interval>> stack;
  auto push = [&](const acb_t x, const acb_t y, long depth) {
    auto iv = std::make_unique<Interval>();
    acb_set(iv->a.v, x);
    acb_set(iv->b.v, y);
    iv->depth = depth;
    stack.push_back(std::move(iv));
  };

  AcbVar diff;
  AcbVec sum(count), u(count);
  MagVar rad;
  std::vector<MagVar> new_tol(count);
  for (auto& t : new_tol) mag_set(t.v, tol);
  // Tolerances from a lower bound of the whole integrals (as Arb does).
  direct_estimate(u.v, ctx, a, b, prec);
  long evals = 1;
  raise_tolerances(new_tol, u.v, goal);

  int status = ARB_CALC_SUCCESS;
  push(a, b, 0);
  while (!stack.empty()) {
    std::unique_ptr<Interval> iv = std::move(stack.back());
    stack.pop_back();
    acb_sub(diff.v, iv->b.v, iv->a.v, prec);
    const bool stop = status != ARB_CALC_SUCCESS;
    if (stop || acb_contains_zero(diff.v)) {
      // Out of budget, or an interval narrower than its ends' enclosures.
      direct_estimate(u.v, ctx, iv->a.v, iv->b.v, prec);
      ++evals;
      _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
      continue;
    }
    long feval = 0;
    const int gl = gl_step(u.v, &feval, ctx, iv->a.v, iv->b.v, new_tol, deg_limit, iv->depth < kDirectDepth, prec);
    evals += feval;
    if (gl == ARB_CALC_SUCCESS) {
      _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
      raise_tolerances(new_tol, u.v, goal);
      continue;
    }
    if (iv->depth >= kDirectDepth) {
      direct_estimate(u.v, ctx, iv->a.v, iv->b.v, prec);
      ++evals;
      bool small = true;
      for (std::size_t k = 0; k < count && small; ++k) {
        mag_hypot(rad.v, arb_radref(acb_realref(u.v + k)), arb_radref(acb_imagref(u.v + k)));
        small = mag_cmp(rad.v, new_tol[k].v) < 0;
      }
      if (small) {
        _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
        continue;
      }
    }
    if (iv->depth + 1 >= depth_limit || evals >= eval_limit) {
      status = ARB_CALC_NO_CONVERGENCE;
      push(iv->a.v, iv->b.v, iv->depth);  // taken again, with its direct enclosure
      continue;
    }
    AcbVar m;
    acb_add(m.v, iv->a.v, iv->b.v, prec);
    acb_mul_2exp_si(m.v, m.v, -1);
    push(m.v, iv->b.v, iv->depth + 1);  // right half after the left one
    push(iv->a.v, m.v, iv->depth + 1);
  }
  _acb_vec_set(res, sum.v, static_cast<slong>(count));
  return status;
}

/// node_fast's values at the narrow real ball t, as Arb balls in
/// out[0 .. count): true when there is a node_fast, prec <= kNodeFastMaxPrec
/// and it answered finite balls (then they hold f_k on t, by its contract);
/// false otherwise (out unspecified), and the caller asks f. Exceptions from
/// node_fast propagate.
bool fast_point(acb_ptr out, const NodeIntegrand& fast, std::size_t count, const arb_t t, long prec) {
  if (!fast || prec > kNodeFastMaxPrec) return false;
  DDBall x;
  if (!dd_set_arb(x, t)) return false;
  std::vector<DDBall> v(count);
  if (!fast(v.data(), x, prec)) return false;
  for (std::size_t k = 0; k < count; ++k)
    if (!dd_is_finite(v[k])) return false;
  for (std::size_t k = 0; k < count; ++k) {
    dd_get_arb(acb_realref(out + k), v[k]);
    arb_zero(acb_imagref(out + k));
  }
  return true;
}

/// add_end_error first bounds f on the ball of radius 2^kEndWideExp around
/// the end (see there).
constexpr long kEndWideExp = -12;

/// Adds rad(end) * sup |f_k(end)| to the error of each res[k]: the integral
/// over the piece between the true end and the midpoint of its enclosure
/// `end`. The bound is node_fast's where it answers, else f's.
void add_end_error(acb_ptr res, const Integrand& f, const NodeIntegrand& fast, std::size_t count, const Ball& end,
                   long prec) {
  const mag_struct* rad = arb_radref(end.get());
  if (mag_is_zero(rad)) return;  // exact dyadic end: nothing to add, f not evaluated
  AcbVar z;
  AcbVec fz(count);
  if (!fast_point(fz.v, fast, count, end.get(), prec)) {
    // First on a wider ball around the end (a superset: its bound holds on
    // the end ball too): wide balls take cheap coarse evaluations, while a
    // narrow one needs accurate local expansions there, built for this one
    // point (integrands next to a zero of the speed, where node_fast refuses
    // the end). Where that bound is not finite, the end ball itself.
    acb_set_arb(z.v, end.get());
    if (mag_cmp_2exp_si(rad, kEndWideExp) < 0) {
      AcbVar w;
      acb_set(w.v, z.v);
      mag_set_ui_2exp_si(arb_radref(acb_realref(w.v)), 1, kEndWideExp);
      f(fz.v, w.v, false, prec);  // exceptions propagate; the holders clean up
    }
    bool finite = mag_cmp_2exp_si(rad, kEndWideExp) < 0;
    for (std::size_t k = 0; k < count && finite; ++k) finite = acb_is_finite(fz.v + k);
    if (!finite) f(fz.v, z.v, false, prec);
  }
  MagVar bound;
  for (std::size_t k = 0; k < count; ++k) {
    acb_get_mag(bound.v, fz.v + k);  // upper bound of |f_k| on the end ball (inf if not finite)
    mag_mul(bound.v, bound.v, rad);
    acb_add_error_mag(res + k, bound.v);
  }
}

/// radius <= 2^-rel * |mid| (with a lower bound of |mid|), or radius <=
/// 2^-abs when abs > 0; false for a non-finite ball.
bool meets_goal(const Ball& r, const QuadratureOptions& opt) {
  if (!r.is_finite()) return false;
  const mag_struct* rad = arb_radref(r.get());
  if (opt.abs_goal_bits > 0 && mag_cmp_2exp_si(rad, -opt.abs_goal_bits) <= 0) return true;
  MagVar m;
  arf_get_mag_lower(m.v, arb_midref(r.get()));
  mag_mul_2exp_si(m.v, m.v, -opt.rel_goal_bits);
  return mag_cmp(rad, m.v) <= 0;
}

/// Bits that evaluating f loses to cancellation on [a, b] (e.g. a power-basis
/// polynomial of high degree with large alternating coefficients): f at 7
/// interior points at precision `prec`, absolute radius against the largest
/// |f_k| seen, the worst k. The first attempt then starts that much higher
/// instead of failing and doubling. 0 when nothing can be measured; an
/// exception from f propagates (as from the quadrature itself).
/// A point node_fast answers is asked of node_fast alone and counts as no
/// loss: its answers meet the nodes' accuracy contract at this precision,
/// and the nodes it answers never reach f. (Its accepted radius,
/// 2^-(prec - kNodeFastSlackBits), read as cancellation, would raise the
/// start precision by that much, often past kNodeFastMaxPrec, where every
/// node then went to f.)
long cancellation_bits(const Integrand& f, const NodeIntegrand& fast, std::size_t count, const Ball& a,
                       const Ball& b, long prec) {
  long worst = 0;
  AcbVar z;
  AcbVec fz(count);
  std::vector<MagVar> big(count), rads(7 * count);
  for (int j = 0; j < 7; ++j) {
    // z = a + (b - a) (j + 1) / 8 at exact dyadic midpoints
    arb_sub(acb_realref(z.v), b.get(), a.get(), prec);
    arb_mul_si(acb_realref(z.v), acb_realref(z.v), j + 1, prec);
    arb_mul_2exp_si(acb_realref(z.v), acb_realref(z.v), -3);
    arb_add(acb_realref(z.v), acb_realref(z.v), a.get(), prec);
    mag_zero(arb_radref(acb_realref(z.v)));
    arb_zero(acb_imagref(z.v));
    const bool answered = fast_point(fz.v, fast, count, acb_realref(z.v), prec);
    if (!answered) f(fz.v, z.v, false, prec);
    for (std::size_t k = 0; k < count; ++k) {
      if (!acb_is_finite(fz.v + k)) return prec;  // everything lost (or a true pole: the real run reports it)
      MagVar m;
      acb_get_mag(m.v, fz.v + k);
      if (mag_cmp(m.v, big[k].v) > 0) mag_set(big[k].v, m.v);
      if (!answered)  // (zero: no loss)
        mag_hypot(rads[j * count + k].v, arb_radref(acb_realref(fz.v + k)), arb_radref(acb_imagref(fz.v + k)));
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (mag_is_zero(big[k].v)) continue;
    for (int j = 0; j < 7; ++j) {
      const MagVar& r = rads[j * count + k];
      if (mag_is_zero(r.v)) continue;
      // accuracy = log2(big / rad); loss = prec - accuracy
      const long acc = fmpz_get_si(MAG_EXPREF(big[k].v)) - fmpz_get_si(MAG_EXPREF(r.v));
      worst = std::max(worst, prec - acc);
    }
  }
  return std::max(0L, worst);
}

std::string goal_text(const QuadratureOptions& opt) {
  std::string s = std::to_string(opt.rel_goal_bits) + " bits";
  if (opt.abs_goal_bits > 0) s += " (or absolute error 2^-" + std::to_string(opt.abs_goal_bits) + ")";
  return s;
}

}  // namespace

std::vector<Ball> integrate_many(const Integrand& f, std::size_t count, const RealAlgebraic& a,
                                 const RealAlgebraic& b, const QuadratureOptions& opt) {
  if (!f) throw InvalidArgument("integrate: empty integrand");
  if (count == 0) throw InvalidArgument("integrate: at least one integral is needed");
  if (opt.rel_goal_bits < 0 || opt.abs_goal_bits < 0)
    throw InvalidArgument("integrate: accuracy goals must be non-negative");
  if (opt.max_prec < 2) throw InvalidArgument("integrate: max_prec must be at least 2 bits");
  if (opt.initial_prec < 0) throw InvalidArgument("integrate: initial_prec must be non-negative");
  if (opt.scale_bits < 0) throw InvalidArgument("integrate: scale_bits must be non-negative");
  const int c = compare(a, b);
  if (c > 0) throw InvalidArgument("integrate: lower end " + a.str() + " exceeds upper end " + b.str());
  if (c == 0) return std::vector<Ball>(count, Ball(0L));

  // The end enclosures at each precision used, converted once: the probe and
  // the first attempt share a precision, and RealAlgebraic::to_ball keeps
  // only its last precision (which the integrand may change in between, e.g.
  // when it evaluates the same algebraic number). to_ball depends on
  // (x, prec) alone, so these are the balls a direct call gives.
  struct EndBalls {
    long prec;
    Ball a, b;
  };
  std::deque<EndBalls> end_balls;  // references stay valid as it grows
  auto ends_at = [&](long p) -> const EndBalls& {
    for (const EndBalls& e : end_balls)
      if (e.prec == p) return e;
    end_balls.push_back(EndBalls{p, a.to_ball(p), b.to_ball(p)});
    return end_balls.back();
  };

  long start = opt.initial_prec > 0 ? opt.initial_prec : opt.rel_goal_bits + 32;
  start = std::min(std::max(start, 2L), opt.max_prec);
  if (opt.initial_prec == 0) {
    // Start above the precision that cancellation in f would eat, measured
    // at the precision that is then used (a total loss doubles it first).
    const long base = start;
    for (int round = 0; round < 4 && start < opt.max_prec; ++round) {
      const EndBalls& e = ends_at(start);
      const long lost = cancellation_bits(f, opt.node_fast, count, e.a, e.b, start);
      const long need = lost >= start ? 2 * start : base + lost;
      if (need <= start + 16) break;
      start = std::min(need, opt.max_prec);
    }
  }

  std::vector<Ball> last(count);
  bool converged = false;
  long prec = start;
  for (;;) {
    check_time_budget();
    // eval_limit 0: Arb's default (1000 prec + prec^2), capped so that one
    // hopeless attempt at thousands of bits cannot run for hours.
    // scale_bits adds its levels' evaluations (and depth) beyond that cap.
    const long eval_limit = opt.eval_limit > 0 ? opt.eval_limit
                                               : std::min(1000 * prec + prec * prec, 2000000L) +
                                                     kEvalsPerScaleBit * opt.scale_bits;
    const long depth_limit = opt.depth_limit > 0 ? opt.depth_limit : 2 * prec + opt.scale_bits;
    const EndBalls& ends = ends_at(prec);
    const Ball& ea = ends.a;
    const Ball& eb = ends.b;
    AcbVar ma, mb;
    AcbVec res(count);
    arb_set_arf(acb_realref(ma.v), arb_midref(ea.get()));  // exact dyadic midpoints
    arb_set_arf(acb_realref(mb.v), arb_midref(eb.get()));

    // Relative goal: rel_goal_bits + kGoalGuardBits (for the sum over
    // subintervals), raised with each retry; never the extra precision that
    // only pays for cancellation in f (asking for it would double the nodes
    // and subintervals for nothing). Absolute tolerance: 2^-prec, or
    // 2^-(abs_goal_bits + 32 + growth) when an absolute goal is set,
    // tightened with the precision so a retry helps.
    long tol_bits = prec;
    if (opt.abs_goal_bits > 0) tol_bits = std::min(prec, opt.abs_goal_bits + 32 + (prec - start));
    MagVar tol;
    mag_set_ui_2exp_si(tol.v, 1, -tol_bits);
    const long goal = std::min(prec, opt.rel_goal_bits + kGoalGuardBits + (prec - start));

    // Wide balls (error bounds) at the bits lost to cancellation plus 64:
    // prec - rel_goal_bits is what the start precision added for them.
    Context ctx{&f, count, nullptr, std::max(64L, prec - opt.rel_goal_bits + 32), &opt.singularity_hints,
                &opt.node_fast, std::vector<DDBall>(count)};
    const int status = adaptive_integrate(res.v, ctx, ma.v, mb.v, goal, tol.v, eval_limit, depth_limit, prec);
    if (ctx.error) std::rethrow_exception(ctx.error);
    // The enclosures are valid whatever the status; NO_CONVERGENCE only
    // means they may be wide, which the goal check below sees.
    converged = status == ARB_CALC_SUCCESS;

    add_end_error(res.v, f, opt.node_fast, count, ea, prec);
    add_end_error(res.v, f, opt.node_fast, count, eb, prec);

    bool met = true;
    for (std::size_t k = 0; k < count; ++k) {
      if (!arb_contains_zero(acb_imagref(res.v + k)))
        throw DomainError("integrate: " + opt.what + " is not real: the integrand is not real-valued on [" +
                          a.str() + ", " + b.str() + "]");
      last[k] = Ball(acb_realref(res.v + k));
      met = met && meets_goal(last[k], opt);
    }
    if (met) return last;
    if (prec >= opt.max_prec) break;
    prec = prec > opt.max_prec / 2 ? opt.max_prec : 2 * prec;
  }
  std::string enclosures;
  for (std::size_t k = 0; k < count; ++k) enclosures += (k ? ", " : "") + last[k].str(10);
  throw BudgetExceeded("could not certify " + opt.what + " to " + goal_text(opt) + " within " +
                       std::to_string(prec) + " bits of working precision (last enclosure" +
                       (count > 1 ? "s " : " ") + enclosures + (converged ? "" : ", quadrature did not converge") +
                       "); raise --max-prec");
}

Ball integrate(const Integrand& f, const RealAlgebraic& a, const RealAlgebraic& b, const QuadratureOptions& opt) {
  return std::move(integrate_many(f, 1, a, b, opt).front());
}

}  // namespace uniparam
