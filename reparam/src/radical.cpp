#include "uniparam/reparam/radical.hpp"

#include <algorithm>
#include <memory>
#include <stdexcept>

#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "moebius_detail.hpp"
#include "moebius_map.hpp"

namespace uniparam {

int RadicalResult::root_index(std::size_t i) const {
  if (T[i].multiplicity > 0) return T[i].multiplicity + 1;
  if (T[i + 1].multiplicity > 0) return T[i + 1].multiplicity + 1;
  return 1;
}

ZeroSide RadicalResult::side(std::size_t i) const {
  if (T[i].multiplicity > 0) return ZeroSide::Left;
  if (T[i + 1].multiplicity > 0) return ZeroSide::Right;
  return ZeroSide::None;
}

namespace {

// radical() for the speed s (options checked).
RadicalResult radical_on(const Speed& s, const Options& opt) {
  RadicalResult r;
  r.kind = s.kind();
  r.identically_zero = s.identically_zero();
  if (r.identically_zero) {
    r.T = critical_breakpoints(s);
    r.mu = Ball(0);
    r.u_before = Ball(1);
    r.S = r.Z = {Ball(0), Ball(1)};
    r.u_radical = r.u_after = Ball(1);
    r.integrals.assign(1, piece_integrals(s, r.T[0], r.T[1], 64, opt.max_prec));
    r.A = r.B = r.C = {Ball(0)};
    return r;
  }
  // mu (its own parallel loop) and the critical points (one serial root
  // isolation of a polynomial of degree ~12d for a space curve) do not
  // depend on each other: side by side, the isolation fills the cores mu's
  // tasks leave idle. The second task works on its own copy of the speed
  // (caches are shared and locked, see LocalPoly and RealAlgebraic). The
  // results do not depend on the threads.
  // The integral of sigma^2 for u_before is not computed here: a piece
  // without zeros has L_i = Delta t_i int sigma^2 over it (rho = Delta t),
  // so only the pieces with a zero at an end need their own.
  long mu_bits = digits_to_bits(opt.digits);
  {
    const Speed s_copy = s;
    parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t i) {
      if (i == 0) r.mu = mean_speed(s, mu_bits, opt);
      else r.T = critical_breakpoints(s_copy);
    });
  }
  const std::size_t N = r.T.size() - 1;
  bool raise_mu = false;
  for (long bits = digits_to_bits(opt.digits) + 8;; bits += 32) {
    check_time_budget();
    const long prec = 2 * bits + 64;
    if (raise_mu && bits > mu_bits) {
      mu_bits = bits;
      r.mu = mean_speed(s, mu_bits, opt);
    }
    r.integrals = all_piece_integrals(s, r.T, bits, opt.max_prec);
    std::vector<Ball> sqrtL(N), sqrtM(N);
    Ball sumL(0), sumM(0), mean_square(0);
    for (std::size_t i = 0; i < N; ++i) {
      arb_sqrt(sqrtL[i].get(), r.integrals[i].L.get(), prec);
      arb_sqrt(sqrtM[i].get(), r.integrals[i].M.get(), prec);
      arb_add(sumL.get(), sumL.get(), sqrtL[i].get(), prec);
      arb_add(sumM.get(), sumM.get(), sqrtM[i].get(), prec);
      const Ball part = piece_square_integral(s, r.T[i], r.T[i + 1], r.integrals[i], bits, opt.max_prec);
      arb_add(mean_square.get(), mean_square.get(), part.get(), prec);
    }
    r.S = cumulative_normalised(sqrtL, sumL, prec);
    r.Z = cumulative_normalised(sqrtM, sumM, prec);
    r.A.clear();
    r.B.clear();
    r.C.clear();
    for (std::size_t i = 0; i < N; ++i) {
      Ball ds, x;
      arb_sub(ds.get(), r.S[i + 1].get(), r.S[i].get(), prec);
      arb_div(x.get(), r.integrals[i].A.get(), ds.get(), prec);
      r.A.push_back(x);
      arb_div(x.get(), r.integrals[i].B.get(), ds.get(), prec);
      r.B.push_back(x);
      arb_div(x.get(), r.integrals[i].C.get(), ds.get(), prec);
      r.C.push_back(x);
    }
    Ball mu2;
    arb_mul(mu2.get(), r.mu.get(), r.mu.get(), prec);
    arb_div(r.u_before.get(), mu2.get(), mean_square.get(), prec);
    arb_mul(sumL.get(), sumL.get(), sumL.get(), prec);
    arb_div(r.u_radical.get(), mu2.get(), sumL.get(), prec);
    arb_mul(sumM.get(), sumM.get(), sumM.get(), prec);
    arb_div(r.u_after.get(), mu2.get(), sumM.get(), prec);

    const long d = opt.digits + 1;
    const bool mu_ok = r.mu.meets_digits(d) && r.u_before.meets_digits(d) && r.u_radical.meets_digits(d) &&
                       r.u_after.meets_digits(d);
    bool ok = mu_ok && all_meet_digits(r.S, d) && all_meet_digits(r.Z, d) && all_meet_digits(r.A, d) && all_meet_digits(r.B, d) &&
              all_meet_digits(r.C, d);
    for (const auto& pi : r.integrals) ok = ok && pi.L.meets_digits(d) && pi.M.meets_digits(d) && pi.alpha.meets_digits(d);
    if (ok) return r;
    // the quantities made with mu: mu may be the one short of accuracy
    raise_mu = !mu_ok;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the radical reparameterization to " + std::to_string(opt.digits) +
                           " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

// rq, radical() on bal.q, composed with m: the same map on p
// (RadicalResult::balanced), with p's breakpoints and u_before.
RadicalResult compose_balanced(const Speed& sp, const std::shared_ptr<const BalancedCurve>& bal,
                               const RadicalResult& rq, const Ball& u_before, long digits) {
  RadicalResult r = rq;
  std::vector<RealAlgebraic> ts;
  for (const Breakpoint& b : rq.T) ts.push_back(balance_map(*bal, b.t));
  r.T = mark_zeros(sp, ts);
  for (std::size_t i = 0; i < r.T.size(); ++i)
    if (r.T[i].multiplicity != rq.T[i].multiplicity)
      throw std::logic_error("radical: the balanced curve's zeros do not map onto the curve's");
  const long prec = detail::balanced_prec(*bal, digits);
  r.outer_k.clear();
  for (std::size_t i = 0; i + 1 < rq.T.size(); ++i) r.outer_k.push_back(balance_local_k(*bal, rq.T[i].t, rq.T[i + 1].t, prec));
  r.u_before = u_before;
  r.balanced = RadicalResult::Balanced{bal, std::make_shared<const RadicalResult>(rq)};
  return r;
}

}  // namespace

RadicalResult radical(const Curve& c, SpeedKind kind, const Options& opt) {
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  if (const auto bal = detail::balanced_for(c, s)) {
    const Speed sq(bal->q, kind);
    const RadicalResult rq = radical_on(sq, opt);
    return compose_balanced(s, bal, rq, uniformity_balanced(s, *bal, sq, opt).u, opt.digits);
  }
  return radical_on(s, opt);
}

namespace {

// The local Moebius map of a piece (moebius_map.hpp) with parameter alpha
// on complex balls: x, 1 - x (xm) and dx/dzt (if non-null) at zt, with
// ztm = 1 - zt. one_minus_alpha is the piece's own enclosure of 1 - alpha
// (PieceIntegrals::one_minus_alpha, made once by the caller, not per
// point): next to a narrow feature alpha is
// within 10^-100 of 1, and 1 - alpha from alpha's ball would hold 0 until
// the map's data had more digits than that. 1 - x = alpha ztm / den keeps
// its relative accuracy where x is next to 1 (a point 10^-300 from the
// piece's end), which 1 - x by subtraction would lose.
void moebius(acb_t x, acb_t xm, acb_t dx, const acb_t zt, const acb_t ztm, const Ball& alpha,
             const Ball& one_minus_alpha, long prec) {
  AcbBox a, q, den;
  acb_set_arb(a, alpha.get());
  acb_set_arb(q, one_minus_alpha.get());
  detail::moebius_map(detail::AcbMapArith{prec}, x, dx, den, zt, q, a);
  // the exact ends stay exact: x = zt there (moebius_map), and 1 - x with it
  if (acb_is_zero(zt) || acb_is_one(zt)) {
    acb_sub_ui(xm, x, 1, prec);
    acb_neg(xm, xm);
  } else {
    acb_mul(xm, a, ztm, prec);
    acb_div(xm, xm, den, prec);
  }
}

// y -> k y / (k y + 1 - y), the balancing map m on a piece
// (RadicalResult::outer_k; moebius_map.hpp with p = k, q = 1), with den =
// k y + 1 - y where asked; ym = 1 - y becomes (1 - y) / den.
void outer_moebius(acb_t y, acb_t ym, acb_t den, const arb_t k, long prec) {
  AcbBox kc, w, d;
  acb_set_arb(kc, k);
  detail::moebius_map(detail::AcbMapArith{prec}, w, nullptr, d, y, kc, nullptr);
  acb_swap(y, w);
  if (acb_is_zero(y) || acb_is_one(y)) {
    acb_sub_ui(ym, y, 1, prec);
    acb_neg(ym, ym);
  } else {
    acb_div(ym, ym, d, prec);
  }
  if (den) acb_set(den, d);
}

// Principal k-th root; for a ball containing 0 (where Arb's root is
// indeterminate) the disk |w| <= sup|x|^(1/k), which contains every k-th root.
void root_enclosure(acb_t out, const acb_t x, int k, long prec) {
  if (k == 1) { acb_set(out, x); return; }
  if (!acb_contains_zero(x)) { acb_root_ui(out, x, static_cast<ulong>(k), prec); return; }
  arb_t m;
  arb_init(m);
  acb_abs(m, x, prec);
  arb_get_ubound_arf(arb_midref(m), m, prec);
  mag_zero(arb_radref(m));
  if (arb_is_zero(m)) {  // x == 0 exactly (Arb's root of 0 is not finite)
    acb_zero(out);
    arb_clear(m);
    return;
  }
  arb_root_ui(m, m, static_cast<ulong>(k), prec);
  mag_t r;
  mag_init(r);
  arb_get_mag(r, m);
  acb_zero(out);
  mag_set(arb_radref(acb_realref(out)), r);
  mag_set(arb_radref(acb_imagref(out)), r);
  mag_clear(r);
  arb_clear(m);
}

// sum_{j<k} w^j (k >= 1).
void geometric_sum(acb_t out, const acb_t w, int k, long prec) {
  acb_t p;
  acb_init(p);
  acb_one(out);
  acb_one(p);
  for (int j = 1; j < k; ++j) {
    acb_mul(p, p, w, prec);
    acb_add(out, out, p, prec);
  }
  acb_clear(p);
}

// psi(x) of the elementary radical piece (out) and 1 - psi(x) (out_m), from
// x and xm = 1 - x; returns false when analytic is requested and the root's
// branch cut cannot be excluded. Each complement comes without a
// subtraction next to its end: for y = x^(1/k), 1 - y = (1 - x) /
// sum_{j<k} y^j, and for 1 - y = (1 - x)^(1/k), y = x / sum_{j<k} (1 - y)^j.
bool psi(acb_t out, acb_t out_m, const acb_t x, const acb_t xm, ZeroSide side, int k, bool analytic, long prec) {
  if (side == ZeroSide::None) {
    acb_set(out, x);
    acb_set(out_m, xm);
    return true;
  }
  const acb_srcptr base = side == ZeroSide::Left ? x : xm;
  const bool ok = !analytic || arb_is_positive(acb_realref(base));
  acb_ptr root = side == ZeroSide::Left ? out : out_m;
  acb_ptr other = side == ZeroSide::Left ? out_m : out;
  root_enclosure(root, base, k, prec);
  acb_t g;
  acb_init(g);
  geometric_sum(g, root, k, prec);
  if (acb_contains_zero(g)) {  // (a disk from root_enclosure)
    acb_sub_ui(other, root, 1, prec);
    acb_neg(other, other);
  } else {
    acb_div(other, side == ZeroSide::Left ? xm : x, g, prec);
  }
  acb_clear(g);
  return ok;
}

// The local coordinate zt = (z - lo) / (hi - lo) of z on the piece [lo,
// hi] = [Z_i, Z_{i+1}], clamped to [0, 1], and ztm = (hi - z) / (hi - lo) =
// 1 - zt without a subtraction next to 1. An exact end keeps an exact local
// coordinate: the radius of the other breakpoint, which a radical at a zero
// of the speed at t = 1 blows up to its square root whatever the precision,
// stays out.
void local_coordinate(acb_t zt, acb_t ztm, const Ball& z, const Ball& lo, const Ball& hi, long prec) {
  Ball dz, u, um;
  arb_sub(dz.get(), hi.get(), lo.get(), prec);
  arb_sub(u.get(), z.get(), lo.get(), prec);
  arb_div(u.get(), u.get(), dz.get(), prec);
  clamp_unit(u.get(), prec);
  detail::pin_exact_end(u.get(), z, lo, hi);
  if (arb_is_zero(u.get()) || arb_is_one(u.get())) {
    arb_sub_ui(um.get(), u.get(), 1, prec);
    arb_neg(um.get(), um.get());
  } else {
    arb_sub(um.get(), hi.get(), z.get(), prec);
    arb_div(um.get(), um.get(), dz.get(), prec);
    clamp_unit(um.get(), prec);
  }
  acb_set_arb(zt, u.get());
  acb_set_arb(ztm, um.get());
}

// t = phi_i(y) on piece i from y and ym = 1 - y (the outer balancing map
// applied where the map has one), taken from the nearer end: t_i + Delta t
// y, or t_{i+1} - Delta t (1 - y) where y > 1/2, so that t keeps the
// accuracy of its distance to that end (a point 10^-300 from a peak at
// t_{i+1}, where the speed varies on that scale). The enclosures ta, tb, dt
// of t_i, t_{i+1}, t_{i+1} - t_i.
void piece_t(acb_t t, const acb_t y, const acb_t ym, const arb_t ta, const arb_t tb, const arb_t dt, long prec) {
  const bool far = arf_cmp_2exp_si(arb_midref(acb_realref(y)), -1) > 0;
  if (far) {
    acb_mul_arb(t, ym, dt, prec);
    acb_neg(t, t);
    acb_add_arb(t, t, tb, prec);
  } else {
    acb_mul_arb(t, y, dt, prec);
    acb_add_arb(t, t, ta, prec);
  }
}

}  // namespace

Ball eval_r(const RadicalResult& r, const Ball& z, long prec) {
  Ball result;
  bool any = false;
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    // pieces whose [Z_i, Z_{i+1}] may meet z
    Ball lo = r.Z[i], hi = r.Z[i + 1];
    if (arb_lt(z.get(), lo.get()) || arb_gt(z.get(), hi.get())) continue;
    Ball dt, ta = r.T[i].t.to_ball(prec), tb = r.T[i + 1].t.to_ball(prec);
    acb_t x, xm, y, ym, zc, zcm;
    for (acb_ptr q : {x, xm, y, ym, zc, zcm}) acb_init(q);
    local_coordinate(zc, zcm, z, lo, hi, prec);
    arb_sub(dt.get(), tb.get(), ta.get(), prec);
    moebius(x, xm, nullptr, zc, zcm, r.integrals[i].alpha, r.integrals[i].one_minus_alpha(prec), prec);
    psi(y, ym, x, xm, r.side(i), r.root_index(i), false, prec);
    if (!r.outer_k.empty()) outer_moebius(y, ym, nullptr, r.outer_k[i].get(), prec);
    Ball v;
    // an exact end maps to its breakpoint exactly (psi and the Moebius map fix
    // 0 and 1); t_i + 1 * (t_{i+1} - t_i) would add t_i's radius twice
    if (acb_is_zero(zc)) v = ta;
    else if (acb_is_one(zc)) v = tb;
    else {
      acb_t t;
      acb_init(t);
      piece_t(t, y, ym, ta.get(), tb.get(), dt.get(), prec);
      arb_set(v.get(), acb_realref(t));
      acb_clear(t);
    }
    if (!any) result = v;
    else arb_union(result.get(), result.get(), v.get(), prec);
    any = true;
    for (acb_ptr q : {x, xm, y, ym, zc, zcm}) acb_clear(q);
  }
  if (!any) throw InvalidArgument("eval_r: z must lie in [0, 1]");
  return result;
}

