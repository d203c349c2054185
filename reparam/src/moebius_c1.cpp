// reparam/src/moebius_c1.cpp -- ImUp's ReparameterizationU: a C1 piecewise
// Moebius map refined until a target uniformity (MATH.md section 3).
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
#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/budget.hpp"
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
// on u, S and alpha).
Built build(const Speed& s, const UniformityResult& base, const std::vector<RealAlgebraic>& T, long digits,
            const Options& opt) {
  const std::size_t N = T.size() - 1;
  for (long bits = digits_to_bits(digits) + 8;; bits += 32) {
    check_time_budget();
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

// ---- The UNCERTIFIED floating-point draft that steers the refinement ----
// Every refinement round needs the C1 map of the current T only to choose the
// next T (and to decide when to try a certification): the same formulas as
// build() and c1_from_pieces, in IEEE double from double-precision quadrature.
// Nothing computed here is reported; reparam_c1 certifies the chosen T with
// build() and decides target.reached from that certified map only.

constexpr int kGL = 20;

struct GaussLegendre {
  std::array<double, kGL> x{}, w{};
  GaussLegendre() {
    for (int i = 0; i < kGL; ++i) {
      double z = std::cos(M_PI * (i + 0.75) / (kGL + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= kGL; ++k) {
          const double p2 = ((2.0 * k - 1) * z * p1 - (k - 1.0) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = kGL * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre g;
  return g;
}

// Over a piece [a, a + h]: int sigma^2 (1-t~)^2, 2 t~ (1-t~), t~^2 and int sigma,
// all over dt (uncertified).
struct FloatPiece {
  double A = 0, B = 0, C = 0, len = 0;
};

FloatPiece operator+(const FloatPiece& x, const FloatPiece& y) {
  return FloatPiece{x.A + y.A, x.B + y.B, x.C + y.C, x.len + y.len};
}

FloatPiece panel(const Speed& s, double a, double h, double l, double r) {
  const GaussLegendre& g = gauss_legendre();
  FloatPiece out;
  const double m = (l + r) / 2, k = (r - l) / 2;
  for (int i = 0; i < kGL; ++i) {
    const double t = m + k * g.x[i], u = (t - a) / h, s2 = detail::sigma2_double(s, t), f = s2 * g.w[i] * k;
    out.A += f * (1 - u) * (1 - u);
    out.B += f * 2 * u * (1 - u);
    out.C += f * u * u;
    out.len += std::sqrt(s2) * g.w[i] * k;
  }
  return out;
}

// Adaptive bisection until both the sigma^2 moments and the length of [l, r]
// change by at most 1e-13 of the piece's first estimates. sigma is smooth on
// [l, r] (zeros of sigma, where |g| has a kink, are panel ends).
FloatPiece adapt(const Speed& s, double a, double h, double l, double r, const FloatPiece& whole,
                 double scale2, double scale1, int depth) {
  const double m = (l + r) / 2;
  const FloatPiece left = panel(s, a, h, l, m), right = panel(s, a, h, m, r), both = left + right;
  const double d2 = std::fabs(both.A - whole.A) + std::fabs(both.B - whole.B) + std::fabs(both.C - whole.C);
  const double d1 = std::fabs(both.len - whole.len);
  if (depth >= 30 || r - l < 1e-15 || (d2 <= 1e-13 * scale2 && d1 <= 1e-13 * scale1)) return both;
  return adapt(s, a, h, l, m, left, scale2, scale1, depth + 1) + adapt(s, a, h, m, r, right, scale2, scale1, depth + 1);
}

double to_double(const RealAlgebraic& x) { return arf_get_d(arb_midref(x.to_ball(64).get()), ARF_RND_NEAR); }

// Float integrals of the pieces of T, cached per pair of breakpoints: a
// refinement round keeps most breakpoints, so most pieces are reused.
class FloatPieces {
 public:
  explicit FloatPieces(const Speed& s) : s_(s) {
    for (const auto& z : s.zeros()) zeros_.push_back(to_double(z.t));
  }
  const FloatPiece& get(double a, double b) {
    const auto key = std::make_pair(a, b);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    const double h = b - a;
    FloatPiece total;
    // split at the zeros of sigma inside (a, b): sigma = |g| ... is not smooth there
    std::vector<double> ends{a};
    for (double z : zeros_)
      if (z > a && z < b) ends.push_back(z);
    ends.push_back(b);
    FloatPiece first;
    for (std::size_t j = 0; j + 1 < ends.size(); ++j) first = first + panel(s_, a, h, ends[j], ends[j + 1]);
    const double scale2 = std::fabs(first.A) + std::fabs(first.B) + std::fabs(first.C) + 1e-300;
    const double scale1 = std::fabs(first.len) + 1e-300;
    for (std::size_t j = 0; j + 1 < ends.size(); ++j) {
      const FloatPiece w = panel(s_, a, h, ends[j], ends[j + 1]);
      total = total + adapt(s_, a, h, ends[j], ends[j + 1], w, scale2, scale1, 0);
    }
    return cache_.emplace(key, total).first->second;
  }

 private:
  const Speed& s_;
  std::vector<double> zeros_;
  std::map<std::pair<double, double>, FloatPiece> cache_;
};

// The draft C1 map of T (UNCERTIFIED, double): t, S, alpha, F and u, the same
// quantities as build() / c1_from_pieces. u is NaN if the floating point
// breaks down (then the draft counts as worst).
struct Draft {
  std::vector<double> t, S, alpha, F;
  double u = std::nan("");
};

Draft draft_c1(FloatPieces& fp, const std::vector<RealAlgebraic>& T, double mu) {
  const std::size_t N = T.size() - 1;
  Draft d;
  for (const auto& x : T) d.t.push_back(to_double(x));
  d.t.front() = 0;
  d.t.back() = 1;
  std::vector<FloatPiece> I(N);
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
// where g S D != 0. N1 and gSD have degree ~4n (plane) to ~12n (space): too
// large for cheap evaluation. Instead
//   E(t) = (sigma^2)'(t) l(t) - k2 sigma^2(t) = sigma^2 F / (g S D) = g S F / D^3
// is evaluated from the curve's components (degree n) by truncated Taylor
// series: the jets of x_i = N_i / Q_i to order 5 (N, N', N'' and N''',
// N'''', N''''' from the LocalPoly expansions of N and of its third
// derivative) give sigma^2 to order 3 (angular: sigma^2 = (A B - C^2) / A^2
// with A = |p'|^2, B = |p''|^2, C = p'.p''; parametric: sigma^2 = A), hence
// E, E' and E'' in ball arithmetic. S > 0 and D != 0 on [0, 1], so the roots of E are those of F
// and the zeros of sigma (roots of g, where E changes sign); brackets holding
// a zero of sigma are dropped. The roots are choices (the coefficients come
// from the draft's alpha), found by certified subdivision: an interval whose
// enclosure of E excludes 0 has no root, one where E' excludes 0 and E
// changes sign has exactly one, located by Newton steps safeguarded by the
// bracket. Enclosures of E and E' on an interval are mean-value forms about
// its midpoint (the direct series enclosure overestimates badly where
// A B - C^2 cancels); a budget of evaluations per piece bounds the search.
// Only intervals narrower than 2^-36 of the piece stay undecided (a double
// root or a cluster): they count as one root when E certainly changes sign
// across them. Far cheaper than the exact isolation of F per piece and round, with
// the same roots except such clusters.
class SlidesEquation {
 public:
  SlidesEquation(const Curve& c, const Speed& s) : angular_(s.kind() == SpeedKind::Angular) {
    for (const auto& x : c.components()) {
      const Poly n = x.num(), q = x.den();
      comp_.push_back(Comp{LocalPoly(n), LocalPoly(n.derivative().derivative().derivative()), LocalPoly(q),
                           LocalPoly(q.derivative().derivative().derivative())});
    }
    for (const auto& z : s.zeros()) zeros_.push_back(z.t.to_ball(kPrec));
    acb_init(z_);
    for (auto& w : w_) acb_init(w);
    for (auto* p : polys()) arb_poly_init(p);
  }
  ~SlidesEquation() {
    acb_clear(z_);
    for (auto& w : w_) acb_clear(w);
    for (auto* p : polys()) arb_poly_clear(p);
  }
  SlidesEquation(const SlidesEquation&) = delete;
  SlidesEquation& operator=(const SlidesEquation&) = delete;

  /// Midpoints of (tiny brackets of) the roots in (lo, hi), increasing, for
  /// l(t) = c1 t + c0 and k2 (exact balls); h is the piece's width.
  std::vector<Ball> roots(const Ball& lo, const Ball& hi, const Ball& c1, const Ball& c0, const Ball& k2,
                          double h) {
    c1_ = &c1;
    c0_ = &c0;
    k2_ = &k2;
    tol_ = std::ldexp(h, -36);
    evals_ = 0;
    std::vector<Ball> out;
    solve(lo, hi, 0, out);
    return out;
  }

 private:
  static constexpr long kPrec = 128;
  // Evaluations of E per piece before the search gives up (a safeguard: the
  // roots are choices, and a piece needs a few hundred at most).
  static constexpr long kMaxEvals = 20000;
  struct Comp {
    LocalPoly n, n3, q, q3;  // N, N''', Q, Q'''
  };
  std::array<arb_poly_struct*, 9> polys() { return {ns_, qs_, xs_, d1_, d2_, t_, A_, B_, C_}; }

  // The jet of p at the real ball in z_ (length 6: p^(k) / k!), into ps.
  void jet(arb_poly_t ps, const LocalPoly& p, const LocalPoly& p3) {
    p.eval(w_[0], w_[1], w_[2], z_, kPrec);
    p3.eval(w_[3], w_[4], w_[5], z_, kPrec);
    static const long fact[6] = {1, 1, 2, 6, 24, 120};
    arb_poly_fit_length(ps, 6);
    for (int k = 0; k < 6; ++k) arb_div_si(ps->coeffs + k, acb_realref(w_[k]), fact[k], kPrec);
    _arb_poly_set_length(ps, 6);
    _arb_poly_normalise(ps);
  }

  // The series of sigma^2 at the real ball x to order 3, into A_.
  void sigma2_series(const arb_t x) {
    acb_set_arb(z_, x);
    arb_poly_zero(A_);
    arb_poly_zero(B_);
    arb_poly_zero(C_);
    for (const auto& c : comp_) {
      jet(ns_, c.n, c.n3);
      jet(qs_, c.q, c.q3);
      arb_poly_div_series(xs_, ns_, qs_, 6, kPrec);
      arb_poly_derivative(d1_, xs_, kPrec);  // p' to order 4
      arb_poly_derivative(d2_, d1_, kPrec);  // p'' to order 3
      arb_poly_mullow(t_, d1_, d1_, 4, kPrec);
      arb_poly_add(A_, A_, t_, kPrec);
      arb_poly_mullow(t_, d2_, d2_, 4, kPrec);
      arb_poly_add(B_, B_, t_, kPrec);
      arb_poly_mullow(t_, d1_, d2_, 4, kPrec);
      arb_poly_add(C_, C_, t_, kPrec);
    }
    if (angular_) {
      arb_poly_mullow(t_, A_, B_, 4, kPrec);
      arb_poly_mullow(B_, C_, C_, 4, kPrec);
      arb_poly_sub(t_, t_, B_, kPrec);  // A B - C^2 = |p' x p''|^2
      arb_poly_mullow(C_, A_, A_, 4, kPrec);
      arb_poly_div_series(A_, t_, C_, 4, kPrec);
    }
  }
  // (sigma^2)^(k) from the series: k! times its coefficient k.
  Ball deriv(int k) const {
    static const long fact[4] = {1, 1, 2, 6};
    Ball b;
    arb_poly_get_coeff_arb(b.get(), A_, k);
    arb_mul_si(b.get(), b.get(), fact[k], kPrec);
    return b;
  }

  // E, and E', E'' where non-null, on the real ball x directly from the series.
  void eval_direct(Ball& e, Ball* e1, Ball* e2, const arb_t x) {
    sigma2_series(x);
    const Ball s0 = deriv(0), s1 = deriv(1);
    Ball l, t;
    arb_mul(l.get(), c1_->get(), x, kPrec);
    arb_add(l.get(), l.get(), c0_->get(), kPrec);
    // E = (sigma^2)' l - k2 sigma^2
    arb_mul(e.get(), s1.get(), l.get(), kPrec);
    arb_submul(e.get(), k2_->get(), s0.get(), kPrec);
    if (!e1 && !e2) return;
    const Ball s2 = deriv(2);
    if (e1) {
      // E' = (sigma^2)'' l + (sigma^2)' (c1 - k2)
      arb_mul(e1->get(), s2.get(), l.get(), kPrec);
      arb_sub(t.get(), c1_->get(), k2_->get(), kPrec);
      arb_addmul(e1->get(), s1.get(), t.get(), kPrec);
    }
    if (e2) {
      // E'' = (sigma^2)''' l + (sigma^2)'' (2 c1 - k2)
      const Ball s3 = deriv(3);
      arb_mul(e2->get(), s3.get(), l.get(), kPrec);
      arb_mul_2exp_si(t.get(), c1_->get(), 1);
      arb_sub(t.get(), t.get(), k2_->get(), kPrec);
      arb_addmul(e2->get(), s2.get(), t.get(), kPrec);
    }
  }
  // Enclosures of E and E' on J = [lo, hi] by mean-value forms about the
  // midpoint m (E(m) + E'(J) [-r, r] and E'(m) + E''(J) [-r, r]), intersected
  // with the direct ones: far tighter on wide intervals, where the series
  // arithmetic overestimates (A B - C^2 cancels).
  void eval_interval(Ball& e, Ball& e1, const Ball& lo, const Ball& hi) {
    Ball x, r, em, e1m, e1j, e2j, t, pm;
    arb_union(x.get(), lo.get(), hi.get(), kPrec);
    const Ball m = midpoint(lo, hi);
    arb_sub(r.get(), hi.get(), lo.get(), kPrec);
    arb_mul_2exp_si(r.get(), r.get(), -1);
    arb_zero(pm.get());
    arb_add_error(pm.get(), r.get());  // [-r, r]
    eval_direct(e, &e1j, &e2j, x.get());
    eval_direct(em, &e1m, nullptr, m.get());
    arb_mul(t.get(), e2j.get(), pm.get(), kPrec);
    arb_add(t.get(), t.get(), e1m.get(), kPrec);
    if (!arb_intersection(e1.get(), e1j.get(), t.get(), kPrec)) e1 = t;
    arb_mul(t.get(), e1.get(), pm.get(), kPrec);
    arb_add(t.get(), t.get(), em.get(), kPrec);
    const Ball ed = e;
    if (!arb_intersection(e.get(), ed.get(), t.get(), kPrec)) e = t;
  }
  // -1, 1, or 0 when the sign of E at the point x is not certain.
  int sign_at(const Ball& x) {
    Ball e;
    ++evals_;
    eval_direct(e, nullptr, nullptr, x.get());
    return arb_is_positive(e.get()) ? 1 : arb_is_negative(e.get()) ? -1 : 0;
  }
  static Ball midpoint(const Ball& lo, const Ball& hi) {
    Ball m;
    arb_add(m.get(), lo.get(), hi.get(), 4 * kPrec);
    arb_mul_2exp_si(m.get(), m.get(), -1);
    arb_get_mid_arb(m.get(), m.get());
    return m;
  }
  static double width(const Ball& lo, const Ball& hi) {
    Ball w;
    arb_sub(w.get(), hi.get(), lo.get(), 4 * kPrec);
    return arf_get_d(arb_midref(w.get()), ARF_RND_NEAR);
  }
  // A root of E located in [lo, hi] (to about tol_): kept unless a zero of
  // sigma lies within 2^10 tol_ of it (then it is that zero, a root of g).
  void found(const Ball& lo, const Ball& hi, std::vector<Ball>& out) const {
    Ball x, r;
    arb_union(x.get(), lo.get(), hi.get(), kPrec);
    arb_set_d(r.get(), std::ldexp(tol_, 10));
    arb_add_error(x.get(), r.get());
    for (const auto& z : zeros_)
      if (arb_overlaps(x.get(), z.get())) return;
    out.push_back(midpoint(lo, hi));
  }

  void solve(const Ball& lo, const Ball& hi, int depth, std::vector<Ball>& out) {
    if (evals_ > kMaxEvals) return;  // budget spent: no more choices from this piece
    evals_ += 2;
    Ball e, de;
    eval_interval(e, de, lo, hi);
    if (!arb_contains_zero(e.get())) return;  // certainly no root
    const double w = width(lo, hi);
    const bool tiny = w < tol_ || depth > 60;
    const bool monotone = !arb_contains_zero(de.get());
    if (monotone || tiny) {
      const int sl = sign_at(lo), sh = sign_at(hi);
      if (sl != 0 && sh != 0) {
        if (sl == sh) return;  // monotone, or an undecided cluster, without a sign change
        // exactly one root when monotone (at least one otherwise): Newton
        // steps safeguarded by the bracket (bisection when a step leaves it)
        Ball a = lo, b = hi, x = midpoint(lo, hi);
        for (int it = 0; it < 200 && width(a, b) > tol_; ++it) {
          Ball ex, e1x, q;
          ++evals_;
          eval_direct(ex, &e1x, nullptr, x.get());
          const int sx = arb_is_positive(ex.get()) ? 1 : arb_is_negative(ex.get()) ? -1 : 0;
          if (sx == 0) {  // E(x) ~ 0 at this precision: x is the root
            a = x;
            b = x;
            break;
          }
          (sx == sl ? a : b) = x;
          arb_div(q.get(), ex.get(), e1x.get(), kPrec);
          arb_sub(q.get(), x.get(), q.get(), kPrec);
          arb_get_mid_arb(q.get(), q.get());
          const double step = std::fabs(width(x, q));
          if (arb_is_finite(q.get()) && arb_gt(q.get(), a.get()) && arb_lt(q.get(), b.get())) {
            x = q;
            if (step < tol_) {  // converged: x is within ~tol of the root
              a = x;
              b = x;
              break;
            }
          } else {
            x = midpoint(a, b);
          }
        }
        found(a, b, out);
        return;
      }
      if (tiny) {
        found(lo, hi, out);  // E is ~0 at an end: the root is there
        return;
      }
    }
    const Ball m = midpoint(lo, hi);
    solve(lo, m, depth + 1, out);
    solve(m, hi, depth + 1, out);
  }

  bool angular_;
  std::vector<Comp> comp_;
  std::vector<Ball> zeros_;
  const Ball *c1_ = nullptr, *c0_ = nullptr, *k2_ = nullptr;
  double tol_ = 0;
  long evals_ = 0;
  acb_t z_, w_[6];
  arb_poly_t ns_, qs_, xs_, d1_, d2_, t_, A_, B_, C_;
};

// New breakpoints of the slides' refinement: on each piece of T, the roots of
// its slides' equation (SlidesEquation) at least 1/1000 of the piece away from
// its ends, rounded to short rationals (within 10^-6 of the piece's width).
std::vector<RealAlgebraic> refine(SlidesEquation& eq, const std::vector<RealAlgebraic>& T, const Draft& d) {
  std::vector<RealAlgebraic> out;
  const Rational tiny(1, 1000000000);
  for (std::size_t i = 0; i + 1 < T.size(); ++i) {
    out.push_back(T[i]);
    const Ball ab = T[i].to_ball(128), bb = T[i + 1].to_ball(128);
    const Rational a = short_rational(ab, tiny), b = short_rational(bb, tiny);
    const Rational al = rational_near(d.alpha[i], Rational(1, 1000000000000L));
    const Rational h = b - a;
    if (h.sign() <= 0) continue;
    const long p = 256;
    const Ball c1(Rational(2) * al - Rational(1), p), c0((Rational(1) - al) * b - al * a, p),
        k2(Rational(4) * (Rational(1) - Rational(2) * al), p);
    const Rational margin = h * Rational(1, 1000);
    const Ball lo(a + margin, p), hi(b - margin, p);
    Ball lom, him;
    arb_get_mid_arb(lom.get(), lo.get());
    arb_get_mid_arb(him.get(), hi.get());
    const double hd = arf_get_d(arb_midref(Ball(h, 64).get()), ARF_RND_NEAR);
    for (const auto& x : eq.roots(lom, him, c1, c0, k2, hd)) {
      const Rational q = short_rational(x, h * Rational(1, 1000000));
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
  SlidesEquation slides(c, s);

  // The rounds choose T in floating point (draft_c1, UNCERTIFIED); a T whose
  // draft meets the target is certified (build) and accepted only if the
  // certified u_after >= target. Otherwise the best draft is certified at the end.
  FloatPieces fp(s);
  const double mu_d = arf_get_d(arb_midref(base.mu.get()), ARF_RND_NEAR);
  const double target_d = arf_get_d(arb_midref(Ball(target, 128).get()), ARF_RND_NEAR);
  const Ball tq(target, 2 * digits_to_bits(opt.digits) + 64);
  std::vector<RealAlgebraic> best = T, certified_T;
  double best_u = -1;
  Built certified;
  bool have_certified = false, reached = false;
  long rounds = 0;
  for (;; ++rounds) {
    check_time_budget();
    const Draft draft = draft_c1(fp, T, mu_d);
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
    std::vector<RealAlgebraic> next = refine(slides, T, draft);
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
    }
    if (static_cast<long>(next.size()) - 1 > max_pieces) break;
    T = next;
  }
  if (!reached && !(have_certified && certified_T.size() == best.size() &&
                    std::equal(best.begin(), best.end(), certified_T.begin())))
    certified = build(s, base, best, opt.digits, opt);
  MoebiusResult r = certified.r;
  r.target.used = true;
  r.target.value = target;
  r.target.rounds = rounds;
  r.target.reached = arb_ge(r.u_after.get(), tq.get());
  return r;
}

}  // namespace uniparam
