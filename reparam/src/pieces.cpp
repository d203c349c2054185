#include "uniparam/reparam/pieces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <functional>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/uniformity.hpp"
#include "speed_charts.hpp"

namespace uniparam {

namespace {

/// Bits the piece integrals' ends are refined to before the workers start:
/// what the first attempt's to_ball asks (working precision rel_goal_bits +
/// 32, see piece_integrals).
constexpr long kFirstEndBits = 32 + RealAlgebraic::kToBallExtraBits;

// Numerator of (sigma^2)' / g, up to the positive factor 1/D^3:
// (g^2 Q / D^2)' = g (2 g' Q D + g Q' D - 2 g Q D') / D^3 with Q = sum K^2.
// Its roots in (0, 1) are the critical points of sigma that are not zeros.
Poly critical_numerator(const Speed& s) {
  const Poly& g = s.g();
  Poly D = s.denominator();
  Poly Q(0);
  for (const auto& k : s.cofactors()) Q = Q + k * k;
  return Poly(2) * g.derivative() * Q * D + g * Q.derivative() * D - Poly(2) * g * Q * D.derivative();
}

// The piece's left end a and its length b - a as balls at precision
// prec (the quadrature's own end balls' precision, so the ends are refined
// once for both; t~ = (t - a) / (b - a) then carries a radius of
// ~2^-prec / (b - a), below the integrand's own rounding), for each
// working precision the integrands are called with (the
// Gauss-Legendre nodes and the wider error-bound balls come at different
// precisions). RealAlgebraic::to_ball remembers one precision only and its
// enclosure depends on (x, prec) alone, so caching here gives exactly the
// balls the integrands would compute on every call, without converting
// (and, for an irrational end, re-refining) the ends at every evaluation.
class PieceEnds {
 public:
  /// The length b - a at a precision (chart_piece_integrals: summed over
  /// the piece's spans in their charts, where b - a from the two ends'
  /// balls would cancel next to a feature).
  using Length = std::function<Ball(long prec)>;
  /// \pre a < b; length, when given, encloses b - a at every precision.
  PieceEnds(const RealAlgebraic& a, const RealAlgebraic& b, Length length = {})
      : a_(a), b_(b), length_(std::move(length)) {}
  PieceEnds(const PieceEnds&) = delete;
  PieceEnds& operator=(const PieceEnds&) = delete;
  /// ta = a, dt = b - a (real balls, imaginary part exactly 0).
  void get(acb_t ta, acb_t dt, long prec) {
    const Entry& e = entry(prec);
    acb_set_arb(ta, e.a.get());
    acb_set_arb(dt, e.d.get());
  }
  /// a, b, dt = b - a and 1 / dt as double-word balls (1 / dt holds 1 / d
  /// for every d in dt's ball).
  struct DD {
    DDBall a, b, dt, inv_dt;
  };
  /// The ends as double-word balls; null when they are not representable.
  const DD* get_dd(long prec) {
    const Entry& e = entry(prec);
    return e.dd_ok ? &e.dd : nullptr;
  }
  /// The enclosure of the end a alone (at prec).
  const Ball& a(long prec) { return entry(prec).a; }
  /// The enclosure of the end b alone (at prec, as a's).
  const Ball& b(long prec) { return entry(prec).b; }

