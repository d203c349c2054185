// locate(): the parameter t at which G(t) = int_0^t sigma reaches a value,
// by the chain of certified integrals (locate_chain.cpp); the checks and
// messages every entry point of the locator shares.
#include "uniparam/reparam/locate.hpp"

#include <acb.h>
#include <arb.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "locate_detail.hpp"

namespace uniparam {

namespace locate_detail {

void check_not_zero_speed(bool identically_zero) {
  if (identically_zero)
    throw DomainError(
        "the angular speed of a straight line is identically zero: its turning angle is 0 at every t, "
        "so it determines no parameter (use the parametric speed, arc length)");
}

void check_digits_fit(const Options& opt) {
  if (digits_to_bits(opt.digits) > opt.max_prec)
    throw BudgetExceeded(std::to_string(opt.digits) + " digits need more than " +
                         std::to_string(digits_to_bits(opt.digits)) + " bits of working precision, above the " +
                         "precision limit of " + std::to_string(opt.max_prec) + " bits (raise it with --max-prec)");
}

// The value in messages: exact when short, else 12 significant digits.
std::string shown(const Rational& x) {
  const std::string exact = x.str();
  return exact.size() <= 40 ? exact : "~" + decimal_string(x, 12);
}

[[noreturn]] void throw_budget(const std::string& what, const Options& opt) {
  throw BudgetExceeded("could not certify " + what + " to " + std::to_string(opt.digits) + " digits within " +
                       std::to_string(opt.max_prec) + " bits of working precision (raise it with --max-prec)");
}

long next_bits(long bits) { return bits + std::max(32L, bits / 2); }

LocatedPoint exact_point(const Track& tr, long t) {
  LocatedPoint p;
  p.t = Ball(t);
  p.point = tr.eval(p.t, 128);
  return p;
}

}  // namespace locate_detail

using namespace locate_detail;

double sigma_estimate(const Speed& s, const Rational& x) {
  acb_t z, out;
  acb_init(z);
  acb_init(out);
  arb_set_fmpq(acb_realref(z), x.get(), 64);
  s.eval_squared(out, z, 64);
  const double v = arf_get_d(arb_midref(acb_realref(out)), ARF_RND_NEAR);
  acb_clear(z);
  acb_clear(out);
  return std::isfinite(v) && v > 0 ? std::sqrt(v) : 0.0;
}

LocateResult locate(const Curve& c, const Speed& s, const Rational& value, LocateTarget target,
                    const Options& opt) {
  validate(opt);
  // A speed concentrated next to one end (huge coefficients, weights
  // growing geometrically): located on the balanced curve q = p o m.
  if (const std::optional<BalancedCurve> bal = balance(c, s))
    return locate_balanced(c, *bal, Speed(bal->q, s.kind()), value, target, opt);
  // Narrow features inside (0, 1): on the track of s's charts.
  if (const SpeedCharts* ch = s.balanced_charts()) return locate_charts(c, s, *ch, value, target, opt);
  return locate_on(CurveTrack(c, s, opt.max_prec), value, target, opt);
}

LocateResult locate_on(const Track& tr, const Rational& value, LocateTarget target, const Options& opt) {
  check_not_zero_speed(tr.identically_zero());
  if (value.sign() < 0)
    throw InvalidArgument(std::string("the ") + (target == LocateTarget::Fraction ? "fraction" : "value") +
                          " must be >= 0, got " + shown(value));
  if (target == LocateTarget::Fraction && Rational(1) < value)
    throw InvalidArgument("the fraction must be in [0, 1], got " + shown(value));
  check_digits_fit(opt);
  LocateResult r;
  Bracket b{Rational(0), Rational(1), Ball(0)};
  for (long bits = digits_to_bits(opt.digits) + 32;; bits = next_bits(bits)) {
    if (bits > opt.max_prec) throw_budget("the located parameter", opt);
    check_time_budget();
    const long prec = 2 * bits + 64;
    r.mu = tr.mu(bits, opt);
    if (!r.mu.meets_digits(opt.digits + 1)) continue;
    if (target == LocateTarget::Fraction) arb_mul_fmpz(r.target.get(), r.mu.get(), value.num().get(), prec),
                                          arb_div_fmpz(r.target.get(), r.target.get(), value.den().get(), prec);
    else r.target = Ball(value, prec);
    if (value.is_zero()) {
      r.at = exact_point(tr, 0);
      return r;
    }
    if (target == LocateTarget::Fraction && value == Rational(1)) {
      r.at = exact_point(tr, 1);
      return r;
    }
    if (target == LocateTarget::Integral) {
      Ball diff;
      arb_sub(diff.get(), r.target.get(), r.mu.get(), prec);
      if (diff.certainly_positive())
        throw InvalidArgument("the value " + shown(value) + " exceeds mu = int_0^1 sigma = " +
                              r.mu.mid_decimal(opt.digits) + " (+/- " + r.mu.rad_decimal() +
                              "), the " + (tr.kind() == SpeedKind::Parametric ? "length" : "turning angle") +
                              " of the whole curve");
      if (!diff.certainly_negative()) {
        if (next_bits(bits) > opt.max_prec)
          throw BudgetExceeded("the value " + shown(value) + " cannot be told apart from mu = int_0^1 sigma = " +
                               r.mu.mid_decimal(opt.digits) + " within " + std::to_string(opt.max_prec) +
                               " bits of working precision (raise it with --max-prec, or ask for fraction 1)");
        continue;
      }
    }
    // G(lo) again at this precision (the bracket itself holds at any).
    b.Glo = b.lo.is_zero() ? Ball(0) : tr.integral(Rational(0), b.lo, bits);
    if (finish_point(tr, b, r.target, bits, opt, r.at)) return r;
  }
}

}  // namespace uniparam