namespace {

// [sigma_p(t) * Delta t * psi'(x)]^2 at t = t_i + Delta t psi(x), piece i, from
// the local Moebius coordinate x and xm = 1 - x (t from the nearer end,
// piece_t). With a zero at an end the singular factors
// cancel exactly (Hong, Wang, Yang 2023, Theorem 7): the value is
// Shat(t) (Delta t^(mu+1) / (mu+1))^2 with Shat = sigma^2 / (t - gamma)^(2 mu).
bool radical_speed_sq_local(acb_t out, const RadicalResult& r, const Speed& s, std::size_t i, const acb_t x,
                            const acb_t xm, bool analytic, long prec) {
  Ball ta = r.T[i].t.to_ball(prec + 16), tb = r.T[i + 1].t.to_ball(prec + 16);
  acb_t y, ym, t, dt;
  acb_init(y);
  acb_init(ym);
  acb_init(t);
  acb_init(dt);
  const ZeroSide side = r.side(i);
  const int k = r.root_index(i);
  bool ok = psi(y, ym, x, xm, side, k, analytic, prec);
  // With the balancing map on the piece, w = ko y / D (D = ko y + 1 - y):
  // dw/dy = ko / D^2, w = (ko / D) y and 1 - w = (1 - y) / D, so the
  // factor below multiplies the value without it by (ko^e / D^(k + 1))^2,
  // e = k for a zero at the left end, 1 otherwise (k = 1 without a zero).
  acb_t den;
  acb_init(den);
  const bool outer = !r.outer_k.empty();
  if (outer) outer_moebius(y, ym, den, r.outer_k[i].get(), prec);
  arb_sub(acb_realref(dt), tb.get(), ta.get(), prec);
  piece_t(t, y, ym, ta.get(), tb.get(), acb_realref(dt), prec);
  if (side == ZeroSide::None) {
    s.eval_squared(out, t, prec);
    acb_mul(out, out, dt, prec);
    acb_mul(out, out, dt, prec);
  } else {
    const Breakpoint& zb = side == ZeroSide::Left ? r.T[i] : r.T[i + 1];
    s.eval_squared_over_zero(out, t, zb.zero(), side == ZeroSide::Left ? 1 : -1, 2 * zb.multiplicity, prec);
    acb_pow_ui(y, dt, static_cast<ulong>(k), prec);
    acb_div_ui(y, y, static_cast<ulong>(k), prec);
    acb_mul(out, out, y, prec);
    acb_mul(out, out, y, prec);
  }
  if (outer) {
    acb_t f;
    acb_init(f);
    acb_set_arb(f, r.outer_k[i].get());
    acb_pow_ui(f, f, static_cast<ulong>(side == ZeroSide::Left ? k : 1), prec);
    acb_pow_ui(den, den, static_cast<ulong>(k + 1), prec);
    acb_div(f, f, den, prec);
    acb_mul(out, out, f, prec);
    acb_mul(out, out, f, prec);
    acb_clear(f);
  }
  acb_clear(den);
  acb_clear(y);
  acb_clear(ym);
  acb_clear(t);
  acb_clear(dt);
  return ok;
}

}  // namespace