 private:
  struct Entry {
    long prec = 0;
    Ball a, b, d;
    DD dd;  // a, b, d, 1 / d as double words (when dd_ok)
    bool dd_ok = false;
  };
  Entry& entry(long prec) {
    for (Entry& e : entries_)
      if (e.prec == prec) return e;
    Entry e;
    e.prec = prec;
    e.a = a_.to_ball(prec);
    e.b = b_.to_ball(prec);
    if (length_) {
      e.d = length_(prec + 16);
    } else {
      arb_sub(e.d.get(), e.b.get(), e.a.get(), prec + 16);
    }
    e.dd_ok = dd_set_arb(e.dd.a, e.a.get()) && dd_set_arb(e.dd.b, e.b.get()) && dd_set_arb(e.dd.dt, e.d.get()) &&
              dd_div(e.dd.inv_dt, dd_from_double(1), e.dd.dt);
    entries_.push_back(std::move(e));
    return entries_.back();
  }
  const RealAlgebraic& a_;
  const RealAlgebraic& b_;
  Length length_;
  std::vector<Entry> entries_;  // a handful of precisions per piece
};

// Integrands scaled by powers of 2 whose exponents are below this bound in
// absolute value are left unscaled (integrals within 2^64 of 1 meet the
// quadrature's absolute tolerance as they are; their double-word nodes stay).
constexpr long kUnscaledExpBound = 64;

// UNCERTIFIED: for each of the count integrands f_k of a piece, e_k with
// 2^e_k near its integral over the piece (0 where |e_k| < kUnscaledExpBound
// or nothing finite and positive was seen): midpoint sums of f at 64 bits
// on 16 equal cells of the piece (in the local coordinate t~) and, since
// the integrands may vary on a scale down to 2^-scale_bits at the ends
// (speed_scale_bits), on the cells [2^-(j+1), 2^-j] next to either end for
// 4 <= j < scale_bits + 8. Only steers the exact scaling of piece_integrals
// (an estimate off by 2^d moves the quadrature's absolute tolerance by
// 2^d against the integral: more work, or a retry at higher precision).
// Curves whose speed has coefficients below kUnscaledExpBound bits
// (coefficient_bits, speed_coefficient_bits) are not sampled (all e_k = 0):
// the samples cost as much as a low-degree piece's quadrature, and such
// pieces are integrated unscaled.
std::vector<long> piece_scale_exponents(const Integrand& f, std::size_t count, PieceEnds& ends, long scale_bits,
                                        long coefficient_bits) {
  constexpr long kPrec = 64;
  std::vector<long> exps(count, 0);
  if (coefficient_bits < kUnscaledExpBound) return exps;
  std::vector<Ball> sums(count, Ball(0));
  acb_t ta, dt, z;
  acb_ptr w = _acb_vec_init(static_cast<slong>(count));
  acb_init(ta);
  acb_init(dt);
  acb_init(z);
  ends.get(ta, dt, kPrec);
  arb_t x, v;
  arb_init(x);
  arb_init(v);
  auto add = [&](long cell_exp) {  // the sample at local x, over a cell of width 2^cell_exp
    acb_set_arb(z, x);
    acb_mul(z, z, dt, kPrec);
    acb_add(z, z, ta, kPrec);
    mag_zero(arb_radref(acb_realref(z)));
    arb_zero(acb_imagref(z));
    try {
      f(w, z, false, kPrec);
    } catch (const std::exception&) {
      return;
    }
    for (std::size_t k = 0; k < count; ++k) {
      if (!acb_is_finite(w + k) || !arb_is_positive(acb_realref(w + k))) continue;
      arb_set_arf(v, arb_midref(acb_realref(w + k)));
      arb_mul_2exp_si(v, v, cell_exp);
      arb_add(sums[k].get(), sums[k].get(), v, kPrec);
    }
  };
  for (int i = 0; i < 16; ++i) {
    arb_set_si(x, 2 * i + 1);
    arb_mul_2exp_si(x, x, -5);  // (2i + 1) / 32
    add(-4);
  }
  for (long j = 4; j < scale_bits + 8; ++j) {
    arb_set_si(x, 3);
    arb_mul_2exp_si(x, x, -(j + 2));  // 3 * 2^-(j+2), the middle of [2^-(j+1), 2^-j]
    add(-(j + 1));
    arb_neg(x, x);
    arb_add_si(x, x, 1, kPrec + j);  // exact
    add(-(j + 1));
  }
  // the piece's length (t~ is the local coordinate)
  Ball len;
  arb_set(len.get(), acb_realref(dt));
  for (std::size_t k = 0; k < count; ++k) {
    arb_mul(sums[k].get(), sums[k].get(), len.get(), kPrec);
    if (!sums[k].is_finite() || !(arf_sgn(arb_midref(sums[k].get())) > 0)) continue;
    const long e = arf_abs_bound_lt_2exp_si(arb_midref(sums[k].get())) - 1;
    if (std::labs(e) >= kUnscaledExpBound) exps[k] = e;
  }
  arb_clear(x);
  arb_clear(v);
  acb_clear(ta);
  acb_clear(dt);
  acb_clear(z);
  _acb_vec_clear(w, static_cast<slong>(count));
  return exps;
}

}  // namespace

std::vector<Breakpoint> mark_zeros(const Speed& s, const std::vector<RealAlgebraic>& ts) {
  if (ts.size() < 2 || !(ts.front() == RealAlgebraic(0)) || !(ts.back() == RealAlgebraic(1)))
    throw InvalidArgument("breakpoints must start at 0 and end at 1");
  std::vector<Breakpoint> out;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (i > 0 && !(ts[i - 1] < ts[i])) throw InvalidArgument("breakpoints must be strictly increasing");
    Breakpoint b{ts[i], 0, 0, 0};
    for (const auto& z : s.zeros())
      if (z.t == ts[i]) { b.multiplicity = z.multiplicity; b.factor = z.factor; b.zero_index = z.index; }
    out.push_back(b);
  }
  return out;
}

std::vector<RealAlgebraic> critical_points(const Speed& s) {
  std::vector<RealAlgebraic> out;
  if (s.identically_zero()) return out;
  Poly P = critical_numerator(s);
  if (P.is_zero()) return out;
  // P's values from the speed's factors (degree ~d local expansions,
  // coarse on the subdivision's intervals), not from P's power basis:
  // for the isolation, and kept by the roots for their refinement (the
  // integrals' ends), so the evaluator owns a copy of the speed (which
  // shares the caches of s).
  auto speed = std::make_shared<const Speed>(s);
  const PolyEvaluator ev = [speed](arb_t v, arb_t d, const arb_t x, long prec) {
    acb_t z, pv, pd;
    acb_init(z);
    acb_init(pv);
    acb_init(pd);
    acb_set_arb(z, x);
    speed->eval_critical(pv, d ? pd : nullptr, z, prec);
    arb_set(v, acb_realref(pv));  // P is real at real points: Re holds it
    if (d) arb_set(d, acb_realref(pd));
    acb_clear(z);
    acb_clear(pv);
    acb_clear(pd);
  };
  // ev evaluates P = lambda r.factor exactly when r.factor is P's
  // primitive part (not a proper factor of P)
  const Poly Pp = P.primitive();
  const auto sev = std::make_shared<const ScaledEvaluator>(
      ScaledEvaluator{ev, Rational(P.leading()) / Rational(Pp.leading()), nullptr});
  // The isolation is serial, and its callers run it next to mu's quadrature
  // (radical, reparam --target): the halves [0, 1/2] and [1/2, 1] side by
  // side keep both cores busy to the end. A fixed split, so the roots do
  // not depend on the threads; a root at 1/2 is exact in both, kept once.
  // ev only reads the speed's caches (locked): safe from both workers.
  const Rational half(1, 2);
  std::vector<IsolatedRoot> halves[2];
  parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t i) {
    halves[i] = isolate_real_roots(P, ev, i == 0 ? Rational(0) : half, i == 0 ? half : Rational(1));
  });
  const bool twice = !halves[0].empty() && !halves[1].empty() && halves[0].back().is_exact() &&
                     halves[1].front().is_exact() && halves[0].back().lo == half && halves[1].front().lo == half;
  if (twice) halves[1].erase(halves[1].begin());
  for (const auto& h : halves)
    for (const auto& r : h) {
      if (!r.is_exact() && r.factor == Pp) out.emplace_back(r, sev);
      else out.emplace_back(r);
    }
  return out;
}

