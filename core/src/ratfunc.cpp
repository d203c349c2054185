#include "uniparam/core/ratfunc.hpp"

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

}  // namespace uniparam
