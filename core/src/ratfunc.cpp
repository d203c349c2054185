#include "uniparam/core/ratfunc.hpp"

#include <algorithm>

#include "error_util.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

RatFunc::RatFunc(const Rational& c) {
  fmpz_poly_q_init(v_);
  fmpz_poly_set_fmpz(fmpz_poly_q_numref(v_), fmpq_numref(c.get()));
  fmpz_poly_set_fmpz(fmpz_poly_q_denref(v_), fmpq_denref(c.get()));
}

RatFunc::RatFunc(const Poly& p) {
  fmpz_poly_q_init(v_);
  fmpz_poly_set(fmpz_poly_q_numref(v_), p.get());
}

RatFunc::RatFunc(const Poly& num, const Poly& den) {
  if (den.is_zero()) throw DomainError("division by zero (the denominator is the zero polynomial)");
  fmpz_poly_q_init(v_);
  fmpz_poly_set(fmpz_poly_q_numref(v_), num.get());
  fmpz_poly_set(fmpz_poly_q_denref(v_), den.get());
  fmpz_poly_q_canonicalise(v_);
}

RatFunc RatFunc::t() { return RatFunc(Poly::t()); }

bool RatFunc::is_constant() const noexcept {
  return fmpz_poly_degree(fmpz_poly_q_numref(v_)) <= 0 && fmpz_poly_degree(fmpz_poly_q_denref(v_)) <= 0;
}

RatFunc RatFunc::derivative() const { RatFunc r; fmpz_poly_q_derivative(r.v_, v_); return r; }

Rational RatFunc::operator()(const Rational& x) const {
  Rational d = den()(x);
  if (d.is_zero()) throw DomainError("evaluation at a pole t = " + x.str());
  return num()(x) / d;
}

std::string RatFunc::str(const char* var) const {
  Poly n = num(), d = den();
  if (d == Poly(1)) return n.str(var);
  return "(" + n.str(var) + ")/(" + d.str(var) + ")";
}

RatFunc operator+(const RatFunc& a, const RatFunc& b) { RatFunc r; fmpz_poly_q_add(r.v_, a.v_, b.v_); return r; }
RatFunc operator-(const RatFunc& a, const RatFunc& b) { RatFunc r; fmpz_poly_q_sub(r.v_, a.v_, b.v_); return r; }
RatFunc operator*(const RatFunc& a, const RatFunc& b) { RatFunc r; fmpz_poly_q_mul(r.v_, a.v_, b.v_); return r; }
RatFunc operator/(const RatFunc& a, const RatFunc& b) {
  if (b.is_zero()) throw DomainError("division by zero");
  RatFunc r;
  fmpz_poly_q_div(r.v_, a.v_, b.v_);
  return r;
}
RatFunc RatFunc::operator-() const { RatFunc r; fmpz_poly_q_neg(r.v_, v_); return r; }

RatFunc RatFunc::pow(long e) const {
  if (e >= 0) { RatFunc r; fmpz_poly_q_pow(r.v_, v_, static_cast<ulong>(e)); return r; }
  if (is_zero()) throw DomainError("division by zero (zero raised to a negative power)");
  RatFunc inv;
  fmpz_poly_q_inv(inv.v_, v_);
  return inv.pow(-e);
}

namespace {

// sum_k c_k a^k b^(d - k) for c of degree d <= deg (homogenised at degree deg).
void homogenise(fmpz_poly_t out, const fmpz_poly_t c, const fmpz_poly_t a, const fmpz_poly_t b, slong deg) {
  fmpz_poly_t apow, term, bp;
  fmpz_poly_init(apow);
  fmpz_poly_init(term);
  fmpz_poly_init(bp);
  fmpz_poly_zero(out);
  fmpz_poly_one(apow);
  for (slong k = 0; k <= fmpz_poly_degree(c); ++k) {
    if (!fmpz_is_zero(c->coeffs + k)) {
      fmpz_poly_pow(bp, b, static_cast<ulong>(deg - k));
      fmpz_poly_mul(term, apow, bp);
      fmpz_poly_scalar_mul_fmpz(term, term, c->coeffs + k);
      fmpz_poly_add(out, out, term);
    }
    fmpz_poly_mul(apow, apow, a);
  }
  fmpz_poly_clear(apow);
  fmpz_poly_clear(term);
  fmpz_poly_clear(bp);
}

}  // namespace

RatFunc compose(const RatFunc& f, const RatFunc& g) {
  const fmpz_poly_struct* a = fmpz_poly_q_numref(g.get());
  const fmpz_poly_struct* b = fmpz_poly_q_denref(g.get());
  const fmpz_poly_struct* n = fmpz_poly_q_numref(f.get());
  const fmpz_poly_struct* q = fmpz_poly_q_denref(f.get());
  const slong d = std::max<slong>(std::max<slong>(fmpz_poly_degree(n), fmpz_poly_degree(q)), 0);
  // f(a/b) = [sum n_k a^k b^(d-k)] / [sum q_k a^k b^(d-k)]: the powers b^d cancel.
  Poly num, den;
  homogenise(num.get(), n, a, b, d);
  homogenise(den.get(), q, a, b, d);
  if (den.is_zero()) throw DomainError("compose: the inner function hits a pole of the outer one identically");
  return RatFunc(num, den);
}

}  // namespace uniparam
