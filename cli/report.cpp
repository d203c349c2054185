#include "report.hpp"

#include <utility>

namespace uniparam::cli {

std::pair<Rational, Rational> short_interval(const RealAlgebraic& x) {
  // Widen the (possibly long) current interval to decimals with few digits,
  // keeping it isolating: exactly one root inside, no root at either end.
  for (long d = 2; d <= 200; d *= 2) {
    Ball b = x.to_ball(static_cast<long>(d * 3.33) + 16);
    const std::string step = "1e-" + std::to_string(d);
    Rational h = Rational::parse(step);
    Rational mid = Rational::parse(decimal_string(x.lo(), d + 2));
    // round to multiples of 10^-d around the interval
    Rational lo = mid - h, hi = mid + h;
    while (lo > x.lo()) lo = lo - h;
    while (hi < x.hi()) hi = hi + h;
    lo = Rational::parse(decimal_string(lo, d + 2));
    hi = Rational::parse(decimal_string(hi, d + 2));
    if (lo > x.lo() || hi < x.hi()) continue;
    if (x.poly().sign_at(lo) != 0 && x.poly().sign_at(hi) != 0 && count_real_roots(x.poly(), lo, hi) == 1)
      return {lo, hi};
  }
  return {x.lo(), x.hi()};
}

Json json_algebraic(const RealAlgebraic& x, long digits) {
  if (x.is_rational()) return json_rational(x.rational(), printed_digits(digits));
  Json j = json_ball(x.to_ball(digits_to_bits(digits) + 16), printed_digits(digits));
  Json e = Json::object();
  e.set("poly", Json::string(x.poly().str()));
  Json iv = Json::array();
  auto [lo, hi] = short_interval(x);
  iv.push(Json::string(lo.str()));
  iv.push(Json::string(hi.str()));
  e.set("interval", iv);
  j.set("exact", e);
  return j;
}

std::string text_algebraic(const RealAlgebraic& x, long digits) {
  if (x.is_rational()) return x.rational().str();
  auto [lo, hi] = short_interval(x);
  std::string poly = x.poly().str();
  if (poly.size() > 80)  // the full polynomial is in the JSON output
    poly = "a polynomial of degree " + std::to_string(x.poly().degree()) + " (see --json)";
  return x.decimal(printed_digits(digits)) + " (root of " + poly + " in (" + lo.str() + ", " + hi.str() + "))";
}

Json json_ratfunc(const RatFunc& r) {
  Json j = Json::object();
  j.set("text", Json::string(format_ratfunc(r, Format::Text)));
  j.set("latex", Json::string(format_ratfunc(r, Format::Latex)));
  j.set("maple", Json::string(format_ratfunc(r, Format::Maple)));
  return j;
}

}  // namespace uniparam::cli
