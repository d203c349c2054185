// reparam/src/moebius_rational.cpp -- exact rational output of a piecewise
// Moebius map: short rational T, S, alpha and the certified u of that map;
// and the refinement of a map's data (the balls S and alpha) to more digits.
#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "moebius_detail.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/uniformity.hpp"

namespace uniparam {

namespace {

Rational pow10_inv(long d) {
  Integer p(1);
  for (long i = 0; i < d; ++i) p = p * Integer(10);
  return Rational(Integer(1), p);
}

// The exact ends of the ball b as rationals.
Rational lower_rational(const Ball& b) {
  Ball lo;
  arb_get_lbound_arf(arb_midref(lo.get()), b.get(), ARF_PREC_EXACT);
  return mid_rational(lo);
}
Rational upper_rational(const Ball& b) {
  Ball hi;
  arb_get_ubound_arf(arb_midref(hi.get()), b.get(), ARF_PREC_EXACT);
  return mid_rational(hi);
}

// A closed interval [first, second] known to hold a value.
using Range = std::pair<Rational, Rational>;

Range range_of(const Ball& b) { return {lower_rational(b), upper_rational(b)}; }

// For the increasing values x_0 = 0 < x_1 < ... < x_n = 1 known to lie in
// v[j]: the simplest rational q_j certainly within tol * gap_j of x_j, with
// gap_j a lower bound of the smaller gap to x_j's neighbours; ends exactly 0
// and 1. For tol < 1/2 the q_j increase strictly. False when some v[j] is
// too wide for its window (wider than tol * gap_j): the caller refines v.
bool round_sequence(const std::vector<Range>& v, const Rational& tol, std::vector<Rational>& out) {
  out.assign(1, Rational(0));
  for (std::size_t j = 1; j + 1 < v.size(); ++j) {
    Rational gap = v[j].first - v[j - 1].second;
    const Rational right = v[j + 1].first - v[j].second;
    if (right < gap) gap = right;
    if (gap <= Rational(0)) return false;
    const Rational w = gap * tol;
    // every x in v[j] is within w of every q in [hi - w, lo + w]
    if (v[j].second - v[j].first > w) return false;  // keep at least half the window
    const Rational q = Rational::simplest_between(v[j].second - w, v[j].first + w);
    if (q <= out.back()) return false;  // impossible for tol < 1/2
    out.push_back(q);
  }
  out.push_back(Rational(1));
  return true;
}

// The simplest rational q certainly within tol * m(x) of the value x the
// ball b encloses, for every x in b: |q - x| <= tol * m(x), with
// m(x) = x for a positive quantity (`unit` false) and m(x) = min(x, 1 - x)
// for one in (0, 1) (`unit` true), so q keeps the sign and, for a quantity in
// (0, 1), stays in (0, 1). tol < 1. Empty (false) when b is not certainly
// inside the domain or too wide for that window (its width above tol * m
// at b's worst end): the caller refines b.
bool round_relative(const Ball& b, const Rational& tol, bool unit, Rational& q) {
  if (!b.is_finite()) return false;
  const Rational lo = lower_rational(b), hi = upper_rational(b);
  if (lo <= Rational(0) || (unit && hi >= Rational(1))) return false;
  Rational m = lo;  // a lower bound of m(x) over b
  if (unit && Rational(1) - hi < m) m = Rational(1) - hi;
  const Rational w = tol * m;
  // every x in [lo, hi] is within w of every q in [hi - w, lo + w]
  if (hi - lo > w) return false;  // keep at least half the window
  q = Rational::simplest_between(hi - w, lo + w);
  return true;
}

}  // namespace

MoebiusResult make_rational(const Curve& c, const MoebiusResult& in, long rational_digits, const Options& opt) {
  if (rational_digits < 1 || rational_digits > 100)
    throw InvalidArgument("the rational rounding must keep 1 to 100 digits, got " + std::to_string(rational_digits));
  validate(opt);
  if (in.balanced) {
    // one more digit on q: composing with m at most doubles alpha's error
    // relative to min(alpha, 1 - alpha), and keeps k_0's relative error
    const MoebiusResult rq = make_rational(in.balanced->curve->q, *in.balanced->on, std::min(rational_digits + 1, 100L), opt);
    return detail::compose_balanced(in.balanced->curve, rq, in.u_before, opt.digits);
  }
  const Speed s(c, in.kind);
  const std::size_t N = in.pieces();
  const Rational tol = pow10_inv(rational_digits);
  const long prec0 = 4 * digits_to_bits(rational_digits + opt.digits) + 64;

  // Breakpoints chosen by a method (the optimiser, the C1 construction) are
  // rounded like S; breakpoints the user gave (moebius_c0) stay exact, and so
  // does every rational one among them. C0: each piece's alpha is rounded to
  // the simplest rational certainly within tol * min(alpha, 1 - alpha) of the
  // optimal alpha (so 0 < alpha < 1, and k = (1 - alpha) / alpha keeps the
  // relative accuracy tol). Every window is certain: the data's balls are
  // refined (the same map, more digits) until each fits its window.
  const bool chosen = in.optimiser.has_value() || in.target.has_value();
  bool irrational = false;
  for (std::size_t j = 1; j < N; ++j) irrational = irrational || !in.T[j].t.is_rational();
  MoebiusResult base = in;
  std::vector<Rational> Tq, Sq, alpha_q;
  for (long dd = 0;;) {
    const long prec = std::max(prec0, dd > 0 ? digits_to_bits(dd) + 64 : 0L);
    std::vector<Range> tr, sr;
    for (const auto& b : in.T)
      tr.push_back(b.t.is_rational() ? Range{b.t.rational(), b.t.rational()} : range_of(b.t.to_ball(prec)));
    for (const auto& b : base.S) sr.push_back(range_of(b));
    bool ok = true;
    if (chosen || irrational) {
      ok = round_sequence(tr, tol, Tq);
    } else {
      Tq.clear();
      for (const auto& b : in.T) Tq.push_back(b.t.rational());
    }
    if (ok && !chosen)
      for (std::size_t j = 0; j <= N; ++j)
        if (in.T[j].t.is_rational()) Tq[j] = in.T[j].t.rational();
    if (!in.identically_zero) {
      ok = ok && round_sequence(sr, tol, Sq);
      if (in.continuity == Continuity::C0) {
        alpha_q.assign(N, Rational(0));
        for (std::size_t i = 0; i < N && ok; ++i) ok = round_relative(base.alpha[i], tol, true, alpha_q[i]);
      }
    }
    if (ok) break;
    dd = dd > 0 ? 2 * dd : opt.digits + rational_digits + 8;
    if (digits_to_bits(dd) > opt.max_prec)
      throw BudgetExceeded("could not certify the map's data to the relative accuracy 10^-" +
                           std::to_string(rational_digits) + " of --rational-digits within " +
                           std::to_string(opt.max_prec) + " bits of working precision (raise it with --max-prec)");
    check_time_budget();
    if (!in.identically_zero) base = refine_moebius_data(s, in, dd, opt.max_prec);
  }
  std::vector<RealAlgebraic> T;
  for (const auto& q : Tq) T.emplace_back(q);

  MoebiusResult r = in;
  r.exact.emplace();
  r.exact->T = Tq;
  r.exact->S = Sq;
  r.T.clear();
  for (const auto& t : T) r.T.push_back(Breakpoint{t, 0, 0, 0});
  if (in.identically_zero) {
    r.exact->alpha.assign(N, Rational(1, 2));
    r.exact->S = Tq;
    r.S.clear();
    for (const auto& q : Tq) r.S.emplace_back(q, prec0);
    r.alpha.assign(N, Ball(Rational(1, 2), prec0));
    return r;
  }

  for (long bits = digits_to_bits(opt.digits) + 8;; bits += 32) {
    const long prec = 2 * bits + 64;
    r.integrals = all_piece_integrals(s, r.T, bits, opt.max_prec);
    std::vector<Rational> k(N);
    if (in.continuity == Continuity::C0) {
      for (std::size_t i = 0; i < N; ++i) k[i] = (Rational(1) - alpha_q[i]) / alpha_q[i];
    } else {
      // C1: the optimal free parameter for the rounded T and S, rounded; the
      // rest follows exactly from rho_i / k_i = rho_{i+1} k_{i+1}.
      std::vector<Ball> Sb;
      for (const auto& q : Sq) Sb.emplace_back(q, prec);
      const detail::C1Data d = detail::c1_from_pieces(T, Sb, r.integrals, r.mu, prec);
      // k_0 > 0 rounded relative to itself; a ball too wide for that waits
      // for the next, more precise round
      if (!round_relative(d.k[0], tol, false, k[0])) {
        if (bits > opt.max_prec)
          throw BudgetExceeded("could not certify the C1 free parameter to the relative accuracy 10^-" +
                               std::to_string(rational_digits) + " of --rational-digits within " +
                               std::to_string(opt.max_prec) + " bits of working precision (raise it with --max-prec)");
        continue;
      }
      for (std::size_t i = 0; i + 1 < N; ++i) {
        const Rational rho_i = (Tq[i + 1] - Tq[i]) / (Sq[i + 1] - Sq[i]);
        const Rational rho_j = (Tq[i + 2] - Tq[i + 1]) / (Sq[i + 2] - Sq[i + 1]);
        k[i + 1] = rho_i / (rho_j * k[i]);
      }
    }
    r.exact->alpha.clear();
    r.alpha.clear();
    r.S.clear();
    for (const auto& q : Sq) r.S.emplace_back(q, prec);
    Ball total(0);
    for (std::size_t i = 0; i < N; ++i) {
      const Rational a = Rational(1) / (Rational(1) + k[i]);
      r.exact->alpha.push_back(a);
      r.alpha.emplace_back(a, prec);
      // the piece's int sigma_{p o m}^2 ds = (k A + B + C / k) / ds_i, exact k, ds
      const Ball kb(k[i], prec), ikb(Rational(1) / k[i], prec), ids(Rational(1) / (Sq[i + 1] - Sq[i]), prec);
      Ball f, t;
      arb_mul(f.get(), kb.get(), r.integrals[i].A.get(), prec);
      arb_add(f.get(), f.get(), r.integrals[i].B.get(), prec);
      arb_mul(t.get(), ikb.get(), r.integrals[i].C.get(), prec);
      arb_add(f.get(), f.get(), t.get(), prec);
      arb_addmul(total.get(), f.get(), ids.get(), prec);
    }
    arb_mul(r.u_after.get(), r.mu.get(), r.mu.get(), prec);
    arb_div(r.u_after.get(), r.u_after.get(), total.get(), prec);
    if (r.u_after.meets_digits(opt.digits + 1)) break;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the rational reparameterization to " + std::to_string(opt.digits) +
                           " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
  if (r.target.has_value()) {
    const Ball tq(r.target->value, 2 * digits_to_bits(opt.digits) + 64);
    r.target->reached = arb_ge(r.u_after.get(), tq.get());
  }
  if (r.optimiser.has_value()) r.optimiser->phi = Ball();  // Phi belonged to the unrounded map
  return r;
}

namespace {

// out[0] = 0, out[N] = 1, out[i] = sum_{k<i} w_k / sum w (exact ends).
std::vector<Ball> cumulative_unit(const std::vector<Ball>& w, long prec) {
  Ball total(0);
  for (const auto& x : w) arb_add(total.get(), total.get(), x.get(), prec);
  return cumulative_normalised(w, total, prec);
}

std::vector<Ball> sqrts(const std::vector<PieceIntegrals>& I, Ball PieceIntegrals::*m, long prec) {
  std::vector<Ball> out(I.size());
  for (std::size_t i = 0; i < I.size(); ++i) arb_sqrtpos(out[i].get(), (I[i].*m).get(), prec);
  return out;
}

std::vector<Ball> alphas(const std::vector<PieceIntegrals>& I) {
  std::vector<Ball> out;
  for (const auto& p : I) out.push_back(p.alpha);
  return out;
}

}  // namespace

MoebiusResult refine_moebius_data(const Speed& sp, const MoebiusResult& in, long digits, long max_prec) {
  if (digits < 1) throw InvalidArgument("refine_moebius_data: digits must be at least 1");
  if (in.balanced) {
    const Speed sq(in.balanced->curve->q, sp.kind());
    const MoebiusResult rq = refine_moebius_data(sq, *in.balanced->on, digits, max_prec);
    return detail::compose_balanced(in.balanced->curve, rq, in.u_before, digits);
  }
  MoebiusResult x = in;
  if (x.identically_zero) return x;
  const std::size_t N = x.pieces();
  if (x.exact.has_value()) {
    const long prec = digits_to_bits(digits) + 64;
    x.S.clear();
    for (const auto& q : x.exact->S) x.S.emplace_back(q, prec);
    x.alpha.clear();
    for (const auto& q : x.exact->alpha) x.alpha.emplace_back(q, prec);
    return x;
  }
  std::vector<RealAlgebraic> T;
  for (const auto& b : x.T) T.push_back(b.t);
  for (long bits = digits_to_bits(digits) + 8;; bits += 32) {
    check_time_budget();
    const long prec = 2 * bits + 64;
    std::vector<PieceIntegrals> I = all_piece_integrals(sp, x.T, bits, max_prec);
    std::vector<Ball> S, alpha;
    if (x.continuity == Continuity::C0) {
      S = cumulative_unit(sqrts(I, &PieceIntegrals::M, prec), prec);
      alpha = alphas(I);
    } else {
      std::vector<Ball> len(N);
      for (std::size_t i = 0; i < N; ++i) len[i] = integrate_speed(sp, T[i], T[i + 1], bits, max_prec);
      S = cumulative_unit(len, prec);
      alpha = detail::c1_from_pieces(T, S, I, x.mu, prec).alpha;
    }
    if (all_meet_digits(S, digits) && all_meet_digits(alpha, digits)) {
      x.integrals = std::move(I);
      x.S = std::move(S);
      x.alpha = std::move(alpha);
      return x;
    }
    if (bits > max_prec)
      throw BudgetExceeded("could not refine the piecewise Moebius map's data to " + std::to_string(digits) +
                           " digits within " + std::to_string(max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

}  // namespace uniparam
