#include "uniparam/core/poly.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <arb.h>
#include <arb_fmpz_poly.h>

#include "error_util.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

Poly::Poly(const std::vector<Integer>& c) {
  fmpz_poly_init(v_);
  for (std::size_t i = 0; i < c.size(); ++i) fmpz_poly_set_coeff_fmpz(v_, static_cast<slong>(i), c[i].get());
}

Poly::Poly(const std::vector<long>& c) {
  fmpz_poly_init(v_);
  for (std::size_t i = 0; i < c.size(); ++i) fmpz_poly_set_coeff_si(v_, static_cast<slong>(i), c[i]);
}

Poly Poly::t() { return Poly(std::vector<long>{0, 1}); }

Integer Poly::coeff(long i) const {
  Integer r;
  if (i >= 0) fmpz_poly_get_coeff_fmpz(r.get(), v_, i);
  return r;
}

long Poly::max_bits() const noexcept {
  slong b = fmpz_poly_max_bits(v_);
  return b < 0 ? -b : b;
}

Poly Poly::derivative() const { Poly r; fmpz_poly_derivative(r.v_, v_); return r; }

Rational Poly::operator()(const Rational& x) const {
  Rational r;
  fmpz_poly_evaluate_fmpq(r.get(), v_, x.get());
  return r;
}

int Poly::sign_at(const Rational& x) const {
  // A ball value first (rigorous: a sign it shows is the sign), the exact
  // rational value only when the ball holds 0 at every precision tried. The
  // exact value of a degree-n polynomial at a b-bit rational has ~n b bits
  // (at degree 1000 and b = 80, milliseconds); the ball costs n operations.
  if (!fmpz_poly_is_zero(v_)) {
    arb_t bx, by;
    arb_init(bx);
    arb_init(by);
    int sign = 0;
    for (long prec : {128L, 512L}) {
      arb_set_fmpq(bx, x.get(), prec);
      arb_fmpz_poly_evaluate_arb(by, v_, bx, prec);
      if (arb_is_positive(by)) sign = 1;
      else if (arb_is_negative(by)) sign = -1;
      if (sign != 0) break;
    }
    arb_clear(bx);
    arb_clear(by);
    if (sign != 0) return sign;
  }
  return (*this)(x).sign();
}

Poly Poly::primitive() const {
  Poly r;
  const slong len = v_->length;
  if (len == 0) return r;
  // The content: the gcd starts from the coefficient with the fewest bits,
  // so every later gcd is a big number modulo a small one, and it stops
  // once it reaches 1. (FLINT's content runs full-size gcds over every
  // coefficient: ~5.5 million instructions for the degree-1633 critical
  // numerator of a degree-150 space curve, made primitive for each root.)
  slong small = -1;
  for (slong k = 0; k < len; ++k)
    if (!fmpz_is_zero(v_->coeffs + k) &&
        (small < 0 || fmpz_bits(v_->coeffs + k) < fmpz_bits(v_->coeffs + small)))
      small = k;
  fmpz_t c;
  fmpz_init(c);
  fmpz_abs(c, v_->coeffs + small);
  for (slong k = len - 1; k >= 0 && !fmpz_is_one(c); --k) fmpz_gcd(c, c, v_->coeffs + k);
  if (fmpz_sgn(v_->coeffs + len - 1) < 0) fmpz_neg(c, c);  // positive leading coefficient
  if (fmpz_is_one(c)) fmpz_poly_set(r.v_, v_);
  else fmpz_poly_scalar_divexact_fmpz(r.v_, v_, c);
  fmpz_clear(c);
  return r;
}

std::string Poly::str(const char* var) const {
  if (is_zero()) return "0";
  std::string out;
  for (long i = degree(); i >= 0; --i) {
    Integer c = coeff(i);
    if (c.sign() == 0) continue;
    bool neg = c.sign() < 0;
    std::string mag = neg ? (-Rational(c)).str() : c.str();
    if (out.empty()) out += neg ? "-" : "";
    else out += neg ? " - " : " + ";
    bool unit = (mag == "1") && i > 0;
    if (!unit) out += mag;
    if (i > 0) {
      if (!unit) out += "*";
      out += var;
      if (i > 1) out += "^" + std::to_string(i);
    }
  }
  return out;
}

