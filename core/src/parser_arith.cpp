// Checked exact arithmetic of the parser: the values of number tokens and
// the operations on rational functions (sum, product, quotient, power),
// each refused with BudgetExceeded when a prediction of its result's degree
// or coefficient size exceeds the limits, before anything is computed.
#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_q.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "parser_detail.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam::parser_detail {
namespace {

Rational power_of_ten(long k) {
  Integer p;
  fmpz_set_ui(p.get(), 10);
  fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(k < 0 ? -k : k));
  return k >= 0 ? Rational(p) : Rational(Integer(1), p);
}

// ---- size predictions -------------------------------------------------------

long poly_bits(const fmpz_poly_struct* p) {
  slong b = fmpz_poly_max_bits(p);
  return b < 0 ? -b : b;
}

/// Upper bound of (length) * (max coefficient bits) of the product p*q.
double product_size(const fmpz_poly_struct* p, const fmpz_poly_struct* q) {
  if (p->length == 0 || q->length == 0) return 0.0;
  const double len = static_cast<double>(p->length + q->length - 1);
  const double shortest = static_cast<double>(std::min(p->length, q->length));
  const double bits = static_cast<double>(poly_bits(p) + poly_bits(q)) + std::ceil(std::log2(shortest)) + 1.0;
  return len * bits;
}

const fmpz_poly_struct* num_of(const RatFunc& r) { return fmpz_poly_q_numref(r.get()); }
const fmpz_poly_struct* den_of(const RatFunc& r) { return fmpz_poly_q_denref(r.get()); }
long deg(const fmpz_poly_struct* p) { return fmpz_poly_degree(p); }

}  // namespace

std::string size_limit_text(long max_bits) {
  return "the size limit of " + std::to_string(max_bits) + " bits (raise it with --max-bits)";
}

Rational number_value(const std::string& s, std::size_t pos, long max_bits) {
  std::string mantissa;
  long frac_digits = 0;
  std::size_t i = 0;
  while (i < s.size() && is_digit(s[i])) mantissa += s[i++];
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) { mantissa += s[i++]; ++frac_digits; }
  }
  long exponent = 0;
  bool too_long = false;
  if (i < s.size()) {  // 'e' or 'E'
    ++i;
    bool neg = false;
    if (s[i] == '+' || s[i] == '-') { neg = s[i] == '-'; ++i; }
    while (i < s.size() && s[i] == '0') ++i;
    too_long = s.size() - i > 15;  // |exponent| < 10^15: no overflow below
    for (; !too_long && i < s.size(); ++i) exponent = 10 * exponent + (s[i] - '0');
    if (neg) exponent = -exponent;
  }
  // mantissa * 10^(exponent - frac_digits): predict its size before computing it.
  const double bits = kBitsPerDigit * (static_cast<double>(mantissa.size()) +
                                       std::fabs(static_cast<double>(exponent - frac_digits)));
  if (too_long || bits > static_cast<double>(max_bits))
    throw BudgetExceeded("the number " + quote(s) + " at " + column_text(pos) +
                         " is too large: its exact value exceeds " + size_limit_text(max_bits));
  Rational value(Integer(mantissa.empty() ? std::string("0") : mantissa));
  if (value.is_zero()) return value;
  return value * power_of_ten(exponent - frac_digits);
}

void Parser::check(long num_deg, long den_deg, double num_size, double den_size, std::size_t pos,
                   const char* what) const {
  const long d = std::max(num_deg, den_deg);
  if (d > lim_.max_degree)
    throw BudgetExceeded("degree limit exceeded at " + column_text(pos) + ": the " + what +
                         " would have degree up to " + std::to_string(d) + ", above the degree limit of " +
                         std::to_string(lim_.max_degree) + " (raise it with --max-degree)");
  const double size = std::max(num_size, den_size);
  if (size > static_cast<double>(lim_.max_bits)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", size);
    throw BudgetExceeded("size limit exceeded at " + column_text(pos) + ": the " + what + " would need about " +
                         buf + " bits, above " + size_limit_text(lim_.max_bits));
  }
}

