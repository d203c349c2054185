#include "uniparam/reparam/moebius.hpp"

#include <memory>
#include <optional>
#include <string>

#include "uniparam/core/ball_poly.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "moebius_detail.hpp"
#include "moebius_map.hpp"

namespace uniparam {

const char* to_string(Continuity c) { return c == Continuity::C0 ? "C0" : "C1"; }

namespace {

// Piece i of r at the real ball s: t (and dt/ds) from (2.1) in local
// coordinates, s~ clamped to [0, 1] (s is known to meet the piece).
void piece_eval(Ball* t, Ball* dt, const MoebiusResult& r, std::size_t i, const Ball& s, long prec) {
  Ball ds, st, ta = r.T[i].t.to_ball(prec), tb = r.T[i + 1].t.to_ball(prec), h;
  arb_sub(ds.get(), r.S[i + 1].get(), r.S[i].get(), prec);
  arb_sub(st.get(), s.get(), r.S[i].get(), prec);
  arb_div(st.get(), st.get(), ds.get(), prec);
  clamp_unit(st.get(), prec);  // only the part of s inside the piece maps through it
  // an exact end (s = 0, s = 1) has the local coordinate exactly 0 or 1,
  // and maps to t_i or t_{i+1} exactly
  detail::pin_exact_end(st.get(), s, r.S[i], r.S[i + 1]);
  arb_sub(h.get(), tb.get(), ta.get(), prec);
  Ball x;
  detail::moebius_alpha_map(detail::BallMapArith{prec}, t ? x.get() : nullptr, dt ? dt->get() : nullptr, st.get(),
                            r.alpha[i].get());
  if (t) {
    if (arb_is_zero(st.get())) *t = ta;
    else if (arb_is_one(st.get())) *t = tb;
    else {
      arb_mul(x.get(), x.get(), h.get(), prec);
      arb_add(t->get(), ta.get(), x.get(), prec);
    }
  }
  if (dt) {
    // dt/ds = (h / ds) dx/ds~
    arb_mul(dt->get(), dt->get(), h.get(), prec);
    arb_div(dt->get(), dt->get(), ds.get(), prec);
  }
}

// Calls f(i) for every piece whose [s_i, s_{i+1}] meets s; InvalidArgument if none.
template <class F>
void for_pieces_at(const MoebiusResult& r, const Ball& s, const char* who, F f) {
  Ball zero(0), one(1);
  if (arb_lt(s.get(), zero.get()) || arb_gt(s.get(), one.get()) || !arb_is_finite(s.get()))
    throw InvalidArgument(std::string(who) + ": s must lie in [0, 1]");
  bool any = false;
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    if (arb_lt(s.get(), r.S[i].get()) || arb_gt(s.get(), r.S[i + 1].get())) continue;
    f(i);
    any = true;
  }
  if (!any) throw InvalidArgument(std::string(who) + ": s must lie in [0, 1]");
}

void unite(Ball& acc, bool& any, const Ball& v, long prec) {
  if (!any) acc = v;
  else arb_union(acc.get(), acc.get(), v.get(), prec);
  any = true;
}

}  // namespace

Ball eval_r(const MoebiusResult& r, const Ball& s, long prec) {
  Ball out;
  bool any = false;
  for_pieces_at(r, s, "eval_r", [&](std::size_t i) {
    Ball t;
    piece_eval(&t, nullptr, r, i, s, prec);
    unite(out, any, t, prec);
  });
  return out;
}

Ball eval_dr(const MoebiusResult& r, const Ball& s, long prec) {
  Ball out;
  bool any = false;
  for_pieces_at(r, s, "eval_dr", [&](std::size_t i) {
    Ball d;
    piece_eval(nullptr, &d, r, i, s, prec);
    unite(out, any, d, prec);
  });
  return out;
}

Ball eval_speed(const MoebiusResult& r, const Speed& sp, const Ball& s, long prec) {
  Ball out;
  bool any = false;
  for_pieces_at(r, s, "eval_speed", [&](std::size_t i) {
    Ball t, d, v;
    piece_eval(&t, &d, r, i, s, prec);
    acb_t z, w;
    acb_init(z);
    acb_init(w);
    acb_set_arb(z, t.get());
    sp.eval_squared(w, z, prec);
    arb_sqrtpos(v.get(), acb_realref(w), prec);
    arb_mul(v.get(), v.get(), d.get(), prec);
    acb_clear(z);
    acb_clear(w);
    unite(out, any, v, prec);
  });
  return out;
}

std::vector<Ball> eval_point(const Curve& c, const MoebiusResult& r, const Ball& s, long prec) {
  // p(r(s)) = q(r_q(s)) for a balanced map, without m's extreme parameters
  if (r.balanced) return eval_point(r.balanced->curve->q, *r.balanced->on, s, prec);
  const Ball t = eval_r(r, s, prec);
  return c.eval(t, prec);
}