std::vector<Breakpoint> critical_breakpoints(const Speed& s) {
  std::vector<RealAlgebraic> ts{RealAlgebraic(0), RealAlgebraic(1)};
  for (const auto& z : s.zeros()) ts.push_back(z.t);
  for (auto& t : critical_points(s)) ts.push_back(std::move(t));
  std::sort(ts.begin(), ts.end(), [](const RealAlgebraic& x, const RealAlgebraic& y) { return x < y; });
  std::vector<RealAlgebraic> uniq;
  for (auto& t : ts)
    if (uniq.empty() || !(uniq.back() == t)) uniq.push_back(t);
  std::vector<Breakpoint> bp = mark_zeros(s, uniq);
  // Never two zeros of sigma in a row (Rolle excludes it inside (0, 1), but
  // keep the rule of docs/math.md section 4 unconditional).
  std::vector<Breakpoint> out;
  for (auto& b : bp) {
    if (!out.empty() && out.back().multiplicity > 0 && b.multiplicity > 0) {
      const RealAlgebraic& x = out.back().t;
      x.refine(16);
      b.t.refine(16);
      Rational mid = (x.hi() + b.t.lo()) * Rational(1, 2);
      out.push_back(Breakpoint{RealAlgebraic(mid), 0, 0, 0});
    }
    out.push_back(b);
  }
  return out;
}

namespace {

// out[0..2] = v (1 - s)^2, 2 v s (1 - s), v s^2: the integrands of a
// piece's A, B, C (Bernstein weights of degree 2) from s and r = 1 - s.
void quadratic_weights(acb_ptr out, const acb_t s, const acb_t r, const acb_t v, long prec) {
  acb_mul(out, r, r, prec);
  acb_mul(out, out, v, prec);
  acb_mul(out + 1, s, r, prec);
  acb_mul_2exp_si(out + 1, out + 1, 1);
  acb_mul(out + 1, out + 1, v, prec);
  acb_mul(out + 2, s, s, prec);
  acb_mul(out + 2, out + 2, v, prec);
}

// r's A, B, C from abc[0..2] and, next to a zero (abc[3]), its integral
// of sigma^2; then L = A + B + C, M = B + 2 sqrt(A C), alpha = 1 / (1 +
// sqrt(C / A)).
void finish_piece(PieceIntegrals& r, std::vector<Ball> abc, long rel_goal_bits) {
  r.A = std::move(abc[0]);
  r.B = std::move(abc[1]);
  r.C = std::move(abc[2]);
  if (abc.size() > 3) {
    r.square = std::move(abc[3]);
    r.square_bits = rel_goal_bits;
  }
  const long prec = 2 * rel_goal_bits + 64;
  arb_add(r.L.get(), r.A.get(), r.B.get(), prec);
  arb_add(r.L.get(), r.L.get(), r.C.get(), prec);
  Ball t;
  arb_mul(t.get(), r.A.get(), r.C.get(), prec);
  arb_sqrt(t.get(), t.get(), prec);
  arb_mul_2exp_si(t.get(), t.get(), 1);
  arb_add(r.M.get(), r.B.get(), t.get(), prec);
  arb_div(t.get(), r.C.get(), r.A.get(), prec);
  arb_sqrt(t.get(), t.get(), prec);
  arb_add_ui(t.get(), t.get(), 1, prec);
  arb_inv(r.alpha.get(), t.get(), prec);
}

// An end e of a piece as k + delta (chart_piece_integrals): k the feature
// end k0 of the chart of the span e ends, and delta = phi(u_e) - k0 from e's
// coordinate u_e there (relative accuracy however close e is to k0); on a
// plain span e's own ball serves. A span of another chart takes
// d (t - e) = d (t - k) - d delta: t - k exactly, and no rounding of e
// against k (e 10^-150 from the neighbouring part's feature end would
// otherwise leave d (t - e) there no digits).
struct EndAnchor {
  Rational k;
  const SpeedChart* chart = nullptr;  // e's chart; null on a plain span
  const RealAlgebraic* at = nullptr;  // u_e, or e itself on a plain span
  // delta at the last precision asked (the integrands ask at every node)
  mutable long delta_prec = -1;
  mutable Ball delta_ball;

  EndAnchor(Rational k_, const SpeedChart* chart_, const RealAlgebraic* at_)
      : k(std::move(k_)), chart(chart_), at(at_) {}

