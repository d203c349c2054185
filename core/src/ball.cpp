#include "uniparam/core/ball.hpp"

#include "uniparam/core/error.hpp"

#include <arf.h>
#include <mag.h>

#include "error_util.hpp"
#include "uniparam/core/decimal.hpp"

namespace uniparam {

bool Ball::meets_digits(long digits) const {
  if (!is_finite()) return false;
  // rad <= 10^-digits * max(1, |mid|), decided exactly on rationals.
  Rational mid, rad;
  arf_get_fmpq(mid.get(), arb_midref(v_));
  arf_t r;
  arf_init(r);
  arf_set_mag(r, arb_radref(v_));
  arf_get_fmpq(rad.get(), r);
  arf_clear(r);
  if (mid.sign() < 0) mid = -mid;
  Rational scale = mid > Rational(1) ? mid : Rational(1);
  Integer p;
  fmpz_set_ui(p.get(), 10); fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(digits < 0 ? 0 : digits));
  return rad * Rational(p) <= scale;
}

std::string Ball::mid_decimal(long digits) const { return decimal_enclosure(*this, digits).mid; }

std::string Ball::rad_decimal() const {
  Rational rad;
  arf_t r;
  arf_init(r);
  arf_set_mag(r, arb_radref(v_));
  arf_get_fmpq(rad.get(), r);
  arf_clear(r);
  return decimal_upper(rad);
}

std::string Ball::str(long digits) const { return detail::take_flint_string(arb_get_str(v_, digits, 0)); }

void clamp_unit(arb_t x, long prec) {
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, x, prec);
  arb_get_ubound_arf(hi, x, prec);
  if (arf_sgn(lo) < 0) arf_zero(lo);
  if (arf_cmp_si(hi, 1) > 0) arf_one(hi);
  if (arf_cmp(lo, hi) > 0) arf_set(lo, hi);
  arb_set_interval_arf(x, lo, hi, prec);
  arf_clear(lo);
  arf_clear(hi);
}

Rational mid_rational(const Ball& b) {
  if (!arf_is_finite(arb_midref(b.get()))) throw DomainError("mid_rational: the ball's midpoint is not finite");
  fmpq_t q;
  fmpq_init(q);
  arf_get_fmpq(q, arb_midref(b.get()));
  Rational r(q);
  fmpq_clear(q);
  return r;
}

Rational rad_rational(const Ball& b) {
  if (!mag_is_finite(arb_radref(b.get()))) throw DomainError("rad_rational: the ball's radius is not finite");
  arf_t r;
  arf_init(r);
  arf_set_mag(r, arb_radref(b.get()));
  Rational q;
  arf_get_fmpq(q.get(), r);
  arf_clear(r);
  return q;
}

Ball interval_ball(const Rational& lo, const Rational& hi, long prec) {
  Ball a(lo, prec), b(hi, prec), r;
  arb_union(r.get(), a.get(), b.get(), prec);
  return r;
}

bool all_meet_digits(const std::vector<Ball>& v, long digits) {
  for (const auto& b : v)
    if (!b.meets_digits(digits)) return false;
  return true;
}

std::vector<Ball> cumulative_normalised(const std::vector<Ball>& w, const Ball& total, long prec) {
  std::vector<Ball> out{Ball(0)};
  Ball acc(0);
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    arb_add(acc.get(), acc.get(), w[k].get(), prec);
    Ball q;
    arb_div(q.get(), acc.get(), total.get(), prec);
    out.push_back(q);
  }
  out.push_back(Ball(1));
  return out;
}

}  // namespace uniparam