MoebiusResult moebius_c0(const Curve& c, SpeedKind kind, const std::vector<RealAlgebraic>& T,
                         const Options& opt) {
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  if (const auto bal = detail::balanced_for(c, s)) {
    // The breakpoints in q's parameter, s = m^-1(t) (exact), once T is valid.
    detail::moebius_breakpoints(s, T);
    std::vector<RealAlgebraic> Tq;
    for (const RealAlgebraic& t : T) Tq.push_back(balance_unmap(*bal, t));
    const Speed sq(bal->q, kind);
    const MoebiusResult rq = detail::moebius_c0(sq, detail::mu_only(sq, opt), Tq, opt);
    return detail::compose_balanced(bal, rq, uniformity_balanced(s, *bal, sq, opt).u, opt.digits);
  }
  return detail::moebius_c0(s, detail::mu_only(s, opt), T, opt);
}

namespace detail {

std::shared_ptr<const BalancedCurve> balanced_for(const Curve& c, const Speed& s) {
  if (s.identically_zero()) return nullptr;
  std::optional<BalancedCurve> b = balance(c, s);
  if (!b) return nullptr;
  return std::make_shared<const BalancedCurve>(std::move(*b));
}

long balanced_prec(const BalancedCurve& bal, long digits) {
  return 2 * digits_to_bits(digits) + 64 + 2 * balance_bits(bal);
}

Ball compose_alpha(const Ball& alpha, const Ball& k, long prec) {
  Ball K, x;
  arb_sub_si(K.get(), alpha.get(), 1, prec);
  arb_neg(K.get(), K.get());
  arb_div(K.get(), K.get(), alpha.get(), prec);
  arb_mul(x.get(), K.get(), k.get(), prec);
  arb_add_si(x.get(), x.get(), 1, prec);
  arb_inv(x.get(), x.get(), prec);
  return x;
}

MoebiusResult compose_balanced(const std::shared_ptr<const BalancedCurve>& bal, const MoebiusResult& rq,
                               const Ball& u_before, long digits) {
  MoebiusResult r = rq;
  const long prec = balanced_prec(*bal, digits);
  const std::size_t N = rq.pieces();
  r.T.clear();
  for (const Breakpoint& b : rq.T) r.T.push_back(Breakpoint{balance_map(*bal, b.t), 0, 0, 0});
  for (std::size_t i = 0; i < N; ++i) {
    // A, B, C of the piece on p: sigma_p^2 dt = sigma_q^2 / (dt/ds) ds and
    // (1 - t~)^2, 2 t~ (1 - t~), t~^2 over dt~/ds~ are (1 - s~)^2 / k,
    // 2 s~ (1 - s~), k s~^2; M = B + 2 sqrt(A C) is unchanged.
    const Ball k = balance_local_k(*bal, rq.T[i].t, rq.T[i + 1].t, prec);
    PieceIntegrals& I = r.integrals[i];
    arb_div(I.A.get(), I.A.get(), k.get(), prec);
    arb_mul(I.C.get(), I.C.get(), k.get(), prec);
    arb_add(I.L.get(), I.A.get(), I.B.get(), prec);
    arb_add(I.L.get(), I.L.get(), I.C.get(), prec);
    I.alpha = compose_alpha(rq.integrals[i].alpha, k, prec);
    I.square = Ball();
    I.square_bits = 0;
    if (rq.exact.has_value()) {
      const Rational kq = balance_local_k(*bal, rq.exact->T[i], rq.exact->T[i + 1]);
      const Rational& a = rq.exact->alpha[i];
      r.exact->alpha[i] = Rational(1) / (Rational(1) + kq * (Rational(1) - a) / a);
      r.alpha[i] = Ball(r.exact->alpha[i], prec);
    } else {
      r.alpha[i] = compose_alpha(rq.alpha[i], k, prec);
    }
  }
  if (rq.exact.has_value())
    for (std::size_t i = 0; i <= N; ++i) r.exact->T[i] = r.T[i].t.rational();
  r.u_before = u_before;
  r.balanced = MoebiusResult::Balanced{bal, std::make_shared<const MoebiusResult>(rq)};
  return r;
}

std::vector<Breakpoint> moebius_breakpoints(const Speed& s, const std::vector<RealAlgebraic>& T) {
  // mark_zeros validates T (0 = t_0 < ... < t_N = 1); the rational method then
  // integrates every piece with ZeroSide::None, so the multiplicities are reset.
  std::vector<Breakpoint> bp = mark_zeros(s, T);
  for (auto& b : bp) b = Breakpoint{b.t, 0, 0, 0};
  return bp;
}

long moebius_first_bits(const Options& opt) { return digits_to_bits(opt.digits) + 8; }

UniformityResult mu_only(const Speed& s, const Options& opt) {
  UniformityResult r;
  r.kind = s.kind();
  r.zeros = s.zeros();
  r.identically_zero = s.identically_zero();
  r.mu = mean_speed(s, digits_to_bits(opt.digits), opt);
  arb_indeterminate(r.mean_square.get());
  arb_indeterminate(r.u.get());
  return r;
}

MoebiusResult moebius_c0(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T,
                         const Options& opt, const std::vector<PieceIntegrals>* first) {
  MoebiusResult r;
  r.kind = s.kind();
  r.T = moebius_breakpoints(s, T);
  r.mu = base.mu;
  r.identically_zero = base.identically_zero;
  r.speed_vanishes = !s.zeros().empty();
  const std::size_t N = r.T.size() - 1;

  if (r.identically_zero) {
    const long prec = digits_to_bits(opt.digits) + 64;
    r.S.clear();
    for (std::size_t i = 0; i <= N; ++i)
      r.S.push_back(i == 0 ? Ball(0) : i == N ? Ball(1) : r.T[i].t.to_ball(prec));
    for (std::size_t i = 0; i < N; ++i) r.integrals.push_back(piece_integrals(s, r.T[i], r.T[i + 1], 64, opt.max_prec));
    r.u_before = r.u_after = Ball(1);
    for (const auto& p : r.integrals) r.alpha.push_back(p.alpha);
    return r;
  }

  long mu_bits = 0;  // 0: base.mu as given
  bool raise_mu = false;
  for (long bits = moebius_first_bits(opt);; bits += 32) {
    check_time_budget();
    const long prec = 2 * bits + 64;
    if (raise_mu && bits > mu_bits) {
      mu_bits = bits;
      r.mu = mean_speed(s, mu_bits, opt);
    }
    if (first && bits == moebius_first_bits(opt)) {
      if (first->size() != N) throw InvalidArgument("moebius_c0: precomputed integrals for another T");
      r.integrals = *first;
    } else {
      r.integrals = all_piece_integrals(s, r.T, bits, opt.max_prec);
    }
    std::vector<Ball> sqrtM(N);
    Ball sum(0), mean_square(0);
    for (std::size_t i = 0; i < N; ++i) {
      arb_sqrt(sqrtM[i].get(), r.integrals[i].M.get(), prec);
      arb_add(sum.get(), sum.get(), sqrtM[i].get(), prec);
      // int sigma^2 over piece i: L_i / Delta t_i (no zeros: multiplicities reset)
      const Ball part = piece_square_integral(s, r.T[i], r.T[i + 1], r.integrals[i], bits, opt.max_prec);
      arb_add(mean_square.get(), mean_square.get(), part.get(), prec);
    }
    // S_i = cumulative sqrt M / sum, with the ends exact.
    r.S.assign(1, Ball(0));
    Ball acc(0);
    for (std::size_t k = 0; k + 1 < N; ++k) {
      arb_add(acc.get(), acc.get(), sqrtM[k].get(), prec);
      Ball q;
      arb_div(q.get(), acc.get(), sum.get(), prec);
      r.S.push_back(q);
    }
    r.S.push_back(Ball(1));
    Ball mu2, sum2;
    arb_mul(mu2.get(), r.mu.get(), r.mu.get(), prec);
    arb_mul(sum2.get(), sum.get(), sum.get(), prec);
    arb_div(r.u_after.get(), mu2.get(), sum2.get(), prec);
    arb_div(r.u_before.get(), mu2.get(), mean_square.get(), prec);

    const long d = opt.digits + 1;
    const bool mu_ok = r.mu.meets_digits(d) && r.u_before.meets_digits(d) && r.u_after.meets_digits(d);
    bool ok = mu_ok;
    for (const auto& b : r.S) ok = ok && b.meets_digits(d);
    for (const auto& pi : r.integrals)
      ok = ok && pi.A.meets_digits(d) && pi.B.meets_digits(d) && pi.C.meets_digits(d) && pi.L.meets_digits(d) &&
           pi.M.meets_digits(d) && pi.alpha.meets_digits(d);
    if (ok) {
      r.alpha.clear();
      for (const auto& p : r.integrals) r.alpha.push_back(p.alpha);
      return r;
    }
    raise_mu = !mu_ok;  // mu may be the one short of accuracy
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the piecewise Moebius reparameterization to " +
                           std::to_string(opt.digits) + " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

Ball phi_of(const MoebiusResult& r, long prec) {
  Ball phi(0);
  for (const auto& p : r.integrals) {
    Ball q;
    arb_sqrtpos(q.get(), p.M.get(), prec);
    arb_add(phi.get(), phi.get(), q.get(), prec);
  }
  return phi;
}

Ball certified_phi(const Speed& s, const std::vector<RealAlgebraic>& T, long bits, long max_prec) {
  return certified_phi(all_piece_integrals(s, moebius_breakpoints(s, T), bits, max_prec), bits);
}

Ball certified_phi(const std::vector<PieceIntegrals>& integrals, long bits) {
  Ball phi(0);
  for (const PieceIntegrals& p : integrals) {
    Ball q;
    arb_sqrtpos(q.get(), p.M.get(), 2 * bits + 64);
    arb_add(phi.get(), phi.get(), q.get(), 2 * bits + 64);
  }
  return phi;
}

}  // namespace detail

MoebiusResult moebius_optimal(const Curve& c, SpeedKind kind, const Options& opt) {
  return moebius_c0(c, kind, {RealAlgebraic(0), RealAlgebraic(1)}, opt);
}

}  // namespace uniparam