  /// The anchor of the piece's start (start) or end, which the span sp
  /// (its first or its last) ends at.
  static EndAnchor of(const SpeedCharts& ch, const SpeedCharts::Span& sp, const RealAlgebraic& e, bool start) {
    if (sp.plain) return EndAnchor{Rational(0), nullptr, &e};
    const SpeedChart& c = ch.charts[sp.chart];
    // in a chart where phi decreases, the span's start in t is u1
    const bool reversed = c.k1 < c.k0;
    return EndAnchor{c.k0, &c, start != reversed ? &sp.u0 : &sp.u1};
  }
  /// delta at prec, memoised for the last precision. \pre chart.
  const Ball& delta(long prec) const {
    if (prec == delta_prec) return delta_ball;
    const Ball u = at->to_ball(prec), zero(0L);
    delta_ball = chart->length_between(zero.get(), u.get(), prec);
    if (chart->k1 < chart->k0) arb_neg(delta_ball.get(), delta_ball.get());
    delta_prec = prec;
    return delta_ball;
  }
  /// d(z) (phi(z) - e) in the chart c.
  void offset(const SpeedChart& c, acb_t out, const acb_t z, long prec) const {
    if (!chart) {  // e away from every feature: its own ball
      c.offset(out, z, at->to_ball(prec).get(), prec);
      return;
    }
    const Ball& dl = delta(prec);
    acb_t d;
    acb_init(d);
    c.denominator(d, z, prec);
    acb_mul_arb(d, d, dl.get(), prec);
    c.offset(out, z, k, prec);
    acb_sub(out, out, d, prec);
    acb_clear(d);
  }
};

// A, B, C of the piece [a, b] of s (piece_integrals), and next to a zero
// of sigma at an end (side, zero with multiplicity mu) the integral of
// sigma^2 besides, span by span in s's charts: sigma^2 dt = sigma_phi(u)^2
// / |phi'(u)| du = sigma_phi^2 d(u)^2 w0 du with t = phi(u) (SpeedChart).
// With g = side (t - gamma) > 0 on the piece, the integrands are those of
// piece_integrals: v = sigma^2 Delta t^(mu+1) / ((mu+1) g^mu) (mu = 0: v =
// sigma^2 Delta t) times the weights of s~ = t~^(mu+1) (Left) or
// 1 - (1 - t~)^(mu+1) (Right; t~ itself for none). On the span at gamma
// in a chart, gamma's image u_g is a zero of the chart's speed of the same
// multiplicity, deflated there: t - gamma = h a b (u - u_g) / (d(u) d(u_g))
// (h = k1 - k0; a Moebius map's difference quotient, no cancellation), so
// sigma^2 / g^mu dt = [sigma_phi^2 / (side_u (u - u_g))^mu] d^2 w0
// (d(u) d(u_g) w0)^mu du, side_u the side of u_g the span lies on. The
// integrands are >= 0, so the spans' relative accuracies carry to the sums.
// Empty where u_g is not a zero of the chart's speed of multiplicity mu
// (not expected: phi is an exact diffeomorphism of the part; the caller
// then integrates on p's own parameter).
std::optional<std::vector<Ball>> chart_piece_integrals(const Speed& s, const SpeedCharts& ch, const RealAlgebraic& a,
                                                       const RealAlgebraic& b, ZeroSide side, const SpeedZero& zero,
                                                       int mu, long rel_goal_bits, long max_prec) {
  const std::size_t count = side == ZeroSide::None ? 3 : 4;
  std::vector<Ball> total(count, Ball(0));
  const std::vector<SpeedCharts::Span> spans = ch.spans(a, b);
  // b - a as the sum of the spans' lengths, each from its ends in its own
  // coordinate (relative enclosures): a piece next to a feature, e.g.
  // between a peak and its inflections 10^-50 away, keeps its length's
  // digits, which b - a from balls of a and b near 1/3 would cancel.
  PieceEnds ends(a, b, [&spans, &ch](long prec) {
    Ball sum(0L);
    for (const SpeedCharts::Span& sp : spans) {
      const Ball u0 = sp.u0.to_ball(prec), u1 = sp.u1.to_ball(prec);
      Ball len;
      if (sp.plain) {
        arb_sub(len.get(), u1.get(), u0.get(), prec);
      } else {
        len = ch.charts[sp.chart].length_between(u0.get(), u1.get(), prec);
      }
      arb_add(sum.get(), sum.get(), len.get(), prec);
    }
    return sum;
  });
  const EndAnchor anchor_a = EndAnchor::of(ch, spans.front(), a, true);
  const EndAnchor anchor_b = EndAnchor::of(ch, spans.back(), b, false);
  for (std::size_t j = 0; j < spans.size(); ++j) {
    const SpeedCharts::Span& sp = spans[j];
    const SpeedChart& c = ch.charts[sp.chart];
    // the speed integrated: the chart's, or s itself on a plain span
    const Speed& speed = sp.plain ? s : c.speed;
    // the span at gamma, where sigma^2 / g^mu is deflated (by the chart
    // speed's own zero at gamma's image, at the span's end u_g)
    const bool at_zero = (side == ZeroSide::Left && j == 0) || (side == ZeroSide::Right && j + 1 == spans.size());
    SpeedZero local_zero = zero;
    int side_u = side == ZeroSide::Left ? 1 : -1;
    const RealAlgebraic* u_g = nullptr;
    if (at_zero && !sp.plain) {
      const RealAlgebraic u_zero = c.local(zero.t);
      bool found = false;
      for (const SpeedZero& z : c.speed.zeros())
        if (z.t == u_zero && z.multiplicity == mu) {
          local_zero = z;
          found = true;
        }
      if (!found) return std::nullopt;
      u_g = u_zero == sp.u0 ? &sp.u0 : &sp.u1;
      side_u = u_g == &sp.u0 ? 1 : -1;
    }
    // the span's ends in u, per precision (u_g is one of them)
    PieceEnds local(sp.u0, sp.u1);
    // the piece's ends a and b where they end this span (its first and its
    // last), as chart points: u0 and u1, swapped where phi decreases
    const bool reversed = c.k1 < c.k0;
    const bool ends_at_a = j == 0, ends_at_b = j + 1 == spans.size();
    Integrand raw = [&, plain = sp.plain, at_zero](acb_ptr out, const acb_t z, bool, long prec) {
      acb_t ta, dt, x, y, v, d, w;
      for (acb_ptr q : {ta, dt, x, y, v, d, w}) acb_init(q);
      ends.get(ta, dt, prec);
      // v = sigma^2 / g^mu dt/du (deflated at gamma), x = t~, y = 1 - t~,
      // and w = sigma^2 dt/du (next to a zero)
      if (plain) {
        if (at_zero) {
          speed.eval_squared_over_zero(v, z, zero, side_u, mu, prec, false);
        } else {
          speed.eval_squared(v, z, prec);
        }
        acb_sub(x, z, ta, prec);
        acb_sub_arb(y, z, ends.b(prec).get(), prec);
        acb_one(d);
      } else {
        if (at_zero) {
          speed.eval_squared_over_zero(v, z, local_zero, side_u, mu, prec, false);
        } else {
          speed.eval_squared(v, z, prec);
        }
        // d (t - a) and d (t - b); from a's or b's chart coordinate where
        // it ends this span, next to which t - a (t - b) is small
        if (ends_at_a) {
          c.offset_local(x, z, (reversed ? local.b(prec) : local.a(prec)).get(), prec);
        } else {
          anchor_a.offset(c, x, z, prec);
        }
        if (ends_at_b) {
          c.offset_local(y, z, (reversed ? local.a(prec) : local.b(prec)).get(), prec);
        } else {
          anchor_b.offset(c, y, z, prec);
        }
        if (side == ZeroSide::None) {
          // f_k = v Y^2, 2 v X Y, v X^2 with X = d t~, Y = d (1 - t~) and
          // v = sigma_phi^2 w0 Delta t: d^2 w0 = dt/du is in X^2, and the
          // integrand has no division by d (whose zero, phi's pole, lies
          // within 2^-k of [0, 1] for a map of ratio 2^k)
          arb_mul(acb_realref(w), c.w0(prec).get(), acb_realref(dt), prec);
          acb_mul_arb(v, v, acb_realref(w), prec);
          acb_div(x, x, dt, prec);
          acb_div(y, y, dt, prec);
          acb_neg(y, y);
          quadratic_weights(out, x, y, v, prec);
          for (acb_ptr q : {ta, dt, x, y, v, d, w}) acb_clear(q);
          return;
        }
        // next to a zero, the weights of s~ = t~^(mu+1) (or its mirror) are
        // not homogeneous in X, Y: t~ = X / (d Delta t), with the pole of
        // phi that the integrand has there too (order mu)
        c.denominator(d, z, prec);
        acb_div(x, x, d, prec);
        acb_div(y, y, d, prec);
        // dt/du = d^2 w0
        acb_mul(w, d, d, prec);
        acb_mul_arb(w, w, c.w0(prec).get(), prec);
        acb_mul(v, v, w, prec);
      }
      acb_div(x, x, dt, prec);  // t~
      acb_div(y, y, dt, prec);
      acb_neg(y, y);            // 1 - t~
      if (side == ZeroSide::None) {
        acb_mul(v, v, dt, prec);
        quadratic_weights(out, x, y, v, prec);
      } else {
        if (at_zero) {
          if (plain) {
            // sigma^2 = v g^mu, g = side (t - gamma) = Delta t t~ (Left) or Delta t (1 - t~)
            acb_mul(w, side == ZeroSide::Left ? x : y, dt, prec);
            acb_pow_ui(w, w, static_cast<ulong>(mu), prec);
            acb_mul(out + 3, v, w, prec);
          } else {
            // (d(u) d(u_g) w0)^mu, and sigma^2 dt/du = v (side_u (u - u_g))^mu / that
            acb_t dg, ug, r;
            acb_init(dg);
            acb_init(ug);
            acb_init(r);
            acb_set_arb(ug, (u_g == &sp.u0 ? local.a(prec) : local.b(prec)).get());
            c.denominator(dg, ug, prec);
            acb_mul(r, d, dg, prec);
            acb_mul_arb(r, r, c.w0(prec).get(), prec);
            acb_pow_ui(r, r, static_cast<ulong>(mu), prec);
            acb_sub(ug, z, ug, prec);
            if (side_u < 0) acb_neg(ug, ug);
            acb_pow_ui(ug, ug, static_cast<ulong>(mu), prec);
            acb_mul(out + 3, v, ug, prec);
            acb_mul(v, v, r, prec);
            acb_clear(dg);
            acb_clear(ug);
            acb_clear(r);
          }
        } else {
          acb_set(out + 3, v);
          acb_mul(w, side == ZeroSide::Left ? x : y, dt, prec);  // g
          acb_pow_ui(w, w, static_cast<ulong>(mu), prec);
          acb_div(v, v, w, prec);
        }
        // v Delta t^(mu+1) / (mu+1), s~ from t~
        acb_pow_ui(w, dt, static_cast<ulong>(mu + 1), prec);
        acb_mul(v, v, w, prec);
        acb_div_ui(v, v, static_cast<ulong>(mu + 1), prec);
        // s~ and 1 - s~ as products, never by 1 - (...): for Left, s~ =
        // t~^(mu+1) and 1 - s~ = (1 - t~) sum_{j<=mu} t~^j; for Right the
        // same with t~ and 1 - t~ swapped. Both keep their relative accuracy
        // next to either end (next to a chart's feature at the end away
        // from the zero, sigma^2 is huge and 1 - (1 - t~)^(mu+1) would
        // leave 2^-prec of it in B and C).
        acb_ptr near = side == ZeroSide::Left ? x : y;  // t~ or 1 - t~: the zero's end
        acb_ptr far = side == ZeroSide::Left ? y : x;
        acb_t sum, pw;
        acb_init(sum);
        acb_init(pw);
        acb_one(sum);
        acb_one(pw);
        for (int i = 1; i <= mu; ++i) {
          acb_mul(pw, pw, near, prec);
          acb_add(sum, sum, pw, prec);
        }
        acb_mul(pw, pw, near, prec);  // near^(mu+1)
        acb_mul(far, far, sum, prec);
        acb_swap(near, pw);
        acb_clear(sum);
        acb_clear(pw);
        quadratic_weights(out, x, y, v, prec);
      }
      for (acb_ptr q : {ta, dt, x, y, v, d, w}) acb_clear(q);
    };
    const long scale_bits = speed_scale_bits(speed);
    const std::vector<long> exps = piece_scale_exponents(raw, count, local, scale_bits, speed_coefficient_bits(speed));
    Integrand f = [&raw, &exps, count](acb_ptr out, const acb_t z, bool analytic, long prec) {
      raw(out, z, analytic, prec);
      for (std::size_t k = 0; k < count; ++k) acb_mul_2exp_si(out + k, out + k, -exps[k]);
    };
    QuadratureOptions qo;
    qo.rel_goal_bits = rel_goal_bits;
    qo.max_prec = max_prec;
    qo.scale_bits = scale_bits;
    qo.what = side == ZeroSide::None ? "the piece integrals A, B, C" : "the piece integrals A, B, C and of sigma^2";
    qo.singularity_hints = speed.singularity_hints(true);
    std::vector<Ball> abc = integrate_many(f, count, sp.u0, sp.u1, qo);
    for (std::size_t k = 0; k < count; ++k) {
      arb_mul_2exp_si(abc[k].get(), abc[k].get(), exps[k]);
      arb_add(total[k].get(), total[k].get(), abc[k].get(), 2 * rel_goal_bits + 64);
    }
  }
  return total;
}

}  // namespace

