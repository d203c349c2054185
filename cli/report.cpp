#include "report.hpp"

#include <arb_poly.h>

#include <utility>

namespace uniparam::cli {

namespace {

/// RAII holder of an arb_poly.
struct ArbPoly {
  arb_poly_t v;
  ArbPoly() { arb_poly_init(v); }
  ~ArbPoly() { arb_poly_clear(v); }
  ArbPoly(const ArbPoly&) = delete;
  ArbPoly& operator=(const ArbPoly&) = delete;
};

/// The sign of p at the exact rational x from a ball evaluation at `prec`
/// bits: -1 or 1 when certain, 0 when the ball contains 0 (unknown).
int ball_sign(const arb_poly_t p, const Rational& x, long prec) {
  const Ball bx(x, prec);
  Ball v;
  arb_poly_evaluate(v.get(), p, bx.get(), prec);
  if (arb_is_positive(v.get())) return 1;
  if (arb_is_negative(v.get())) return -1;
  return 0;
}

/// Whether the squarefree p, known to have a root in (lo, hi), has exactly
/// one root in [lo, hi] (lo < hi) and none at the ends. Yes: p(lo) and p(hi)
/// are nonzero with opposite signs and p' has no zero on [lo, hi], so p is
/// strictly monotone there. No: p(lo) and p(hi) are nonzero with the same
/// sign, so the simple roots inside are even in number, hence at least two. p' on [lo, hi] is
/// enclosed in the mean-value form p'(m) + p''([lo, hi]) [-r, r] (m, r the
/// centre and radius of a ball containing [lo, hi]), all in Arb balls. False
/// Unknown: p' may vanish, or the precision was too low. A few
/// evaluations of p, p' and p'' at doubling precisions, never an exact root
/// count, so a polynomial of degree thousands costs milliseconds here.
enum class Answer { Yes, No, Unknown };

Answer one_root_by_monotony(const Poly& p, const Rational& lo, const Rational& hi) {
  if (p.degree() < 1) return Answer::Unknown;
  for (long prec = 128; prec <= 8192; prec *= 4) {
    check_time_budget();
    ArbPoly P, D1, D2;
    arb_poly_set_fmpz_poly(P.v, p.get(), prec);
    arb_poly_derivative(D1.v, P.v, prec);
    arb_poly_derivative(D2.v, D1.v, prec);
    const int s_lo = ball_sign(P.v, lo, prec), s_hi = ball_sign(P.v, hi, prec);
    if (s_lo == 0 || s_hi == 0) continue;
    if (s_lo == s_hi) return Answer::No;
    const Ball a(lo, prec), b(hi, prec);
    Ball J, m, w, dm, d1, d2;
    arb_union(J.get(), a.get(), b.get(), prec);
    arb_set_arf(m.get(), arb_midref(J.get()));
    arb_zero(w.get());
    arb_add_error_mag(w.get(), arb_radref(J.get()));  // [-r, r]
    arb_poly_evaluate(dm.get(), D1.v, m.get(), prec);
    arb_poly_evaluate(d2.get(), D2.v, J.get(), prec);
    arb_mul(d1.get(), d2.get(), w.get(), prec);
    arb_add(d1.get(), d1.get(), dm.get(), prec);
    if (!arb_contains_zero(d1.get())) return Answer::Yes;
    // p'(m) known to a few bits: the spread p''(J) r decides, which more
    // bits do not shrink (the interval's width does).
    if (arb_rel_accuracy_bits(dm.get()) >= 8) return Answer::Unknown;
  }
  return Answer::Unknown;
}

}  // namespace

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
    // Exactly one root inside, none at the ends: first the cheap test, then
    // (when it cannot tell) the exact count.
    const Answer cheap = one_root_by_monotony(x.poly(), lo, hi);
    if (cheap == Answer::Yes) return {lo, hi};
    if (cheap == Answer::Unknown && x.poly().sign_at(lo) != 0 && x.poly().sign_at(hi) != 0 && count_real_roots(x.poly(), lo, hi) == 1)
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
