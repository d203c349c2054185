#include "uniparam/core/number.hpp"

#include <cctype>

#include "error_util.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

Integer::Integer(const std::string& decimal) {
  fmpz_init(v_);
  std::size_t i = (!decimal.empty() && decimal[0] == '-') ? 1 : 0;
  bool ok = i < decimal.size();
  for (std::size_t k = i; k < decimal.size(); ++k) ok = ok && std::isdigit(static_cast<unsigned char>(decimal[k]));
  if (!ok || fmpz_set_str(v_, decimal.c_str(), 10) != 0) {
    fmpz_clear(v_);
    throw InvalidArgument("not a decimal integer: '" + decimal + "'");
  }
}

std::string Integer::str() const { return detail::take_flint_string(fmpz_get_str(nullptr, 10, v_)); }

Integer operator+(const Integer& a, const Integer& b) { Integer r; fmpz_add(r.v_, a.v_, b.v_); return r; }
Integer operator-(const Integer& a, const Integer& b) { Integer r; fmpz_sub(r.v_, a.v_, b.v_); return r; }
Integer operator*(const Integer& a, const Integer& b) { Integer r; fmpz_mul(r.v_, a.v_, b.v_); return r; }

Rational::Rational(const Integer& num, const Integer& den) {
  if (den.sign() == 0) throw DomainError("division by zero in a rational number");
  fmpq_init(v_);
  fmpq_set_fmpz_frac(v_, num.get(), den.get());
}

Rational::Rational(long num, long den) : Rational(Integer(num), Integer(den)) {}

Rational Rational::parse(const std::string& s) {
  // grammar: ['-'] digits ['.' digits] [('e'|'E') ['+'|'-'] digits] | ['-'] digits '/' digits
  std::size_t i = 0;
  bool neg = false;
  if (i < s.size() && (s[i] == '-' || s[i] == '+')) { neg = s[i] == '-'; ++i; }
  auto digits = [&](std::size_t& k) {
    std::size_t start = k;
    while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
    return s.substr(start, k - start);
  };
  std::string ip = digits(i);
  std::string fp;
  bool had_point = false;
  if (i < s.size() && s[i] == '.') { had_point = true; ++i; fp = digits(i); }
  if (ip.empty() && fp.empty()) throw ParseError(i + 1, "a digit", "invalid number '" + s + "'");
  Rational value(Integer(ip.empty() ? std::string("0") : ip));
  if (!fp.empty()) {
    Integer f(fp), p;
    fmpz_set_ui(p.get(), 10); fmpz_pow_ui(p.get(), p.get(), fp.size());
    value = value + Rational(f, p);
  }
  if (i < s.size() && s[i] == '/' && !had_point) {
    ++i;
    std::string dp = digits(i);
    if (dp.empty()) throw ParseError(i + 1, "a digit", "invalid fraction '" + s + "'");
    Integer d(dp);
    if (d.sign() == 0) throw DomainError("division by zero in '" + s + "'");
    value = Rational(Integer(ip), d);
  } else if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    bool eneg = false;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) { eneg = s[i] == '-'; ++i; }
    std::string ep = digits(i);
    if (ep.empty()) throw ParseError(i + 1, "a digit", "invalid exponent in '" + s + "'");
    if (ep.size() > 6) throw InvalidArgument("exponent out of range in '" + s + "'");
    Integer p;
    fmpz_set_ui(p.get(), 10); fmpz_pow_ui(p.get(), p.get(), std::stoul(ep));
    value = eneg ? value / Rational(p) : value * Rational(p);
  }
  if (i != s.size()) throw ParseError(i + 1, "end of number", "unexpected character in '" + s + "'");
  return neg ? -value : value;
}

std::string Rational::str() const { return detail::take_flint_string(fmpq_get_str(nullptr, 10, v_)); }

Rational operator+(const Rational& a, const Rational& b) { Rational r; fmpq_add(r.v_, a.v_, b.v_); return r; }
Rational operator-(const Rational& a, const Rational& b) { Rational r; fmpq_sub(r.v_, a.v_, b.v_); return r; }
Rational operator*(const Rational& a, const Rational& b) { Rational r; fmpq_mul(r.v_, a.v_, b.v_); return r; }
Rational operator/(const Rational& a, const Rational& b) {
  if (b.is_zero()) throw DomainError("division by zero");
  Rational r;
  fmpq_div(r.v_, a.v_, b.v_);
  return r;
}
Rational Rational::operator-() const { Rational r; fmpq_neg(r.v_, v_); return r; }

Rational Rational::simplest_between(const Rational& lo, const Rational& hi) {
  if (hi < lo) throw InvalidArgument("Rational::simplest_between: empty interval [" + lo.str() + ", " + hi.str() + "]");
  Rational r;
  fmpq_simplest_between(r.v_, lo.v_, hi.v_);
  return r;
}

Rational pow2(long e) {
  Rational r(1);
  if (e >= 0) fmpq_mul_2exp(r.get(), r.get(), static_cast<flint_bitcnt_t>(e));
  else fmpq_div_2exp(r.get(), r.get(), static_cast<flint_bitcnt_t>(-e));
  return r;
}

Rational grid_floor(const Rational& x, long s) {
  const Rational y = x * pow2(-s);
  Integer f;
  fmpz_fdiv_q(f.get(), fmpq_numref(y.get()), fmpq_denref(y.get()));
  return Rational(f) * pow2(s);
}

}  // namespace uniparam