Ball PieceIntegrals::one_minus_alpha(long prec) const {
  Ball r;
  arb_sub_ui(r.get(), alpha.get(), 1, prec);
  arb_neg(r.get(), r.get());
  if (!arb_is_positive(A.get()) || !arb_is_positive(C.get())) return r;
  Ball q;
  arb_div(q.get(), A.get(), C.get(), prec);
  arb_sqrt(q.get(), q.get(), prec);
  arb_add_ui(q.get(), q.get(), 1, prec);
  arb_inv(q.get(), q.get(), prec);
  Ball both;
  if (arb_intersection(both.get(), r.get(), q.get(), prec)) return both;
  return r;  // unreachable under the precondition: both enclose 1 - alpha
}

PieceIntegrals piece_integrals(const Speed& s, const Breakpoint& a, const Breakpoint& b, long rel_goal_bits,
                               long max_prec) {
  if (a.multiplicity > 0 && b.multiplicity > 0)
    throw DomainError("a piece may not have zeros of the speed at both ends");
  PieceIntegrals r;
  if (s.identically_zero()) {
    r.A = r.B = r.C = r.L = r.M = Ball(0);
    r.alpha = Ball(Rational(1, 2), 64);
    return r;
  }
  const ZeroSide side = a.multiplicity > 0 ? ZeroSide::Left : b.multiplicity > 0 ? ZeroSide::Right : ZeroSide::None;
  const int mu = side == ZeroSide::Left ? a.multiplicity : side == ZeroSide::Right ? b.multiplicity : 0;
  const SpeedZero zero = side == ZeroSide::Left ? a.zero() : side == ZeroSide::Right ? b.zero() : SpeedZero{a.t, 0};
  // A speed with narrow features inside (0, 1): span by span in its
  // parts' charts (speed_charts.hpp).
  if (const SpeedCharts* ch = s.charts())
    if (std::optional<std::vector<Ball>> abc =
            chart_piece_integrals(s, *ch, a.t, b.t, side, zero, mu, rel_goal_bits, max_prec)) {
      finish_piece(r, std::move(*abc), rel_goal_bits);
      return r;
    }

  // f_k(t) = sigma^2 rho w_k(s~): k = 0, 1, 2 for (1-s~)^2, 2 s~(1-s~), s~^2,
  // the three in one quadrature (one evaluation of the speed per point).
  PieceEnds ends(a.t, b.t);
  Integrand raw = [&s, &ends, &zero, side, mu](acb_ptr out, const acb_t z, bool, long prec) {
    acb_t ta, dt, tt, st, w, v;
    acb_init(ta);
    acb_init(dt);
    acb_init(tt);
    acb_init(st);
    acb_init(w);
    acb_init(v);
    ends.get(ta, dt, prec);
    acb_sub(tt, z, ta, prec);
    acb_div(tt, tt, dt, prec);  // t~
    if (side == ZeroSide::None) {
      // every narrow real point went to node_fast (below) first: where it
      // refused, eval_squared's double-word attempt would refuse too
      s.eval_squared(v, z, prec, false);
      acb_mul(v, v, dt, prec);  // rho = Delta t
      acb_set(st, tt);
    } else {
      // sigma^2 rho = Delta t^(mu+1) / (mu+1) * sigma^2 / (side (t - gamma))^mu
      // (double words skipped as above)
      s.eval_squared_over_zero(v, z, zero, side == ZeroSide::Left ? 1 : -1, mu, prec, false);
      // out[3] = sigma^2 = v (side (t - gamma))^mu, for piece_square_integral;
      // gamma is the end a (Left) or b (Right), the cached enclosure
      if (side == ZeroSide::Left) {
        acb_sub(w, z, ta, prec);
      } else {
        acb_sub_arb(w, z, ends.b(prec).get(), prec);
        acb_neg(w, w);
      }
      acb_pow_ui(w, w, static_cast<ulong>(mu), prec);
      acb_mul(out + 3, v, w, prec);
      acb_pow_ui(w, dt, static_cast<ulong>(mu + 1), prec);
      acb_mul(v, v, w, prec);
      acb_div_ui(v, v, static_cast<ulong>(mu + 1), prec);
      if (side == ZeroSide::Left) {
        acb_pow_ui(st, tt, static_cast<ulong>(mu + 1), prec);
      } else {
        acb_sub_ui(w, tt, 1, prec);
        acb_neg(w, w);  // 1 - t~
        acb_pow_ui(w, w, static_cast<ulong>(mu + 1), prec);
        acb_sub_ui(st, w, 1, prec);
        acb_neg(st, st);
      }
    }
    acb_sub_ui(w, st, 1, prec);
    acb_neg(w, w);  // 1 - s~
    quadratic_weights(out, st, w, v, prec);
    acb_clear(ta);
    acb_clear(dt);
    acb_clear(tt);
    acb_clear(st);
    acb_clear(w);
    acb_clear(v);
  };
  const std::size_t count = side == ZeroSide::None ? 3 : 4;
  const long scale_bits = speed_scale_bits(s);
  // Each integrand times 2^-exps[k] (exact), so that an integral of about
  // 2^exps[k] becomes about 1: the quadrature's absolute tolerance
  // 2^-prec then stands for the relative one, whatever the size (a piece
  // where sigma^2 is 2^-6650 would otherwise be accepted at once and
  // certified only once prec passes 6650 bits).
  std::vector<long> exps = piece_scale_exponents(raw, count, ends, scale_bits, speed_coefficient_bits(s));
  bool scaled = false;
  for (long e : exps) scaled = scaled || e != 0;
  Integrand f = [&raw, &exps, count](acb_ptr out, const acb_t z, bool analytic, long prec) {
    raw(out, z, analytic, prec);
    for (std::size_t k = 0; k < count; ++k) acb_mul_2exp_si(out + k, out + k, -exps[k]);
  };
  QuadratureOptions qo;
  qo.rel_goal_bits = rel_goal_bits;
  qo.max_prec = max_prec;
  qo.scale_bits = scale_bits;
  // next to a zero, the integral of sigma^2 too (u_before: not L / Delta t there)
  qo.what = side == ZeroSide::None ? "the piece integrals A, B, C" : "the piece integrals A, B, C and of sigma^2";
  qo.singularity_hints = s.singularity_hints(true);
  // The narrow real points in double words: the same f_k as above. Next to
  // a zero, sigma^2 / (side (t - gamma))^mu by division (the nodes are not
  // at gamma; close to it, sigma^2's cancellation shows in its radius and
  // the accuracy check below sends the node to f, which deflates).
  // Double words scale exactly by 2^e for small |e| only: a scaled piece's
  // nodes all go to f (its unscaled values are out of double range anyway).
  if (!scaled) qo.node_fast = [&s, &ends, side, mu](DDBall* out, const DDBall& t, long prec) {
    const PieceEnds::DD* e = ends.get_dd(prec);
    if (!e) return false;
    const DDBall &ta = e->a, &tb = e->b, &dt = e->dt;
    DDBall v, st;
    if (!s.eval_dd(v, t, Speed::PieceSigns{}, true, prec)) return false;
    const DDBall tt = dd_mul(dd_sub(t, ta), e->inv_dt);  // t~
    const DDBall one = dd_from_double(1);
    if (side == ZeroSide::None) {
      v = dd_mul(v, dt);  // rho = Delta t
      st = tt;
    } else {
      out[3] = v;  // sigma^2
      // g = side (t - gamma), gamma = a (Left) or b (Right)
      const DDBall g = side == ZeroSide::Left ? dd_sub(t, ta) : dd_sub(tb, t);
      DDBall gm = g, dm = dt;
      for (int i = 1; i < mu; ++i) gm = dd_mul(gm, g);  // g^mu
      for (int i = 0; i < mu; ++i) dm = dd_mul(dm, dt);  // dt^(mu+1)
      if (!dd_div(v, v, gm)) return false;
      if (!dd_div(v, dd_mul(v, dm), dd_from_double(mu + 1))) return false;
      // s~ = t~^(mu+1) (Left) or 1 - (1 - t~)^(mu+1) (Right)
      const DDBall base = side == ZeroSide::Left ? tt : dd_sub(one, tt);
      DDBall p = base;
      for (int i = 0; i < mu; ++i) p = dd_mul(p, base);
      st = side == ZeroSide::Left ? p : dd_sub(one, p);
    }
    const DDBall w = dd_sub(one, st);  // 1 - s~
    const DDBall wv = dd_mul(w, v), sv = dd_mul(st, v);
    out[0] = dd_mul(wv, w);
    out[1] = dd_mul_2exp(dd_mul(wv, st), 1);
    out[2] = dd_mul(sv, st);
    const double goal = std::ldexp(1.0, -static_cast<int>(prec - kNodeFastSlackBits));
    for (int k = 0; k < (side == ZeroSide::None ? 3 : 4); ++k)
      if (!(dd_rel_rad(out[k]) <= goal)) return false;
    return true;
  };
  std::vector<Ball> abc = integrate_many(f, count, a.t, b.t, qo);
  for (std::size_t k = 0; k < count; ++k) arb_mul_2exp_si(abc[k].get(), abc[k].get(), exps[k]);
  finish_piece(r, std::move(abc), rel_goal_bits);
  return r;
}

