// Locating on a balanced curve (scaling.hpp): where a curve's speed is
// concentrated next to one end (huge coefficients, weights growing
// geometrically), locate() and the exact samples run on q = p o m and carry
// each point back by t = m(s).
#include <arb.h>

#include <algorithm>
#include <cmath>

#include "uniparam/core/decimal.hpp"
#include "locate_detail.hpp"

namespace uniparam::locate_detail {

namespace {

// The digits to ask of q's parameter s so that t = m(s) meets `digits`,
// after a try with `asked` gave t with the radius of `t`.
long more_digits(const Ball& t, long digits, long asked) {
  const double excess = static_cast<double>(mag_get_d_log2_approx(arb_radref(t.get()))) / 3.3219280948873623 +
                        static_cast<double>(digits);
  return asked + std::max(1L, static_cast<long>(std::ceil(excess)) + 1);
}

}  // namespace

LocatedPoint mapped_point(const Curve& p, const BalancedCurve& bal, const LocatedPoint& on_q, long digits) {
  LocatedPoint out = on_q;
  if (on_q.t.is_exact() && (arb_is_zero(on_q.t.get()) || arb_is_one(on_q.t.get()))) {
    out.point = p.eval(on_q.t, 128);
    return out;
  }
  out.t = balance_map_ball(bal, on_q.t, 2 * digits_to_bits(digits) + 64);
  return out;
}

LocateResult locate_balanced(const Curve& p, const BalancedCurve& bal, const Speed& sq, const Rational& value,
                             LocateTarget target, const Options& opt) {
  Options o = opt;
  for (;;) {
    LocateResult r = locate_on(CurveTrack(bal.q, sq, o.max_prec), value, target, o);
    r.at = mapped_point(p, bal, r.at, opt.digits);
    if (meets(r.at.t, opt.digits)) return r;
    o.digits = more_digits(r.at.t, opt.digits, o.digits);
    if (digits_to_bits(o.digits) > opt.max_prec) throw_budget("the located parameter", opt);
  }
}

}  // namespace uniparam::locate_detail
