#include "arc_model.hpp"

#include <arb.h>
#include <mag.h>

#include <algorithm>
#include <cmath>

namespace uniparam {

namespace {

// Upper bound of sum_{j >= from} |p_j| r^j.
void abs_sum(mag_t out, const arb_poly_t p, const mag_t r, slong from) {
  mag_t t, rp;
  mag_init(t);
  mag_init(rp);
  mag_zero(out);
  mag_one(rp);
  for (slong j = 0; j < arb_poly_length(p); ++j) {
    if (j >= from) {
      arb_get_mag(t, p->coeffs + j);
      mag_mul(t, t, rp);
      mag_add(out, out, t);
    }
    mag_mul(rp, rp, r);
  }
  mag_clear(t);
  mag_clear(rp);
}

// q as a ball at prec (exact when q is dyadic and fits).
Ball ball_of(const Rational& q, long prec) { return Ball(q, prec); }

// The dyadic number with about 64 significant bits nearest to q.
Rational dyadic_near(const Rational& q) {
  arb_t x;
  arb_init(x);
  arb_set_fmpq(x, q.get(), 80);
  arf_t m;
  arf_init(m);
  arf_set_round(m, arb_midref(x), 64, ARF_RND_NEAR);
  fmpq_t f;
  fmpq_init(f);
  arf_get_fmpq(f, m);
  Rational r(f);
  fmpq_clear(f);
  arf_clear(m);
  arb_clear(x);
  return r;
}

double mid_d(const arb_t x) { return arf_get_d(arb_midref(x), ARF_RND_NEAR); }

bool to_dd(std::vector<DDBall>& out, const arb_poly_t p) {
  out.assign(static_cast<std::size_t>(std::max<slong>(arb_poly_length(p), 1)), DDBall{});
  for (slong j = 0; j < arb_poly_length(p); ++j)
    if (!dd_set_arb(out[static_cast<std::size_t>(j)], p->coeffs + j)) return false;
  return true;
}


}  // namespace

ArcCell::ArcCell() {
  arb_poly_init(T);
  arb_poly_init(P);
}

ArcCell::~ArcCell() {
  arb_poly_clear(T);
  arb_poly_clear(P);
}

ArcCell::ArcCell(const ArcCell& o)
    : a(o.a), b(o.b), c(o.c), xa(o.xa), xb(o.xb), e(o.e), integral(o.integral), Td(o.Td), Pd(o.Pd),
      Pxa(o.Pxa), Pdd(o.Pdd), L(o.L), Terr(o.Terr), use_dd(o.use_dd), wp(o.wp) {
  arb_poly_init(T);
  arb_poly_init(P);
  arb_poly_set(T, o.T);
  arb_poly_set(P, o.P);
}

ArcCell& ArcCell::operator=(const ArcCell& o) {
  if (this == &o) return *this;
  a = o.a;
  b = o.b;
  c = o.c;
  xa = o.xa;
  xb = o.xb;
  e = o.e;
  integral = o.integral;
  Td = o.Td;
  Pd = o.Pd;
  Pxa = o.Pxa;
  Terr = o.Terr;
  use_dd = o.use_dd;
  wp = o.wp;
  Pdd = o.Pdd;
  L = o.L;
  arb_poly_set(T, o.T);
  arb_poly_set(P, o.P);
  return *this;
}

Ball ArcCell::from_a(const Ball& x, long prec) const {
  Ball v, d, err;
  arb_poly_evaluate(v.get(), P, x.get(), prec);
  arb_sub(v.get(), v.get(), Pxa.get(), prec);
  // |int_xa^x (sigma - T_N)| <= |x - xa| e
  arb_sub(d.get(), x.get(), xa.get(), prec);
  arb_abs(d.get(), d.get());
  arb_mul(err.get(), d.get(), e.get(), prec);
  mag_t m;
  mag_init(m);
  arb_get_mag(m, err.get());
  arb_add_error_mag(v.get(), m);
  mag_clear(m);
  return v;
}

namespace {

DDBall horner_dd(const std::vector<DDBall>& p, double x) {
  const DDBall xd = dd_from_double(x);
  DDBall v = p.back();
  for (std::size_t j = p.size() - 1; j-- > 0;) v = dd_add(dd_mul(v, xd), p[j]);
  return v;
}

double horner(const std::vector<double>& p, double x) {
  double v = 0;
  for (std::size_t j = p.size(); j-- > 0;) v = v * x + p[j];
  return v;
}

// An upper bound of the exact value whose rounding to nearest is x >= 0
// (normal or zero): x (1 + 2^-52) >= x + ulp(x), rounded up past it.
double up(double x) { return x * (1 + 0x1p-52) + 0x1p-1000; }

}  // namespace

bool ArcCell::at_double(double x, Ball& from_a_x, double& s, double& r) const {
  const long prec = wp;
  if (use_dd) {
    const DDBall p = horner_dd(Pdd, x);
    if (!dd_is_finite(p)) return false;
    dd_get_arb(from_a_x.get(), p);
  } else {
    Ball xb;
    arb_set_d(xb.get(), x);
    arb_poly_evaluate(from_a_x.get(), P, xb.get(), std::max(prec, 128L));
  }
  arb_sub(from_a_x.get(), from_a_x.get(), Pxa.get(), std::max(prec, 128L));
  Ball d;
  arb_set_d(d.get(), x);
  arb_sub(d.get(), d.get(), xa.get(), 128);
  arb_abs(d.get(), d.get());
  arb_mul(d.get(), d.get(), e.get(), 64);
  mag_t m;
  mag_init(m);
  arb_get_mag(m, d.get());
  arb_add_error_mag(from_a_x.get(), m);
  arb_get_mag(m, e.get());
  s = horner(Td, x);
  r = up(up(Terr + mag_get_d(m)));
  mag_clear(m);
  return std::isfinite(s) && std::isfinite(r);
}

namespace {

Poly times(const Poly& a, long k) { return a * Poly(k); }

}  // namespace

ArcModeller::ArcModeller(const Speed& s) : s_(s) {
  arb_poly_init(g_);
  arb_poly_init(Q_);
  arb_poly_init(D_);
  arb_poly_init(A_);
  arb_poly_init(B_);
  long kdeg = 0;
  for (const Poly& k : s.cofactors()) kdeg = std::max(kdeg, k.degree());
  const Poly& D = s.denominator();
  too_large_ = 2 * kdeg + std::max(0L, D.degree()) > kMaxDegreeA;
  if (too_large_) return;
  Poly q(0);
  for (const Poly& k : s.cofactors()) q = q + k * k;
  const Poly A = times(q * D, 2), B = q.derivative() * D - times(q * D.derivative(), 2);
  // Integer coefficients: exact at any precision that holds them.
  const long maxbits = std::max({s.g().max_bits(), q.max_bits(), D.max_bits(), A.max_bits(), B.max_bits()});
  const long prec = 64 + maxbits;
  // Shifted to a centre c (64 bits), the coefficients may cancel by up to
  // their size and c's powers: shifts at that much more than wp.
  extra_bits_ = maxbits + 64 + 2 * std::max({s.g().degree(), A.degree(), B.degree(), 1L});
  arb_poly_set_fmpz_poly(g_, s.g().get(), prec);
  arb_poly_set_fmpz_poly(Q_, q.get(), prec);
  arb_poly_set_fmpz_poly(D_, D.get(), prec);
  arb_poly_set_fmpz_poly(A_, A.get(), prec);
  arb_poly_set_fmpz_poly(B_, B.get(), prec);
}

ArcModeller::~ArcModeller() {
  arb_poly_clear(g_);
  arb_poly_clear(Q_);
  arb_poly_clear(D_);
  arb_poly_clear(A_);
  arb_poly_clear(B_);
}

bool ArcModeller::build(const Rational& a, const Rational& b, long bits, ArcCell& out) const {
  if (!(a < b)) return false;
  if (too_large_) return false;
  const long wp = bits + 40, sp = wp + extra_bits_;
  const Rational c = dyadic_near((a + b) / Rational(2));
  if (!(a < c && c < b)) return false;
  const Ball cb = ball_of(c, wp);
  if (!cb.is_exact()) return false;
  Ball xa, xb;
  {
    const Ball ab = ball_of(a, wp), bb = ball_of(b, wp);
    arb_sub(xa.get(), ab.get(), cb.get(), wp);
    arb_sub(xb.get(), bb.get(), cb.get(), wp);
  }
  // h >= |x| on the interval
  mag_t h;
  mag_init(h);
  {
    mag_t t;
    mag_init(t);
    arb_get_mag(h, xa.get());
    arb_get_mag(t, xb.get());
    mag_max(h, h, t);
    mag_clear(t);
  }
  arb_poly_t gs, Qs, Ds;
  arb_poly_init(gs);
  arb_poly_init(Qs);
  arb_poly_init(Ds);
  arb_poly_taylor_shift(gs, g_, cb.get(), sp);
  arb_poly_taylor_shift(Qs, Q_, cb.get(), sp);
  arb_poly_taylor_shift(Ds, D_, cb.get(), sp);
  bool ok = false;
  Ball g0, Q0, D0, sig0;
  arb_poly_get_coeff_arb(g0.get(), gs, 0);
  arb_poly_get_coeff_arb(Q0.get(), Qs, 0);
  arb_poly_get_coeff_arb(D0.get(), Ds, 0);
  int sign = 0;
  if (arb_is_positive(Q0.get()) && arb_is_nonzero(g0.get()) && arb_is_nonzero(D0.get())) {
    sign = (arb_is_positive(g0.get()) ? 1 : -1) * (arb_is_positive(D0.get()) ? 1 : -1);
    arb_sqrt(sig0.get(), Q0.get(), wp);
    arb_mul(sig0.get(), sig0.get(), g0.get(), wp);
    arb_div(sig0.get(), sig0.get(), D0.get(), wp);
    arb_abs(sig0.get(), sig0.get());
  }
  // The disc radius rho = lambda h with the smallest degree N: on the disc,
  // Re Q(c + z) >= Q0 - sum_{j>=1} |Q_j| rho^j > 0 (the principal square
  // root is holomorphic), |D| >= |D0| - sum_{j>=1} |D_j| rho^j > 0, and
  // |f| <= M = (sum |g_j| rho^j) sqrt(sum |Q_j| rho^j) / that lower bound.
  long best_n = -1;
  double best_lambda = 0;
  mag_t bestM;
  mag_init(bestM);
  if (sign != 0) {
    const double goal_log2 = std::log2(mid_d(sig0.get())) - static_cast<double>(bits + 4);
    static const double lambdas[] = {16, 8, 5, 3.5, 2.5, 1.75, 1.375};
    mag_t rho, gU, Qr, Dr, Q0l, D0l, M, t;
    mag_init(rho);
    mag_init(gU);
    mag_init(Qr);
    mag_init(Dr);
    mag_init(Q0l);
    mag_init(D0l);
    mag_init(M);
    mag_init(t);
    arb_get_mag_lower(Q0l, Q0.get());
    arb_get_mag_lower(D0l, D0.get());
    for (double lambda : lambdas) {
      mag_set_d(t, lambda);
      mag_mul(rho, h, t);
      abs_sum(Qr, Qs, rho, 1);
      abs_sum(Dr, Ds, rho, 1);
      if (mag_cmp(Qr, Q0l) >= 0 || mag_cmp(Dr, D0l) >= 0) continue;
      abs_sum(gU, gs, rho, 0);
      {  // |Q| <= |Q0| + sum_{j>=1} |Q_j| rho^j
        mag_t q0u;
        mag_init(q0u);
        arb_get_mag(q0u, Q0.get());
        mag_add(t, q0u, Qr);
        mag_clear(q0u);
      }
      mag_sqrt(t, t);
      mag_mul(M, gU, t);
      mag_sub_lower(t, D0l, Dr);
      mag_div(M, M, t);
      const double Md = mag_get_d(M);
      if (!std::isfinite(Md) || Md <= 0) continue;
      // M lambda^-(N+1) / (1 - 1/lambda) <= 2^goal_log2
      const double need = (std::log2(Md) - std::log2(1 - 1 / lambda) - goal_log2) / std::log2(lambda);
      const long n = std::max(0L, static_cast<long>(std::ceil(need)) - 1);
      if (best_n < 0 || n < best_n) {
        best_n = n;
        best_lambda = lambda;
        mag_set(bestM, M);
      }
    }
    mag_clear(rho);
    mag_clear(gU);
    mag_clear(Qr);
    mag_clear(Dr);
    mag_clear(Q0l);
    mag_clear(D0l);
    mag_clear(M);
    mag_clear(t);
  }
  if (best_n >= 0 && best_n <= max_degree) {
    const slong len = best_n + 1;
    // h = sqrt(Q) / D from A h' = B h: the coefficient of x^n gives
    //   a_0 (n + 1) h_{n+1} = sum_i b_i h_{n-i} - sum_{i>=1} a_i (n + 1 - i) h_{n+1-i}
    // (A and B shifted to c; a_0 = 2 Q0 D0 != 0). Then T = s g h.
    // In double-word balls where their ~100 bits suffice and the ends are
    // doubles (xa and xb exact in double), else in Arb's balls at wp.
    const double xad = arf_get_d(arb_midref(xa.get()), ARF_RND_NEAR);
    const double xbd = arf_get_d(arb_midref(xb.get()), ARF_RND_NEAR);
    out.use_dd = bits <= ArcCell::kDDBits && arb_is_exact(xa.get()) && arb_is_exact(xb.get()) &&
                 arf_equal_d(arb_midref(xa.get()), xad) && arf_equal_d(arb_midref(xb.get()), xbd);
    out.wp = wp;
    arb_poly_t As, Bs;
    arb_poly_init(As);
    arb_poly_init(Bs);
    arb_poly_taylor_shift(As, A_, cb.get(), sp);
    arb_poly_taylor_shift(Bs, B_, cb.get(), sp);
    Ball h0;
    arb_sqrt(h0.get(), Q0.get(), wp);
    arb_div(h0.get(), h0.get(), D0.get(), wp);
    std::vector<DDBall> Tv;  // T's coefficients (exactly T's in the double-word path; containing them else)
    ok = true;
    if (out.use_dd) {
      std::vector<DDBall> a, bb, g, h(static_cast<std::size_t>(len)), kh(static_cast<std::size_t>(len));
      ok = to_dd(a, As) && to_dd(bb, Bs) && to_dd(g, gs) && dd_set_arb(h[0], h0.get());
      DDBall inv;
      ok = ok && dd_div(inv, dd_from_double(1), a[0]);
      const std::size_t la = static_cast<std::size_t>(arb_poly_length(As)),
                        lb = static_cast<std::size_t>(arb_poly_length(Bs));
      for (std::size_t n = 0; ok && n + 1 < static_cast<std::size_t>(len); ++n) {
        DDBall acc{};
        for (std::size_t i = 0; i < lb && i <= n; ++i) acc = dd_add(acc, dd_mul(bb[i], h[n - i]));
        for (std::size_t i = 1; i < la && i <= n + 1; ++i) acc = dd_sub(acc, dd_mul(a[i], kh[n + 1 - i]));
        DDBall q;
        ok = dd_div(q, dd_mul(acc, inv), dd_from_double(static_cast<double>(n + 1)));
        h[n + 1] = q;
        kh[n + 1] = dd_mul(q, dd_from_double(static_cast<double>(n + 1)));
      }
      const std::size_t lg = static_cast<std::size_t>(arb_poly_length(gs));
      Tv.assign(static_cast<std::size_t>(len), DDBall{});
      for (std::size_t n = 0; ok && n < Tv.size(); ++n) {
        DDBall acc{};
        for (std::size_t i = 0; i < lg && i <= n; ++i) acc = dd_add(acc, dd_mul(g[i], h[n - i]));
        Tv[n] = sign < 0 ? dd_neg(acc) : acc;
      }
      out.Pdd.assign(Tv.size() + 1, DDBall{});
      for (std::size_t j = 0; ok && j < Tv.size(); ++j)
        ok = dd_div(out.Pdd[j + 1], Tv[j], dd_from_double(static_cast<double>(j + 1)));
      for (const DDBall& v : Tv) ok = ok && dd_is_finite(v);
      arb_poly_zero(out.T);
      arb_poly_zero(out.P);
    } else {
      arb_poly_t hs;
      arb_poly_init(hs);
      arb_poly_fit_length(hs, len);
      // kh[k] = k h_k, so that both sums are dot products
      arb_ptr hc = hs->coeffs;
      arb_ptr kh = _arb_vec_init(len);
      arb_set(hc, h0.get());
      const slong la = arb_poly_length(As), lb = arb_poly_length(Bs);
      arb_t acc, inv, b_sum;
      arb_init(acc);
      arb_init(inv);
      arb_init(b_sum);
      arb_inv(inv, As->coeffs, wp);
      for (slong n = 0; n + 1 < len; ++n) {
        const slong nb = std::min(lb, n + 1), na = std::min(la, n + 2);
        // sum_{i < nb} b_i h_{n-i}
        arb_dot(b_sum, nullptr, 0, Bs->coeffs, 1, hc + n, -1, nb, wp);
        // - sum_{1 <= i < na} a_i (n + 1 - i) h_{n+1-i}
        if (na > 1) arb_dot(acc, b_sum, 1, As->coeffs + 1, 1, kh + n, -1, na - 1, wp);
        else arb_set(acc, b_sum);
        arb_mul(acc, acc, inv, wp);
        arb_div_ui(hc + n + 1, acc, static_cast<ulong>(n + 1), wp);
        arb_mul_ui(kh + n + 1, hc + n + 1, static_cast<ulong>(n + 1), wp);
      }
      arb_clear(acc);
      arb_clear(inv);
      arb_clear(b_sum);
      _arb_vec_clear(kh, len);
      _arb_poly_set_length(hs, len);
      _arb_poly_normalise(hs);
      arb_poly_mullow(out.T, hs, gs, len, wp);
      if (sign < 0) arb_poly_neg(out.T, out.T);
      arb_poly_clear(hs);
      arb_poly_integral(out.P, out.T, wp);
      ok = to_dd(Tv, out.T) && to_dd(out.Pdd, out.P);
      Tv.resize(static_cast<std::size_t>(len), DDBall{});
    }
    arb_poly_clear(As);
    arb_poly_clear(Bs);
    // e = M q^(N+1) / (1 - q), q = 1 / lambda (dyadic lambdas: exact)
    Ball lam, q, e;
    arb_set_d(lam.get(), best_lambda);
    arb_inv(q.get(), lam.get(), wp);
    arb_pow_ui(e.get(), q.get(), static_cast<ulong>(len), wp);
    {
      Ball Mb;
      arf_set_mag(arb_midref(Mb.get()), bestM);
      arb_mul(e.get(), e.get(), Mb.get(), wp);
      Ball one_q;
      arb_one(one_q.get());
      arb_sub(one_q.get(), one_q.get(), q.get(), wp);
      arb_div(e.get(), e.get(), one_q.get(), wp);
    }
    out.e = e;
    out.a = a;
    out.b = b;
    out.c = c;
    out.xa = xa;
    out.xb = xb;
    out.Td.resize(Tv.size());
    for (std::size_t j = 0; j < Tv.size(); ++j) out.Td[j] = Tv[j].hi;
    out.Pd.resize(out.Pdd.size());
    for (std::size_t j = 0; j < out.Pdd.size(); ++j) out.Pd[j] = out.Pdd[j].hi;
    if (ok) {
      // L >= sum_{j>=1} j |t_j| h^(j-1); S1 >= sum |t_j| h^j; Sr >= sum
      // |t_j - Td_j| h^j (|lo| + rad of the double-word balls). Horner's
      // rule in double on Td (at most 100 terms) errs by at most
      // 2 (n + 1) u sum |Td_j| |x|^j (Higham, eq. 5.3): below 1e-13 S1.
      // Sums of non-negative doubles, each operation rounded up.
      const double hd = mag_get_d(h);  // >= h
      double Lsum = 0, S1 = 0, Sr = 0, hp = 1, hprev = 0;
      for (std::size_t j = 0; j < Tv.size(); ++j) {
        const double ab = up(up(std::fabs(Tv[j].hi) + std::fabs(Tv[j].lo)) + Tv[j].rad);
        const double off = up(std::fabs(Tv[j].lo) + Tv[j].rad);
        S1 = up(S1 + up(ab * hp));
        Sr = up(Sr + up(off * hp));
        if (j >= 1) Lsum = up(Lsum + up(up(static_cast<double>(j) * ab) * hprev));  // hprev = h^(j-1)
        hprev = hp;
        hp = up(hp * hd);
      }
      out.L = Lsum;
      out.Terr = up(Sr + up(1e-13 * S1));
      ok = std::isfinite(out.L) && std::isfinite(out.Terr) && len <= 100;
    }
    // P(xa) and the integral P(xb) - P(xa) +- (xb - xa) e
    if (ok && out.use_dd) {
      const DDBall pa = horner_dd(out.Pdd, xad), pb = horner_dd(out.Pdd, xbd);
      ok = dd_is_finite(pa) && dd_is_finite(pb);
      if (ok) {
        dd_get_arb(out.Pxa.get(), pa);
        dd_get_arb(out.integral.get(), pb);
        arb_sub(out.integral.get(), out.integral.get(), out.Pxa.get(), wp);
        Ball w;
        arb_sub(w.get(), xb.get(), xa.get(), wp);
        arb_mul(w.get(), w.get(), out.e.get(), wp);
        mag_t m;
        mag_init(m);
        arb_get_mag(m, w.get());
        arb_add_error_mag(out.integral.get(), m);
        mag_clear(m);
      }
    } else if (ok) {
      arb_poly_evaluate(out.Pxa.get(), out.P, xa.get(), wp);
      out.integral = out.from_a(xb, wp);
    }
    // relative radius of the integral at most 2^-bits
    ok = ok && std::isfinite(out.L) && arb_is_positive(out.integral.get()) && arb_is_finite(out.integral.get());
    if (ok) {
      arf_t lo, rad;
      arf_init(lo);
      arf_init(rad);
      arb_get_lbound_arf(lo, out.integral.get(), 64);
      arf_set_mag(rad, arb_radref(out.integral.get()));
      arf_mul_2exp_si(rad, rad, bits);
      ok = arf_cmp(rad, lo) <= 0;
      arf_clear(lo);
      arf_clear(rad);
    }
  }
  mag_clear(bestM);
  mag_clear(h);
  arb_poly_clear(gs);
  arb_poly_clear(Qs);
  arb_poly_clear(Ds);
  return ok;
}

}  // namespace uniparam