Ball piece_square_integral(const Speed& s, const Breakpoint& a, const Breakpoint& b, const PieceIntegrals& pi,
                           long rel_goal_bits, long max_prec) {
  if (a.multiplicity > 0 || b.multiplicity > 0)
    return pi.square_bits >= rel_goal_bits ? pi.square : integrate_speed_squared(s, a.t, b.t, rel_goal_bits, max_prec);
  const long prec = 2 * rel_goal_bits + 64;
  Ball dt, out;
  arb_sub(dt.get(), b.t.to_ball(rel_goal_bits + 32).get(), a.t.to_ball(rel_goal_bits + 32).get(), prec);
  arb_div(out.get(), pi.L.get(), dt.get(), prec);
  return out;
}

std::vector<PieceIntegrals> all_piece_integrals(const Speed& s, const std::vector<Breakpoint>& T,
                                                long rel_goal_bits, long max_prec) {
  return std::move(all_piece_integrals(s, {PieceJob{T, rel_goal_bits}}, max_prec).front());
}

std::vector<std::vector<PieceIntegrals>> all_piece_integrals(const Speed& s, const std::vector<PieceJob>& jobs,
                                                             long max_prec) {
  std::vector<std::vector<PieceIntegrals>> out(jobs.size());
  // (job, piece) of every task, in job order
  std::vector<std::pair<std::size_t, std::size_t>> tasks;
  for (std::size_t k = 0; k < jobs.size(); ++k) {
    if (jobs[k].T.size() < 2) throw InvalidArgument("all_piece_integrals: needs at least two breakpoints");
    out[k].resize(jobs[k].T.size() - 1);
    for (std::size_t i = 0; i + 1 < jobs[k].T.size(); ++i) tasks.emplace_back(k, i);
  }
  if (tasks.empty()) return out;
  const std::size_t workers = std::min(worker_count(), tasks.size());
  // Refine the irrational breakpoints (and the speed's zeros, which the
  // integrands next to a zero evaluate) once, before the workers start:
  // copies share their refinement (RealAlgebraic::refine), and this keeps
  // two workers from refining one number at the same time. The enclosures
  // the integrals use depend on (t, prec) alone, not on how far t was
  // refined before (RealAlgebraic::to_ball), so nothing else changes. The
  // integrands ask for rel_goal_bits + 32 + RealAlgebraic::kToBallExtraBits
  // bits at the first attempt when no cancellation raises it (working
  // precision rel_goal_bits + 32, and to_ball's refinement).
  // The numbers are independent (each refinement is an exact root
  // refinement of its own), so they are refined on the workers too; a
  // number's copies share one locked state, so each is refined once.
  long most_bits = 0;
  std::vector<std::pair<const RealAlgebraic*, long>> to_refine;
  for (const PieceJob& j : jobs) {
    for (const Breakpoint& b : j.T)
      if (!b.t.is_rational()) to_refine.emplace_back(&b.t, j.rel_goal_bits + kFirstEndBits);
    most_bits = std::max(most_bits, j.rel_goal_bits);
  }
  if (!to_refine.empty())
    parallel_for(to_refine.size(), std::min(worker_count(), to_refine.size()),
                 [&](std::size_t, std::size_t i) { to_refine[i].first->refine(to_refine[i].second); });
  for (const SpeedZero& z : s.zeros()) z.t.refine(most_bits + kFirstEndBits);  // mostly breakpoints already
  // Extra workers' copies of the speed and the jobs (mutable caches), made
  // only when the loop is long enough to wake them.
  std::vector<Speed> speeds;
  std::vector<std::vector<PieceJob>> job_copies;
  parallel_for(
      tasks.size(), workers,
      [&](std::size_t w, std::size_t t) {
        const Speed& sw = w == 0 ? s : speeds[w - 1];
        const std::size_t k = tasks[t].first, i = tasks[t].second;
        const PieceJob& job = w == 0 ? jobs[k] : job_copies[w - 1][k];
        out[k][i] = piece_integrals(sw, job.T[i], job.T[i + 1], job.rel_goal_bits, max_prec);
      },
      [&](std::size_t k) {
        for (std::size_t w = 1; w < k; ++w) {
          speeds.push_back(s);
          job_copies.push_back(jobs);
        }
      });
  return out;
}

}  // namespace uniparam
