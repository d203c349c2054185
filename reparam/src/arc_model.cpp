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

void coeff_doubles(std::vector<double>& out, const arb_poly_t p) {
  out.resize(static_cast<std::size_t>(std::max<slong>(arb_poly_length(p), 1)));
  std::fill(out.begin(), out.end(), 0.0);
  for (slong j = 0; j < arb_poly_length(p); ++j) out[static_cast<std::size_t>(j)] = mid_d(p->coeffs + j);
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
      Pxa(o.Pxa) {
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

Ball ArcCell::sigma(const Ball& x, long prec) const {
  Ball v;
  arb_poly_evaluate(v.get(), T, x.get(), prec);
  mag_t m;
  mag_init(m);
  arb_get_mag(m, e.get());
  arb_add_error_mag(v.get(), m);
  mag_clear(m);
  return v;
}

ArcModeller::ArcModeller(const Speed& s) : s_(s) {
  arb_poly_init(g_);
  arb_poly_init(Q_);
  arb_poly_init(D_);
  Poly q(0);
  for (const Poly& k : s.cofactors()) q = q + k * k;
  // Integer coefficients: exact at any precision that holds them.
  const long prec = 64 + std::max({s.g().max_bits(), q.max_bits(), s.denominator().max_bits()});
  arb_poly_set_fmpz_poly(g_, s.g().get(), prec);
  arb_poly_set_fmpz_poly(Q_, q.get(), prec);
  arb_poly_set_fmpz_poly(D_, s.denominator().get(), prec);
  d_const_ = s.denominator().degree() <= 0;
}

ArcModeller::~ArcModeller() {
  arb_poly_clear(g_);
  arb_poly_clear(Q_);
  arb_poly_clear(D_);
}

bool ArcModeller::build(const Rational& a, const Rational& b, long bits, ArcCell& out) const {
  if (!(a < b)) return false;
  const long wp = bits + 40;
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
  arb_poly_taylor_shift(gs, g_, cb.get(), wp);
  arb_poly_taylor_shift(Qs, Q_, cb.get(), wp);
  arb_poly_taylor_shift(Ds, D_, cb.get(), wp);
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
    arb_poly_t sq;
    arb_poly_init(sq);
    arb_poly_sqrt_series(sq, Qs, len, wp);
    arb_poly_mullow(out.T, sq, gs, len, wp);
    if (d_const_) arb_poly_scalar_div(out.T, out.T, D0.get(), wp);
    else arb_poly_div_series(out.T, out.T, Ds, len, wp);
    if (sign < 0) arb_poly_neg(out.T, out.T);
    arb_poly_clear(sq);
    arb_poly_integral(out.P, out.T, wp);
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
    arb_poly_evaluate(out.Pxa.get(), out.P, xa.get(), wp);
    out.integral = out.from_a(xb, wp);
    coeff_doubles(out.Td, out.T);
    coeff_doubles(out.Pd, out.P);
    // relative radius of the integral at most 2^-bits
    ok = arb_is_positive(out.integral.get()) && arb_is_finite(out.integral.get());
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
