#include "report.hpp"

namespace uniparam::cli {

Json json_algebraic(const RealAlgebraic& x, long digits) {
  if (x.is_rational()) return json_rational(x.rational(), printed_digits(digits));
  Json j = json_ball(x.to_ball(digits_to_bits(digits) + 16), printed_digits(digits));
  Json e = Json::object();
  e.set("poly", Json::string(x.poly().str()));
  Json iv = Json::array();
  iv.push(Json::string(x.lo().str()));
  iv.push(Json::string(x.hi().str()));
  e.set("interval", iv);
  j.set("exact", e);
  return j;
}

std::string text_algebraic(const RealAlgebraic& x, long digits) {
  if (x.is_rational()) return x.rational().str();
  return x.decimal(printed_digits(digits)) + " (root of " + x.poly().str() + " in (" + x.lo().str() + ", " +
         x.hi().str() + "))";
}

Json json_ratfunc(const RatFunc& r) {
  Json j = Json::object();
  j.set("text", Json::string(format_ratfunc(r, Format::Text)));
  j.set("latex", Json::string(format_ratfunc(r, Format::Latex)));
  j.set("maple", Json::string(format_ratfunc(r, Format::Maple)));
  return j;
}

}  // namespace uniparam::cli
