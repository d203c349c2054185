// reparam/src/moebius_c1.cpp -- ImUp's ReparameterizationU: a C1 piecewise
// Moebius map refined until a target uniformity (docs/math.md section 3).
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "float_quadrature.hpp"
#include "moebius_detail.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/pieces.hpp"

namespace uniparam {

namespace detail {

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
// on u, S and alpha).
Built build(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T, long digits,
            const Options& opt) {
  const std::size_t N = T.size() - 1;
  // base holds mu alone (detail::mu_only): u_before comes from the pieces'
  // integrals, int sigma^2 = sum L_i / Delta t_i (the pieces have no zeros
  // at their ends: rho = Delta t), as in moebius_c0; mu is recomputed at the
  // loop's accuracy when a result made with it falls short.
  Ball mu = base.mu;
  long mu_bits = 0;
  bool raise_mu = false;
  for (long bits = digits_to_bits(digits) + 8;; bits += 32) {
    check_time_budget();
    const long prec = 2 * bits + 64;
    if (raise_mu && bits > mu_bits) {
      mu_bits = bits;
      mu = mean_speed(s, mu_bits, opt);
    }
    Built b;
    MoebiusResult& r = b.r;
    r.kind = s.kind();
    r.continuity = Continuity::C1;
    r.mu = mu;
    r.speed_vanishes = !s.zeros().empty();
    std::vector<Ball> len(N);
    Ball total(0);
    // Pieces on worker threads, each extra worker with its own copies of the
    // speed and the breakpoints (both keep mutable caches).
    r.integrals.resize(N);
    const std::size_t workers = std::min(worker_count(), N);
    std::vector<Speed> speeds;  // made only when the loop wakes the workers
    std::vector<std::vector<RealAlgebraic>> Ts;
    parallel_for(
        N, workers,
        [&](std::size_t w, std::size_t i) {
          const Speed& sw = w == 0 ? s : speeds[w - 1];
          const std::vector<RealAlgebraic>& tw = w == 0 ? T : Ts[w - 1];
          r.integrals[i] = piece_integrals(sw, Breakpoint{tw[i], 0, 0, 0}, Breakpoint{tw[i + 1], 0, 0, 0}, bits,
                                           opt.max_prec);
          len[i] = integrate_speed(sw, tw[i], tw[i + 1], bits, opt.max_prec);
        },
        [&](std::size_t k) {
          speeds.assign(k - 1, s);
          Ts.assign(k - 1, T);
        });
    for (std::size_t i = 0; i < N; ++i) {
      r.T.push_back(Breakpoint{T[i], 0, 0, 0});
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
    b.d = detail::c1_from_pieces(T, r.S, r.integrals, mu, prec);
    r.alpha = b.d.alpha;
    r.u_after = b.d.u;
    Ball mean_square(0), mu2;
    for (std::size_t i = 0; i < N; ++i) {
      const Ball part = piece_square_integral(s, r.T[i], r.T[i + 1], r.integrals[i], bits, opt.max_prec);
      arb_add(mean_square.get(), mean_square.get(), part.get(), prec);
    }
    arb_mul(mu2.get(), mu.get(), mu.get(), prec);
    arb_div(r.u_before.get(), mu2.get(), mean_square.get(), prec);
    const long d = digits + 1;
    const bool mu_ok = mu.meets_digits(d) && r.u_before.meets_digits(d) && r.u_after.meets_digits(d);
    raise_mu = !mu_ok;
    bool ok = mu_ok;
    for (const auto& x : r.S) ok = ok && x.meets_digits(d);
    for (const auto& x : r.alpha) ok = ok && x.meets_digits(d);
    if (ok) return b;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the C1 piecewise Moebius reparameterization to " +
                           std::to_string(digits) + " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

// ---- The UNCERTIFIED floating-point draft that steers the refinement ----
// Every refinement round needs the C1 map of the current T only to choose the
// next T (and to decide when to try a certification): the same formulas as
// build() and c1_from_pieces, in IEEE double from double-precision quadrature.
// Nothing computed here is reported; reparam_c1 certifies the chosen T with
// build() and decides target->reached from that certified map only.

// The draft C1 map of T (UNCERTIFIED, double): t, S, alpha, F and u, the same
// quantities as build() / c1_from_pieces. u is NaN if the floating point
// breaks down (then the draft counts as worst).
struct Draft {
  std::vector<double> t, S, alpha, F;
  double u = std::nan("");
};

Draft draft_c1(detail::FloatPieces& fp, const std::vector<RealAlgebraic>& T, double mu) {
  const std::size_t N = T.size() - 1;
  Draft d;
  for (const auto& x : T) d.t.push_back(detail::midpoint_double(x));
  d.t.front() = 0;
  d.t.back() = 1;
  std::vector<detail::FloatPiece> I(N);
  double total = 0;
  for (std::size_t i = 0; i < N; ++i) {
    I[i] = fp.get(d.t[i], d.t[i + 1]);
    const double h = d.t[i + 1] - d.t[i];
    I[i].A *= h;  // the PieceIntegrals convention: dt_i times the integrals over dt
    I[i].B *= h;
    I[i].C *= h;
    total += I[i].len;
  }
  d.S.assign(1, 0.0);
  double acc = 0;
  for (std::size_t i = 0; i + 1 < N; ++i) {
    acc += I[i].len;
    d.S.push_back(acc / total);
  }
  d.S.push_back(1.0);
  std::vector<double> rho(N), w(N), cc(N);
  for (std::size_t i = 0; i < N; ++i) {
    const double ds = d.S[i + 1] - d.S[i];
    rho[i] = (d.t[i + 1] - d.t[i]) / ds;
    w[i] = 1 / ds;
  }
  cc[0] = 1;
  for (std::size_t i = 0; i + 1 < N; ++i) cc[i + 1] = rho[i] / (rho[i + 1] * cc[i]);
  double P = 0, Q = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double ca = i % 2 == 0 ? cc[i] * I[i].A : I[i].C / cc[i];
    const double cq = i % 2 == 0 ? I[i].C / cc[i] : cc[i] * I[i].A;
    P += w[i] * ca;
    Q += w[i] * cq;
  }
  const double x = std::sqrt(Q / P);
  double sumF = 0;
  for (std::size_t i = 0; i < N; ++i) {
    const double k = i % 2 == 0 ? cc[i] * x : cc[i] / x;
    d.alpha.push_back(1 / (k + 1));
    d.F.push_back((k * I[i].A + I[i].B + I[i].C / k) * w[i]);
    sumF += d.F.back();
  }
  d.u = mu * mu / sumF;
  return d;
}

// A short rational within w of the double x.
Rational rational_near(double x, const Rational& w) {
  Ball b;
  arb_set_d(b.get(), x);
  const Rational m = mid_rational(b);
  return Rational::simplest_between(m - w, m + w);
}

// A short rational in the ball x +- w (x a ball, w > 0 a rational width).
Rational short_rational(const Ball& x, const Rational& w) {
  const Rational m = mid_rational(x);
  return Rational::simplest_between(m - w, m + w);
}

// The slides' equation of one piece,
//   F(t) = N1(t) l(t) - k2 gSD(t),  l(t) = c1 t + c0,
// with sigma'/sigma = N1 / (2 g S D), l(t) = dt [alpha t~ + (1-alpha)(1-t~)]
// = (2 alpha - 1) t + (1 - alpha) b - alpha a and k2 = 4 (1 - 2 alpha):
// F = 0 iff sigma' dt [alpha t~ + (1 - alpha)(1 - t~)] - 2 sigma (1 - 2 alpha) = 0
// where g S D != 0. Its roots are choices (the coefficients come from the
// draft's alpha), so they are searched in floating point. N1 and gSD have
// degree ~4n (plane) to ~12n (space), too large for cheap evaluation (their
// exact isolation per piece and round, or even their local expansions, cost
// seconds); instead
//   E(t) = (sigma^2)'(t) l(t) - k2 sigma^2(t) = sigma^2 F / (g S D) = g S F / D^3
// is evaluated from the components of the speed's evaluation curve
// (speed.hpp: the curve itself, or for the angular speed of a curve whose p'
// has a common factor the polynomial curve along p' with it cancelled, so
// A = |p'|^2 below does not vanish at a cusp) by truncated Taylor
// series: the jets of x_i = N_i / Q_i to order 5 (N, N', N'' and N''',
// N'''', N''''' from the LocalPoly expansions of N and of its third
// derivative, in double) give sigma^2 to order 3 (angular: sigma^2 =
// (A B - C^2) / A^2 with A = |p'|^2, B = |p''|^2, C = p'.p''; parametric:
// sigma^2 = A), hence E and E'. S > 0 and D != 0 on [0, 1], so the roots of
// E are those of F and the zeros of sigma (roots of g, where E changes sign);
// roots at a zero of sigma are dropped.
class SlidesEquation {
 public:
  // The speed's own expansions of the components: their cells are mostly
  // built by the quadratures already (same working precision).
  explicit SlidesEquation(const Speed& s) : angular_(s.kind() == SpeedKind::Angular) {
    for (std::size_t i = 0; i < s.component_count(); ++i)
      comp_.push_back(Comp{s.component_numerator(i), s.component_denominator(i)});
    for (const auto& z : s.zeros()) zeros_d_.push_back(arf_get_d(arb_midref(z.t.to_ball(64).get()), ARF_RND_NEAR));
  }

  /// UNCERTIFIED floating-point search (a choice only): the roots of E in
  /// (lo, hi) from a scan of kScan equally spaced points, each sign change
  /// refined by safeguarded Newton steps in double; roots at a zero of sigma
  /// dropped. Two roots closer than the scan's spacing may be missed.
  std::vector<double> roots_double(double lo, double hi, double c1, double c0, double k2) const {
    std::vector<double> out;
    const double step = (hi - lo) / kScan, tol = (hi - lo) * 1e-13;
    double xa = lo, ea = e_double(lo, c1, c0, k2, nullptr);
    for (int i = 1; i <= kScan; ++i) {
      const double xb = i == kScan ? hi : lo + step * i, eb = e_double(xb, c1, c0, k2, nullptr);
      if (std::isfinite(ea) && std::isfinite(eb) && ((ea < 0 && eb > 0) || (ea > 0 && eb < 0))) {
        double a = xa, b = xb, x = (a + b) / 2;
        const bool neg_a = ea < 0;
        for (int it = 0; it < 100 && b - a > tol; ++it) {
          double d1 = 0;
          const double ex = e_double(x, c1, c0, k2, &d1);
          if (ex == 0 || !std::isfinite(ex)) break;
          ((ex < 0) == neg_a ? a : b) = x;
          const double nx = x - ex / d1;
          if (std::isfinite(nx) && nx > a && nx < b) {
            const bool done = std::fabs(nx - x) < tol;
            x = nx;
            if (done) break;
          } else {
            x = (a + b) / 2;
          }
        }
        bool at_zero = false;
        for (double z : zeros_d_) at_zero = at_zero || std::fabs(x - z) <= (hi - lo) * 1e-9;
        if (!at_zero) out.push_back(x);
      } else if (ea == 0 && i > 1) {
        out.push_back(xa);
      }
      xa = xb;
      ea = eb;
    }
    return out;
  }

 private:
  static constexpr int kScan = 64;
  // E(t) (and E'(t) into d1 if non-null) in IEEE double from the jets of the
  // components (LocalPoly::eval_double_taylor): UNCERTIFIED.
  double e_double(double t, double c1, double c0, double k2, double* d1) const {
    double A[4] = {0, 0, 0, 0}, B[4] = {0, 0, 0, 0}, C[4] = {0, 0, 0, 0};
    for (const auto& c : comp_) {
      double n[6], q[6], x[6], p1[5], p2[4];
      c.n.eval_double_taylor(t, 5, n);  // Taylor coefficients at t
      c.q.eval_double_taylor(t, 5, q);
      for (int k = 0; k < 6; ++k) {  // x = n / q as series
        double v = n[k];
        for (int j = 1; j <= k; ++j) v -= q[j] * x[k - j];
        x[k] = v / q[0];
      }
      for (int k = 0; k < 5; ++k) p1[k] = (k + 1) * x[k + 1];
      for (int k = 0; k < 4; ++k) p2[k] = (k + 1) * p1[k + 1];
      for (int k = 0; k < 4; ++k)
        for (int j = 0; j <= k; ++j) {
          A[k] += p1[j] * p1[k - j];
          B[k] += p2[j] * p2[k - j];
          C[k] += p1[j] * p2[k - j];
        }
    }
    double s[4];
    if (angular_) {
      double num[4], den[4];
      for (int k = 0; k < 4; ++k) {
        num[k] = den[k] = 0;
        for (int j = 0; j <= k; ++j) {
          num[k] += A[j] * B[k - j] - C[j] * C[k - j];
          den[k] += A[j] * A[k - j];
        }
      }
      for (int k = 0; k < 4; ++k) {
        double v = num[k];
        for (int j = 1; j <= k; ++j) v -= den[j] * s[k - j];
        s[k] = v / den[0];
      }
    } else {
      for (int k = 0; k < 4; ++k) s[k] = A[k];
    }
    // sigma^2 = s0, (sigma^2)' = s1, (sigma^2)'' = 2 s2
    const double l = c1 * t + c0;
    if (d1) *d1 = 2 * s[2] * l + s[1] * (c1 - k2);
    return s[1] * l - k2 * s[0];
  }

  struct Comp {
    LocalPoly n, q;  // numerator and denominator
  };
  bool angular_;
  std::vector<Comp> comp_;
  std::vector<double> zeros_d_;
};

// New breakpoints of the slides' refinement: on each piece of T, the roots of
// its slides' equation (SlidesEquation, found in floating point: UNCERTIFIED
// choices, certified later as part of the map) at least 1/1000 of the piece away from
// its ends, rounded to short rationals (within 10^-6 of the piece's width). The
// equation is that of the piece's ends rounded within 10^-12 of its width and of
// the draft's alpha rounded within 10^-12, so each breakpoint is within about
// 10^-6 of the width of a sign change of the piece's exact slides' equation
// with that alpha (checked by tests/reparam/test_reparam_c1_slides.cpp).
// Each added breakpoint is recorded in *added (if non-null; round left 0).
std::vector<RealAlgebraic> refine(SlidesEquation& eq, const std::vector<RealAlgebraic>& T, const Draft& d,
                                  std::vector<detail::C1Trace::SlidesBreakpoint>* added) {
  std::vector<RealAlgebraic> out;
  for (std::size_t i = 0; i + 1 < T.size(); ++i) {
    out.push_back(T[i]);
    const Ball ab = T[i].to_ball(128), bb = T[i + 1].to_ball(128);
    // The ends within 10^-12 of the piece's width: an absolute rounding (say
    // 10^-9) moves the roots by more than the 10^-6 width rounding below
    // on pieces narrower than ~10^-2 (tests/reparam/test_reparam_c1_slides.cpp).
    Ball hb;
    arb_sub(hb.get(), bb.get(), ab.get(), 128);
    const Rational tiny = mid_rational(hb) * Rational(1, 1000000000000L);
    const Rational a = short_rational(ab, tiny), b = short_rational(bb, tiny);
    const Rational al = rational_near(d.alpha[i], Rational(1, 1000000000000L));
    const Rational h = b - a;
    if (h.sign() <= 0) continue;
    const long p = 256;
    const Ball c1(Rational(2) * al - Rational(1), p), c0((Rational(1) - al) * b - al * a, p),
        k2(Rational(4) * (Rational(1) - Rational(2) * al), p);
    const Rational margin = h * Rational(1, 1000);
    const Ball lo(a + margin, p), hi(b - margin, p);
    auto dbl = [](const Ball& x) { return arf_get_d(arb_midref(x.get()), ARF_RND_NEAR); };
    for (const double r : eq.roots_double(dbl(lo), dbl(hi), dbl(c1), dbl(c0), dbl(k2))) {
      Ball x;
      arb_set_d(x.get(), r);
      const Rational q = short_rational(x, h * Rational(1, 1000000));
      if (q > a + margin && q < b - margin && (out.empty() || compare(out.back(), RealAlgebraic(q)) < 0)) {
        out.emplace_back(q);
        if (added) added->push_back(detail::C1Trace::SlidesBreakpoint{0, i, T[i], T[i + 1], al, q});
      }
    }
  }
  out.push_back(T.back());
  return out;
}

}  // namespace

MoebiusResult reparam_c1(const Curve& c, SpeedKind kind, const Rational& target, const Options& opt,
                         long max_pieces) {
  return detail::reparam_c1_traced(c, kind, target, opt, max_pieces, nullptr);
}

namespace {

// reparam_c1_traced for the speed s (the arguments checked).
MoebiusResult reparam_c1_on(const Speed& s, const Rational& target, const Options& opt, long max_pieces,
                            detail::C1Trace* trace) {
  using detail::C1Trace;
  // mu (its own parallel loop) and the critical points (the root isolation
  // of a polynomial of degree ~11d, in two halves) side by side, as in
  // radical(): the second on its own copy of the speed.
  UniformityResult base;
  std::vector<RealAlgebraic> critical;
  {
    const Speed s_copy = s;
    parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t i) {
      if (i == 0) base = detail::mu_only(s, opt);  // u_before: from the pieces (build)
      else critical = critical_points(s_copy);
    });
  }
  if (s.identically_zero()) {
    MoebiusResult r = detail::moebius_c0(s, base, {RealAlgebraic(0), RealAlgebraic(1)}, opt);
    r.continuity = Continuity::C1;
    r.target = MoebiusResult::Target{target, true, 0};
    return r;
  }
  // T: 0, the zeros of sigma' in (0, 1), 1.
  std::vector<RealAlgebraic> T{RealAlgebraic(0)};
  for (auto& t : critical)
    if (!(t.is_rational() && (t.rational().is_zero() || t.rational() == Rational(1)))) T.push_back(std::move(t));
  T.emplace_back(RealAlgebraic(1));
  SlidesEquation slides(s);

  // The rounds choose T in floating point (draft_c1, UNCERTIFIED); a T whose
  // draft meets the target is certified (build) and accepted only if the
  // certified u_after >= target. Otherwise the best draft is certified at the end.
  // The draft integrates sigma 2^-e, with 2^e near mu where mu is beyond
  // 2^+-256 (a huge coefficient: sigma^2 would leave double's range), so
  // that its quantities, all relative, stay representable.
  long e = 0;
  if (arb_is_finite(base.mu.get()) && !arf_is_zero(arb_midref(base.mu.get()))) {
    const long m = arf_abs_bound_lt_2exp_si(arb_midref(base.mu.get()));
    if (m > 256 || m < -256) e = m;
  }
  detail::FloatPieces fp(s, e);
  Ball mu_scaled;
  arb_mul_2exp_si(mu_scaled.get(), base.mu.get(), -e);
  const double mu_d = arf_get_d(arb_midref(mu_scaled.get()), ARF_RND_NEAR);
  const double target_d = arf_get_d(arb_midref(Ball(target, 128).get()), ARF_RND_NEAR);
  const Ball tq(target, 2 * digits_to_bits(opt.digits) + 64);
  std::vector<RealAlgebraic> best = T, certified_T;
  double best_u = -1;
  Built certified;
  bool have_certified = false, reached = false, draft_failed = false;
  long rounds = 0;
  for (;; ++rounds) {
    check_time_budget();
    const Draft draft = draft_c1(fp, T, mu_d);
    if (trace) trace->rounds.push_back(C1Trace::Round{T, draft.alpha});
    const double u = draft.u;
    if (u > best_u) {
      best_u = u;
      best = T;
    }
    if (u >= target_d) {
      certified = build(s, base, T, opt.digits, opt);
      certified_T = T;
      have_certified = true;
      if (arb_ge(certified.r.u_after.get(), tq.get())) {
        reached = true;
        break;
      }
      // the floating point was optimistic: refine on
    }
    if (static_cast<long>(T.size()) - 1 >= max_pieces) break;
    // A draft whose floating point broke down (integrals beyond double's
    // range: a huge coefficient) cannot steer the refinement: the best T so
    // far is certified below, and target->reached says whether it is enough.
    if (!std::isfinite(u)) {
      draft_failed = true;
      break;
    }
    std::vector<C1Trace::SlidesBreakpoint> added;
    std::vector<RealAlgebraic> next = refine(slides, T, draft, trace ? &added : nullptr);
    if (next.size() == T.size()) {
      // The slides' rule added nothing: split the piece with the largest
      // excess F_i - mu^2 Delta s_i (its share of int sigma_{p o m}^2 above the
      // ideal) at its midpoint.
      std::size_t worst = 0;
      double wv = -1;
      for (std::size_t i = 0; i + 1 < T.size(); ++i) {
        const double e = draft.F[i] - mu_d * mu_d * (draft.S[i + 1] - draft.S[i]);
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
      if (trace) trace->bisections.push_back(q);
    }
    if (static_cast<long>(next.size()) - 1 > max_pieces) break;
    if (trace)
      for (auto& x : added) {
        x.round = static_cast<std::size_t>(rounds);
        trace->slides.push_back(x);
      }
    T = next;
  }
  if (!reached && !(have_certified && certified_T.size() == best.size() &&
                    std::equal(best.begin(), best.end(), certified_T.begin())))
    certified = build(s, base, best, opt.digits, opt);
  MoebiusResult r = certified.r;
  r.target.emplace();
  r.target->value = target;
  r.target->rounds = rounds;
  r.target->draft_failed = draft_failed;
  r.target->reached = arb_ge(r.u_after.get(), tq.get());
  return r;
}

}  // namespace

MoebiusResult detail::reparam_c1_traced(const Curve& c, SpeedKind kind, const Rational& target,
                                        const Options& opt, long max_pieces, C1Trace* trace) {
  if (trace) *trace = C1Trace{};
  if (!(target.sign() > 0 && target < Rational(1)))
    throw InvalidArgument("the target uniformity must lie in (0, 1), got " + target.str());
  if (max_pieces < 1 || max_pieces > 1000)
    throw InvalidArgument("the piece budget must be in [1, 1000], got " + std::to_string(max_pieces));
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  if (const auto bal = balanced_for(c, s)) {
    const Speed sq(bal->q, kind);
    const MoebiusResult rq = reparam_c1_on(sq, target, opt, max_pieces, trace);
    MoebiusResult r = compose_balanced(bal, rq, uniformity_balanced(s, *bal, sq, opt).u, opt.digits);
    const Ball tq(target, 2 * digits_to_bits(opt.digits) + 64);
    r.target->reached = arb_ge(r.u_after.get(), tq.get());
    return r;
  }
  return reparam_c1_on(s, target, opt, max_pieces, trace);
}

}  // namespace uniparam
