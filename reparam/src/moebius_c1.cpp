// reparam/src/moebius_c1.cpp -- ImUp's ReparameterizationU: a C1 piecewise
// Moebius map refined until a target uniformity (MATH.md section 3).
#include <algorithm>
#include <string>
#include <vector>

#include "moebius_detail.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/moebius.hpp"

namespace uniparam {

namespace detail {

Poly log_derivative_numerator(const Speed& s) {
  // sigma^2 = g^2 S / D^2 with S = sum K^2, so (sigma^2)' / sigma^2 =
  // 2 g'/g + S'/S - 2 D'/D = N1 / (g S D).
  Poly S(0);
  for (const auto& k : s.cofactors()) S = S + k * k;
  const Poly& g = s.g();
  const Poly& D = s.denominator();
  return Poly(2) * g.derivative() * S * D + g * S.derivative() * D - Poly(2) * g * S * D.derivative();
}

C1Data c1_from_pieces(const std::vector<RealAlgebraic>& T, const std::vector<Ball>& S,
                      const std::vector<PieceIntegrals>& I, const Ball& mu, long prec) {
  const std::size_t N = I.size();
  C1Data d;
  d.rho.resize(N);
  // PieceIntegrals hold dt_i times the integrals over dt (pieces.hpp), so a
  // piece's int sigma_{p o m}^2 ds is (k A + B + C / k) / ds_i: weight w_i.
  std::vector<Ball> w(N);
  for (std::size_t i = 0; i < N; ++i) {
    Ball dt, ds;
    arb_sub(dt.get(), T[i + 1].to_ball(prec).get(), T[i].to_ball(prec).get(), prec);
    arb_sub(ds.get(), S[i + 1].get(), S[i].get(), prec);
    arb_div(d.rho[i].get(), dt.get(), ds.get(), prec);
    arb_inv(w[i].get(), ds.get(), prec);
  }
  // k_i = c_i x for even i, c_i / x for odd i, with c_0 = 1 and
  // c_{i+1} = rho_i / (rho_{i+1} c_i) (the C1 condition rho_i / k_i = rho_{i+1} k_{i+1}).
  std::vector<Ball> cc(N);
  cc[0] = Ball(1);
  for (std::size_t i = 0; i + 1 < N; ++i) {
    arb_mul(cc[i + 1].get(), d.rho[i + 1].get(), cc[i].get(), prec);
    arb_div(cc[i + 1].get(), d.rho[i].get(), cc[i + 1].get(), prec);
  }
  // sum w_i (k_i A_i + B_i + C_i / k_i) = x P + Q / x + sum w_i B_i
  Ball P(0), Q(0), t;
  for (std::size_t i = 0; i < N; ++i) {
    Ball ca, cq;  // coefficient of x and of 1/x
    if (i % 2 == 0) {
      arb_mul(ca.get(), cc[i].get(), I[i].A.get(), prec);
      arb_div(cq.get(), I[i].C.get(), cc[i].get(), prec);
    } else {
      arb_div(ca.get(), I[i].C.get(), cc[i].get(), prec);
      arb_mul(cq.get(), cc[i].get(), I[i].A.get(), prec);
    }
    arb_addmul(P.get(), w[i].get(), ca.get(), prec);
    arb_addmul(Q.get(), w[i].get(), cq.get(), prec);
  }
  Ball x;
  arb_div(x.get(), Q.get(), P.get(), prec);
  arb_sqrtpos(x.get(), x.get(), prec);
  d.k.resize(N);
  d.alpha.resize(N);
  d.F.resize(N);
  for (std::size_t i = 0; i < N; ++i) {
    if (i % 2 == 0) arb_mul(d.k[i].get(), cc[i].get(), x.get(), prec);
    else arb_div(d.k[i].get(), cc[i].get(), x.get(), prec);
    arb_add_ui(t.get(), d.k[i].get(), 1, prec);
    arb_inv(d.alpha[i].get(), t.get(), prec);
    Ball f;
    arb_mul(f.get(), d.k[i].get(), I[i].A.get(), prec);
    arb_add(f.get(), f.get(), I[i].B.get(), prec);
    arb_div(t.get(), I[i].C.get(), d.k[i].get(), prec);
    arb_add(f.get(), f.get(), t.get(), prec);
    arb_mul(d.F[i].get(), f.get(), w[i].get(), prec);
  }
  Ball total(0);
  for (const auto& f : d.F) arb_add(total.get(), total.get(), f.get(), prec);
  arb_mul(d.u.get(), mu.get(), mu.get(), prec);
  arb_div(d.u.get(), d.u.get(), total.get(), prec);
  return d;
}

}  // namespace detail

namespace {

struct Built {
  MoebiusResult r;
  detail::C1Data d;
};

// The C1 map for breakpoints T: S from int sigma / mu, alpha from the C1
// condition (optimal free parameter), certified to `digits` digits (checked
// on u, S and alpha) or, with digits == 0, to about 40 bits (a draft to steer
// the refinement).
Built build(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T, long digits,
            const Options& opt) {
  const std::size_t N = T.size() - 1;
  for (long bits = digits > 0 ? digits_to_bits(digits) + 8 : 40;; bits += 32) {
    const long prec = 2 * bits + 64;
    Built b;
    MoebiusResult& r = b.r;
    r.kind = s.kind();
    r.continuity = Continuity::C1;
    r.mu = base.mu;
    r.u_before = base.u;
    r.speed_vanishes = !s.zeros().empty();
    std::vector<Ball> len(N);
    Ball total(0);
    for (std::size_t i = 0; i < N; ++i) {
      r.T.push_back(Breakpoint{T[i], 0, 0, 0});
      r.integrals.push_back(piece_integrals(s, Breakpoint{T[i], 0, 0, 0}, Breakpoint{T[i + 1], 0, 0, 0}, bits,
                                            opt.max_prec));
      len[i] = integrate_speed(s, T[i], T[i + 1], bits, opt.max_prec);
      arb_add(total.get(), total.get(), len[i].get(), prec);
    }
    r.T.push_back(Breakpoint{T[N], 0, 0, 0});
    r.S.assign(1, Ball(0));
    Ball acc(0);
    for (std::size_t i = 0; i + 1 < N; ++i) {
      arb_add(acc.get(), acc.get(), len[i].get(), prec);
      Ball q;
      arb_div(q.get(), acc.get(), total.get(), prec);
      r.S.push_back(q);
    }
    r.S.push_back(Ball(1));
    b.d = detail::c1_from_pieces(T, r.S, r.integrals, base.mu, prec);
    r.alpha = b.d.alpha;
    r.u_after = b.d.u;
    if (digits == 0) return b;
    const long d = digits + 1;
    bool ok = r.u_after.meets_digits(d);
    for (const auto& x : r.S) ok = ok && x.meets_digits(d);
    for (const auto& x : r.alpha) ok = ok && x.meets_digits(d);
    if (ok) return b;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the C1 piecewise Moebius reparameterization to " +
                           std::to_string(digits) + " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

// A short rational in the ball x +- w (x a ball, w > 0 a rational width).
Rational short_rational(const Ball& x, const Rational& w) {
  const Rational m = mid_rational(x);
  return Rational::simplest_between(m - w, m + w);
}

// New breakpoints of the slides' refinement: on each piece, the roots of
//   sigma' dt [alpha t~ + (1 - alpha)(1 - t~)] - 2 sigma (1 - 2 alpha) = 0,
// i.e. with sigma'/sigma = N1 / (2 g S D) and l(t) = dt [alpha t~ + (1-alpha)(1-t~)]
// = (2 alpha - 1) t + (1 - alpha) b - alpha a:
//   N1 l - 4 (1 - 2 alpha) g S D = 0.
// The roots are choices (computed from rounded alpha and ends), not results.
std::vector<RealAlgebraic> refine(const Poly& N1, const Poly& gSD,
                                  const std::vector<RealAlgebraic>& T, const detail::C1Data& d) {
  std::vector<RealAlgebraic> out;
  const Rational tiny(1, 1000000000);
  for (std::size_t i = 0; i + 1 < T.size(); ++i) {
    out.push_back(T[i]);
    const Ball ab = T[i].to_ball(128), bb = T[i + 1].to_ball(128);
    const Rational a = short_rational(ab, tiny), b = short_rational(bb, tiny);
    const Rational al = short_rational(d.alpha[i], Rational(1, 1000000000000L));
    const Rational h = b - a;
    if (h.sign() <= 0) continue;
    // l(t) = c1 t + c0, and the equation N1 l - 4 (1 - 2 alpha) gSD, scaled to Z[t].
    const Rational c1 = Rational(2) * al - Rational(1);
    const Rational c0 = (Rational(1) - al) * b - al * a;
    const Rational c2 = Rational(4) * (Rational(1) - Rational(2) * al);
    const Integer den = Integer(c1.den()) * Integer(c0.den()) * Integer(c2.den());
    const Rational k1 = c1 * Rational(den), k0 = c0 * Rational(den), k2 = c2 * Rational(den);
    // den clears every denominator, so k0, k1, k2 are integers
    const Poly lin(std::vector<Integer>{k0.num(), k1.num()});
    const Poly eq = N1 * lin - Poly(std::vector<Integer>{k2.num()}) * gSD;
    if (eq.is_zero()) continue;
    const Rational margin = h * Rational(1, 1000);
    std::vector<IsolatedRoot> roots = isolate_real_roots(eq, a + margin, b - margin);
    for (const auto& rt : roots) {
      const RealAlgebraic x(rt);
      const Rational q = short_rational(x.to_ball(64), h * Rational(1, 1000000));
      if (q > a + margin && q < b - margin && (out.empty() || compare(out.back(), RealAlgebraic(q)) < 0))
        out.emplace_back(q);
    }
  }
  out.push_back(T.back());
  return out;
}

}  // namespace

MoebiusResult reparam_c1(const Curve& c, SpeedKind kind, const Rational& target, const Options& opt,
                         long max_pieces) {
  if (!(target.sign() > 0 && target < Rational(1)))
    throw InvalidArgument("the target uniformity must lie in (0, 1), got " + target.str());
  if (max_pieces < 1 || max_pieces > 1000)
    throw InvalidArgument("the piece budget must be in [1, 1000], got " + std::to_string(max_pieces));
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  const UniformityResult base = uniformity(s, opt);
  if (s.identically_zero()) {
    MoebiusResult r = detail::moebius_c0(s, base, {RealAlgebraic(0), RealAlgebraic(1)}, opt);
    r.continuity = Continuity::C1;
    r.target = MoebiusResult::Target{true, target, true, 0};
    return r;
  }
  // T: 0, the zeros of sigma' in (0, 1), 1.
  const Poly N1 = detail::log_derivative_numerator(s);
  std::vector<RealAlgebraic> T{RealAlgebraic(0)};
  if (!N1.is_zero())
    for (const auto& rt : isolate_real_roots(N1, Rational(0), Rational(1))) {
      if (rt.is_exact() && (rt.lo.is_zero() || rt.lo == Rational(1))) continue;
      T.emplace_back(rt);
    }
  T.emplace_back(RealAlgebraic(1));
  Poly S2(0);
  for (const auto& k : s.cofactors()) S2 = S2 + k * k;
  const Poly gSD = s.g() * S2 * s.denominator();

  std::vector<RealAlgebraic> best = T;
  double best_u = -1;
  long rounds = 0;
  for (;; ++rounds) {
    const Built draft = build(s, base, T, 0, opt);
    const double u = arf_get_d(arb_midref(draft.r.u_after.get()), ARF_RND_NEAR);
    if (u > best_u) {
      best_u = u;
      best = T;
    }
    Ball tq(target, 128);
    if (arb_ge(draft.r.u_after.get(), tq.get())) break;
    if (static_cast<long>(T.size()) - 1 >= max_pieces) break;
    std::vector<RealAlgebraic> next = refine(N1, gSD, T, draft.d);
    if (next.size() == T.size()) {
      // The slides' rule added nothing: split the piece with the largest
      // excess F_i - mu^2 Delta s_i (its share of int sigma_{p o m}^2 above the
      // ideal) at its midpoint.
      std::size_t worst = 0;
      double wv = -1;
      const double mu = arf_get_d(arb_midref(base.mu.get()), ARF_RND_NEAR);
      for (std::size_t i = 0; i + 1 < T.size(); ++i) {
        const double ds = arf_get_d(arb_midref(draft.r.S[i + 1].get()), ARF_RND_NEAR) -
                          arf_get_d(arb_midref(draft.r.S[i].get()), ARF_RND_NEAR);
        const double e = arf_get_d(arb_midref(draft.d.F[i].get()), ARF_RND_NEAR) - mu * mu * ds;
        if (e > wv) {
          wv = e;
          worst = i;
        }
      }
      const Ball m = T[worst].to_ball(128), n = T[worst + 1].to_ball(128);
      Ball mid;
      arb_add(mid.get(), m.get(), n.get(), 128);
      arb_mul_2exp_si(mid.get(), mid.get(), -1);
      Ball w;
      arb_sub(w.get(), n.get(), m.get(), 128);
      const Rational q = short_rational(mid, mid_rational(w) * Rational(1, 100));
      next = T;
      next.insert(next.begin() + static_cast<long>(worst) + 1, RealAlgebraic(q));
    }
    if (static_cast<long>(next.size()) - 1 > max_pieces) break;
    T = next;
  }
  Built fin = build(s, base, best, opt.digits, opt);
  MoebiusResult r = fin.r;
  r.target.used = true;
  r.target.value = target;
  r.target.rounds = rounds;
  const Ball tq(target, 2 * digits_to_bits(opt.digits) + 64);
  r.target.reached = arb_ge(r.u_after.get(), tq.get());
  return r;
}

}  // namespace uniparam