Ball eval_speed(const RadicalResult& r, const Speed& s, const Ball& z, long prec) {
  Ball result;
  bool any = false;
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    Ball lo = r.Z[i], hi = r.Z[i + 1];
    if (arb_lt(z.get(), lo.get()) || arb_gt(z.get(), hi.get())) continue;
    Ball dz;
    arb_sub(dz.get(), hi.get(), lo.get(), prec);
    acb_t x, xm, dx, zc, zcm, v;
    for (acb_ptr q : {x, xm, dx, zc, zcm, v}) acb_init(q);
    local_coordinate(zc, zcm, z, lo, hi, prec);
    moebius(x, xm, dx, zc, zcm, r.integrals[i].alpha, r.integrals[i].one_minus_alpha(prec), prec);
    radical_speed_sq_local(v, r, s, i, x, xm, false, prec);
    Ball w;
    arb_sqrt(w.get(), acb_realref(v), prec);
    arb_mul(w.get(), w.get(), acb_realref(dx), prec);
    arb_div(w.get(), w.get(), dz.get(), prec);
    if (!any) result = w;
    else arb_union(result.get(), result.get(), w.get(), prec);
    any = true;
    for (acb_ptr q : {x, xm, dx, zc, zcm, v}) acb_clear(q);
  }
  if (!any) throw InvalidArgument("eval_speed: z must lie in [0, 1]");
  return result;
}

