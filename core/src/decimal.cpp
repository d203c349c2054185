#include "uniparam/core/decimal.hpp"

#include <arf.h>
#include <mag.h>

#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

Rational pow10(long k) {
  Integer p;
  fmpz_set_ui(p.get(), 10); fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(k < 0 ? -k : k));
  return k >= 0 ? Rational(p) : Rational(Integer(1), p);
}

// floor(log10(a)) for a > 0, exactly.
long floor_log10(const Rational& a) {
  long e = static_cast<long>(fmpz_sizeinbase(fmpq_numref(a.get()), 10)) -
           static_cast<long>(fmpz_sizeinbase(fmpq_denref(a.get()), 10));
  while (pow10(e) > a) --e;
  while (pow10(e + 1) <= a) ++e;
  return e;
}

// Formats N * 10^(e - digits(N) + 1), where N has exactly `nd` digits and the
// value's decimal exponent is e.
std::string format_scaled(bool neg, std::string digits, long e) {
  while (digits.size() > 1 && digits.back() == '0') digits.pop_back();
  std::string out = neg ? "-" : "";
  const long n = static_cast<long>(digits.size());
  if (e >= -7 && e < 21) {
    if (e < 0) {
      out += "0." + std::string(static_cast<std::size_t>(-e - 1), '0') + digits;
    } else if (e + 1 >= n) {
      out += digits + std::string(static_cast<std::size_t>(e + 1 - n), '0');
    } else {
      out += digits.substr(0, static_cast<std::size_t>(e + 1)) + "." + digits.substr(static_cast<std::size_t>(e + 1));
    }
  } else {
    out += digits.substr(0, 1);
    if (n > 1) out += "." + digits.substr(1);
    out += "e" + std::to_string(e);
  }
  return out;
}

enum class Round { Nearest, Up };

std::string format(const Rational& x, long sig, Round mode) {
  if (sig < 1) throw InvalidArgument("at least one significant digit is needed");
  if (x.is_zero()) return "0";
  const bool neg = x.sign() < 0;
  const Rational a = neg ? -x : x;
  long e = floor_log10(a);
  Rational scaled = a * pow10(sig - 1 - e);
  Integer n;
  if (mode == Round::Up) {
    fmpz_cdiv_q(n.get(), fmpq_numref(scaled.get()), fmpq_denref(scaled.get()));
  } else {  // nearest, ties away from zero: floor(scaled + 1/2)
    Rational h = scaled + Rational(1, 2);
    fmpz_fdiv_q(n.get(), fmpq_numref(h.get()), fmpq_denref(h.get()));
  }
  std::string digits = n.str();
  if (static_cast<long>(digits.size()) > sig) {  // rounded up to 10^sig
    ++e;
    digits = digits.substr(0, static_cast<std::size_t>(sig));
  }
  return format_scaled(neg, digits, e);
}

}  // namespace

std::string decimal_string(const Rational& x, long sig_digits) { return format(x, sig_digits, Round::Nearest); }

std::string decimal_upper(const Rational& x) {
  if (x.sign() < 0) throw InvalidArgument("decimal_upper needs a nonnegative number");
  return format(x, 2, Round::Up);
}

DecimalEnclosure decimal_enclosure(const Ball& x, long sig_digits) {
  if (!x.is_finite()) throw DomainError("a non-finite ball cannot be printed as an enclosure");
  const Rational mid = mid_rational(x), rad = rad_rational(x);
  DecimalEnclosure out;
  out.mid = decimal_string(mid, sig_digits);
  Rational printed = Rational::parse(out.mid);
  Rational err = mid - printed;
  if (err.sign() < 0) err = -err;
  out.rad = decimal_upper(rad + err);
  return out;
}

}  // namespace uniparam