RatFunc Parser::add(const RatFunc& a, const RatFunc& b, bool subtract, std::size_t pos) const {
  if (!a.is_zero() && !b.is_zero()) {
    const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
    const long num_deg = std::max(deg(na) + deg(db), deg(nb) + deg(da));
    const double num_size = std::max(product_size(na, db), product_size(nb, da)) + static_cast<double>(num_deg + 1);
    check(num_deg, deg(da) + deg(db), num_size, product_size(da, db), pos, subtract ? "difference" : "sum");
  }
  return subtract ? a - b : a + b;
}

RatFunc Parser::mul(const RatFunc& a, const RatFunc& b, std::size_t pos) const {
  if (a.is_zero() || b.is_zero()) return RatFunc(0);
  const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
  check(deg(na) + deg(nb), deg(da) + deg(db), product_size(na, nb), product_size(da, db), pos, "product");
  return a * b;
}

RatFunc Parser::div(const RatFunc& a, const RatFunc& b, std::size_t pos) const {
  if (b.is_zero())
    throw DomainError("division by zero at " + column_text(pos) + ": the divisor is identically zero");
  if (a.is_zero()) return RatFunc(0);
  const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
  check(deg(na) + deg(db), deg(da) + deg(nb), product_size(na, db), product_size(da, nb), pos, "quotient");
  return a / b;
}

// base^e by left-to-right binary powering, checking the size of every step.
void Parser::pow_poly(fmpz_poly_t out, const fmpz_poly_struct* base, unsigned long e, std::size_t pos) const {
  if (e == 0) { fmpz_poly_one(out); return; }
  fmpz_poly_set(out, base);
  int top = 63;
  while (!((e >> top) & 1UL)) --top;
  fmpz_poly_t tmp;
  fmpz_poly_init(tmp);
  try {
    for (int bit = top - 1; bit >= 0; --bit) {
      check(0, 0, product_size(out, out), 0.0, pos, "power");
      fmpz_poly_sqr(tmp, out);
      fmpz_poly_swap(tmp, out);
      if ((e >> bit) & 1UL) {
        check(0, 0, product_size(out, base), 0.0, pos, "power");
        fmpz_poly_mul(tmp, out, base);
        fmpz_poly_swap(tmp, out);
      }
    }
  } catch (...) {
    fmpz_poly_clear(tmp);
    throw;
  }
  fmpz_poly_clear(tmp);
}

RatFunc Parser::pow(const RatFunc& a, long e, std::size_t pos) const {
  if (e == 0) return RatFunc(1);
  if (a.is_zero()) {
    if (e < 0) throw DomainError("division by zero at " + column_text(pos) + ": 0 raised to a negative power");
    return RatFunc(0);
  }
  const unsigned long m = static_cast<unsigned long>(e < 0 ? -e : e);
  const double d = static_cast<double>(std::max(deg(num_of(a)), deg(den_of(a)))) * static_cast<double>(m);
  if (d > static_cast<double>(lim_.max_degree))
    throw BudgetExceeded("degree limit exceeded at " + column_text(pos) + ": the power would have degree " +
                         std::to_string(static_cast<long>(d)) + ", above the degree limit of " +
                         std::to_string(lim_.max_degree) + " (raise it with --max-degree)");
  // num and den are coprime with den's leading coefficient positive, so
  // num^m / den^m is already canonical; an inverse only needs the sign fixed.
  RatFunc r;
  fmpz_poly_struct* rn = fmpz_poly_q_numref(r.get());
  fmpz_poly_struct* rd = fmpz_poly_q_denref(r.get());
  pow_poly(rn, num_of(a), m, pos);
  pow_poly(rd, den_of(a), m, pos);
  if (e < 0) {
    fmpz_poly_swap(rn, rd);
    if (fmpz_sgn(fmpz_poly_lead(rd)) < 0) {
      fmpz_poly_neg(rn, rn);
      fmpz_poly_neg(rd, rd);
    }
  }
  return r;
}

}  // namespace uniparam::parser_detail