std::vector<Ball> eval_point(const Curve& c, const RadicalResult& r, const Ball& z, long prec) {
  // p(r(z)) = q(r_q(z)) for a balanced map, without m's extreme parameters
  if (r.balanced) return eval_point(r.balanced->curve->q, *r.balanced->on, z, prec);
  const Ball t = eval_r(r, z, prec);
  return c.eval(t, prec);
}

Ball radical_direct_uniformity(const RadicalResult& r, const Speed& s, long digits, long max_prec) {
  if (r.identically_zero) return Ball(1);
  const long bits = digits_to_bits(digits);
  const long prec = 2 * bits + 64;
  Ball total(0);
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    // int_{Z_i}^{Z_{i+1}} sigma_{p o r}^2 dz = (1 / Delta z) int_0^1 F(x(zt)) x'(zt)^2 dzt
    // 1 - alpha per working precision, not per node
    Ball oma;
    long oma_prec = -1;
    Integrand f = [&r, &s, i, &oma, &oma_prec](acb_t out, const acb_t zt, bool analytic, long p) {
      if (p != oma_prec) {
        oma = r.integrals[i].one_minus_alpha(p);
        oma_prec = p;
      }
      acb_t x, xm, dx, ztm;
      for (acb_ptr q : {x, xm, dx, ztm}) acb_init(q);
      acb_sub_ui(ztm, zt, 1, p);
      acb_neg(ztm, ztm);
      moebius(x, xm, dx, zt, ztm, r.integrals[i].alpha, oma, p);
      if (!radical_speed_sq_local(out, r, s, i, x, xm, analytic, p)) acb_indeterminate(out);
      else {
        acb_mul(out, out, dx, p);
        acb_mul(out, out, dx, p);
      }
      for (acb_ptr q : {x, xm, dx, ztm}) acb_clear(q);
    };
    QuadratureOptions qo;
    qo.rel_goal_bits = bits;
    qo.max_prec = max_prec;
    qo.what = "the direct integral of the reparameterized speed";
    Ball piece = integrate(f, RealAlgebraic(0), RealAlgebraic(1), qo), dz;
    arb_sub(dz.get(), r.Z[i + 1].get(), r.Z[i].get(), prec);
    arb_div(piece.get(), piece.get(), dz.get(), prec);
    arb_add(total.get(), total.get(), piece.get(), prec);
  }
  Ball u;
  arb_mul(u.get(), r.mu.get(), r.mu.get(), prec);
  arb_div(u.get(), u.get(), total.get(), prec);
  return u;
}