Poly operator+(const Poly& a, const Poly& b) { Poly r; fmpz_poly_add(r.v_, a.v_, b.v_); return r; }
Poly operator-(const Poly& a, const Poly& b) { Poly r; fmpz_poly_sub(r.v_, a.v_, b.v_); return r; }
Poly operator*(const Poly& a, const Poly& b) { Poly r; fmpz_poly_mul(r.v_, a.v_, b.v_); return r; }
Poly Poly::operator-() const { Poly r; fmpz_poly_neg(r.v_, v_); return r; }
Poly Poly::pow(unsigned long e) const { Poly r; fmpz_poly_pow(r.v_, v_, e); return r; }

Poly gcd(const Poly& a, const Poly& b) {
  Poly r;
  fmpz_poly_gcd(r.get(), a.get(), b.get());
  return r;
}

Poly divexact(const Poly& a, const Poly& b) {
  if (b.is_zero()) throw DomainError("polynomial division by zero");
  Poly q;  // distinct from a: fmpz_poly_divides zeroes q on failure
  if (!fmpz_poly_divides(q.get(), a.get(), b.get()))
    throw DomainError("polynomial does not divide exactly");
  return q;
}

Poly centred_at_half(const Poly& p) {
  if (p.is_zero()) return p;
  const slong n = p.degree();
  Poly r, q;  // r(u) = 2^n p(u / 2) = sum p_k 2^(n-k) u^k, q(s) = r(1 + s)
  fmpz_poly_fit_length(r.get(), n + 1);
  for (slong k = 0; k <= n; ++k)
    fmpz_mul_2exp(r.get()->coeffs + k, p.get()->coeffs + k, static_cast<ulong>(n - k));
  _fmpz_poly_set_length(r.get(), n + 1);
  fmpz_t one;
  fmpz_init_set_ui(one, 1);
  fmpz_poly_taylor_shift(q.get(), r.get(), one);
  fmpz_clear(one);
  return q;
}

std::vector<double> scaled_doubles(const Poly& p) {
  const slong n = p.degree();
  if (n < 0) return {};
  const fmpz* a = p.get()->coeffs;
  std::vector<double> m(static_cast<std::size_t>(n + 1));
  std::vector<slong> e(static_cast<std::size_t>(n + 1));
  slong emax = std::numeric_limits<slong>::min();
  for (slong k = 0; k <= n; ++k) {
    m[k] = fmpz_get_d_2exp(&e[k], a + k);
    if (m[k] != 0) emax = std::max(emax, e[k]);
  }
  std::vector<double> c(static_cast<std::size_t>(n + 1));
  for (slong k = 0; k <= n; ++k)
    c[k] = m[k] == 0 ? 0 : std::ldexp(m[k], static_cast<int>(std::max<slong>(e[k] - emax, -2000)));
  return c;
}

Poly mapped_to_unit_interval(const Poly& f, const Rational& a, const Rational& b) {
  // a = A / L, b - a = W / L: G = L^n f((A + W x) / L), the Taylor shift by
  // A of sum f_i L^(n - i) y^i, then y = W x.
  const Rational w = b - a;
  const Integer L = a.den() * w.den();
  const Integer A = a.num() * w.den();
  const Integer W = w.num() * a.den();
  const slong n = f.degree();
  Poly H(f);
  {
    Integer Lp(1);
    fmpz* c = H.get()->coeffs;
    for (slong i = n; i >= 0; --i) {  // c_i * L^(n-i)
      fmpz_mul(c + i, c + i, Lp.get());
      fmpz_mul(Lp.get(), Lp.get(), L.get());
    }
  }
  Poly G;
  fmpz_poly_taylor_shift(G.get(), H.get(), A.get());
  {
    Integer Wp(1);
    fmpz* c = G.get()->coeffs;
    for (slong i = 0; i <= n; ++i) {
      fmpz_mul(c + i, c + i, Wp.get());
      fmpz_mul(Wp.get(), Wp.get(), W.get());
    }
  }
  return G.primitive();
}

}  // namespace uniparam
