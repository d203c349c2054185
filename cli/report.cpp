#include "report.hpp"

#include <utility>

namespace uniparam::cli {

std::pair<Rational, Rational> short_interval(const RealAlgebraic& x) { return x.short_interval(); }

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

Json json_surd(const QuadraticSurd& q, const Ball& b, long pd) {
  if (q.is_rational()) return json_rational(q.rational(), pd);
  Json j = json_ball(b, pd);
  Json e = Json::object();
  e.set("text", Json::string(q.str(Format::Text)));
  e.set("latex", Json::string(q.str(Format::Latex)));
  e.set("maple", Json::string(q.str(Format::Maple)));
  j.set("exact", e);
  return j;
}

Json json_zeros(const std::vector<SpeedZero>& zeros, long digits) {
  Json zs = Json::array();
  for (const auto& z : zeros) {
    Json e = Json::object();
    e.set("t", json_algebraic(z.t, digits));
    e.set("multiplicity", Json::number(z.multiplicity));
    zs.push(e);
  }
  return zs;
}

}  // namespace uniparam::cli