RadicalResult refine_radical_data(const Speed& sp, const RadicalResult& in, long digits, long max_prec) {
  if (digits < 1) throw InvalidArgument("refine_radical_data: digits must be at least 1");
  if (in.balanced) {
    const Speed sq(in.balanced->curve->q, sp.kind());
    const RadicalResult rq = refine_radical_data(sq, *in.balanced->on, digits, max_prec);
    return compose_balanced(sp, in.balanced->curve, rq, in.u_before, digits);
  }
  RadicalResult x = in;
  if (x.identically_zero) return x;
  const std::size_t N = x.pieces();
  for (long bits = digits_to_bits(digits) + 8;; bits += 32) {
    check_time_budget();
    const long prec = 2 * bits + 64;
    std::vector<PieceIntegrals> I = all_piece_integrals(sp, x.T, bits, max_prec);
    std::vector<Ball> sqrtL(N), sqrtM(N), alpha(N);
    Ball sumL(0), sumM(0);
    for (std::size_t i = 0; i < N; ++i) {
      arb_sqrt(sqrtL[i].get(), I[i].L.get(), prec);
      arb_sqrt(sqrtM[i].get(), I[i].M.get(), prec);
      arb_add(sumL.get(), sumL.get(), sqrtL[i].get(), prec);
      arb_add(sumM.get(), sumM.get(), sqrtM[i].get(), prec);
      alpha[i] = I[i].alpha;
    }
    std::vector<Ball> S = cumulative_normalised(sqrtL, sumL, prec), Z = cumulative_normalised(sqrtM, sumM, prec);
    if (all_meet_digits(S, digits) && all_meet_digits(Z, digits) && all_meet_digits(alpha, digits)) {
      x.A.clear();
      x.B.clear();
      x.C.clear();
      for (std::size_t i = 0; i < N; ++i) {
        Ball ds, q;
        arb_sub(ds.get(), S[i + 1].get(), S[i].get(), prec);
        arb_div(q.get(), I[i].A.get(), ds.get(), prec);
        x.A.push_back(q);
        arb_div(q.get(), I[i].B.get(), ds.get(), prec);
        x.B.push_back(q);
        arb_div(q.get(), I[i].C.get(), ds.get(), prec);
        x.C.push_back(q);
      }
      x.integrals = std::move(I);
      x.S = std::move(S);
      x.Z = std::move(Z);
      return x;
    }
    if (bits > max_prec)
      throw BudgetExceeded("could not refine the radical map's data to " + std::to_string(digits) +
                           " digits within " + std::to_string(max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

}  // namespace uniparam
