// Speed charts (speed_charts.hpp): the parts of a speed with narrow
// interior features, their exact charts, and the spans of an interval in them.
#include "speed_charts.hpp"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <utility>

#include "uniparam/core/error.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/algebra/newton_polygon.hpp"

namespace uniparam {

Rational SpeedChart::length() const {
  const Rational h = k1 - k0;
  return h.sign() < 0 ? -h : h;
}

RealAlgebraic SpeedChart::local(const RealAlgebraic& t) const {
  // x = (t - k0) / (k1 - k0) in [0, 1], then u = m^-1(x)
  const RealAlgebraic x = [&]() {
    if (t.is_rational()) return RealAlgebraic((t.rational() - k0) / (k1 - k0));
    // t is irrational, so strictly between k0 and k1: its interval is
    // refined into that part, then mapped (increasing or not).
    const Rational lo = std::min(k0, k1), hi = std::max(k0, k1);
    for (long bits = 64; !(lo <= t.lo() && t.hi() <= hi); bits *= 2) t.refine(bits);
    Rational xl = (t.lo() - k0) / (k1 - k0), xh = (t.hi() - k0) / (k1 - k0);
    if (xh < xl) std::swap(xl, xh);
    return RealAlgebraic(mapped_to_unit_interval(t.poly(), k0, k1), xl, xh);
  }();
  return bal ? balance_unmap(*bal, x) : x;
}

Rational SpeedChart::at(const Rational& u) const {
  Rational m = u;
  if (bal) {
    const Rational a(bal->a), b(bal->b);
    m = a * u / (a * u + b * (Rational(1) - u));
  }
  return k0 + (k1 - k0) * m;
}

Ball SpeedChart::at(const arf_t u, long prec) const {
  Ball m;
  arb_set_arf(m.get(), u);
  if (bal) m = balance_map_ball(*bal, m, prec);
  const Rational h = k1 - k0;
  Ball t;
  arb_mul_fmpz(t.get(), m.get(), h.num().get(), prec);
  arb_div_fmpz(t.get(), t.get(), h.den().get(), prec);
  Ball k(k0, prec);
  arb_add(t.get(), t.get(), k.get(), prec);
  return t;
}

namespace {

const Integer& chart_a(const SpeedChart& c) {
  static const Integer one(1);
  return c.bal ? c.bal->a : one;
}
const Integer& chart_b(const SpeedChart& c) {
  static const Integer one(1);
  return c.bal ? c.bal->b : one;
}

// w0 = 1 / (a b |k1 - k0|) of the chart c.
Rational chart_w0(const SpeedChart& c) { return Rational(1) / (Rational(chart_a(c) * chart_b(c)) * c.length()); }

}  // namespace

void SpeedChart::denominator(acb_t d, const acb_t z, long prec) const {
  if (!bal) {
    acb_one(d);
    return;
  }
  acb_t t;
  acb_init(t);
  acb_neg(d, z);
  acb_add_si(d, d, 1, prec);
  acb_mul_fmpz(d, d, bal->b.get(), prec);
  acb_mul_fmpz(t, z, bal->a.get(), prec);
  acb_add(d, d, t, prec);
  acb_clear(t);
}

namespace {

// c1 a z + c0 b (1 - z): d(z) (phi(z) - x) with c1 = k1 - x, c0 = k0 - x.
void offset_terms(const SpeedChart& c, acb_t out, const acb_t z, arb_t c1, arb_t c0, long prec) {
  acb_t t;
  acb_init(t);
  arb_mul_fmpz(c1, c1, chart_a(c).get(), prec);
  acb_mul_arb(out, z, c1, prec);
  arb_mul_fmpz(c0, c0, chart_b(c).get(), prec);
  acb_neg(t, z);
  acb_add_si(t, t, 1, prec);
  acb_mul_arb(t, t, c0, prec);
  acb_add(out, out, t, prec);
  acb_clear(t);
}

}  // namespace

void SpeedChart::offset(acb_t out, const acb_t z, const arb_t x, long prec) const {
  arb_t c1, c0;
  arb_init(c1);
  arb_init(c0);
  arb_set_fmpq(c1, k1.get(), prec);
  arb_sub(c1, c1, x, prec);
  arb_set_fmpq(c0, k0.get(), prec);
  arb_sub(c0, c0, x, prec);
  offset_terms(*this, out, z, c1, c0, prec);
  arb_clear(c1);
  arb_clear(c0);
}

void SpeedChart::offset(acb_t out, const acb_t z, const Rational& x, long prec) const {
  arb_t c1, c0;
  arb_init(c1);
  arb_init(c0);
  arb_set_fmpq(c1, (k1 - x).get(), prec);
  arb_set_fmpq(c0, (k0 - x).get(), prec);
  offset_terms(*this, out, z, c1, c0, prec);
  arb_clear(c1);
  arb_clear(c0);
}

void SpeedChart::offset_local(acb_t out, const acb_t z, const arb_t v, long prec) const {
  acb_t dv;
  arb_t k;
  acb_init(dv);
  arb_init(k);
  acb_set_arb(dv, v);
  denominator(dv, dv, prec);
  acb_sub_arb(out, z, v, prec);
  arb_set_fmpq(k, (k1 - k0).get(), prec);
  arb_mul_fmpz(k, k, chart_a(*this).get(), prec);
  arb_mul_fmpz(k, k, chart_b(*this).get(), prec);
  acb_mul_arb(out, out, k, prec);
  acb_div(out, out, dv, prec);
  arb_clear(k);
  acb_clear(dv);
}

Ball SpeedChart::length_between(const arb_t v0, const arb_t v1, long prec) const {
  acb_t d0, d1;
  acb_init(d0);
  acb_init(d1);
  acb_set_arb(d0, v0);
  denominator(d0, d0, prec);
  acb_set_arb(d1, v1);
  denominator(d1, d1, prec);
  acb_mul(d0, d0, d1, prec);
  Ball out;
  arb_sub(out.get(), v1, v0, prec);
  arb_mul_fmpz(out.get(), out.get(), chart_a(*this).get(), prec);
  arb_mul_fmpz(out.get(), out.get(), chart_b(*this).get(), prec);
  Ball len(length(), prec);
  arb_mul(out.get(), out.get(), len.get(), prec);
  arb_div(out.get(), out.get(), acb_realref(d0), prec);
  acb_clear(d0);
  acb_clear(d1);
  return out;
}

namespace {

// Whether [x, y] (inside c's part) is certainly farther from k0 than a
// quarter of its length, from 128-bit enclosures (undecided: false).
bool far_from_feature(const SpeedChart& c, const RealAlgebraic& x, const RealAlgebraic& y) {
  constexpr long kPrec = 128;
  const Ball bx = x.to_ball(kPrec), by = y.to_ball(kPrec), k0(c.k0, kPrec);
  Ball d, len;
  // the distance from k0 to the nearer end (k0 is an end of the part)
  if (c.k0 < c.k1) arb_sub(d.get(), bx.get(), k0.get(), kPrec);
  else arb_sub(d.get(), k0.get(), by.get(), kPrec);
  arb_sub(len.get(), by.get(), bx.get(), kPrec);
  arb_mul_2exp_si(d.get(), d.get(), 2);
  return arb_gt(d.get(), len.get());
}

}  // namespace

std::vector<SpeedCharts::Span> SpeedCharts::spans(const RealAlgebraic& a, const RealAlgebraic& b) const {
  std::vector<Span> out;
  for (std::size_t j = 0; j < charts.size(); ++j) {
    const SpeedChart& c = charts[j];
    const RealAlgebraic lo(std::min(c.k0, c.k1)), hi(std::max(c.k0, c.k1));
    if (!(a < hi && lo < b)) continue;
    const RealAlgebraic& x = a < lo ? lo : a;
    const RealAlgebraic& y = hi < b ? hi : b;
    if (far_from_feature(c, x, y)) {
      out.push_back(Span{j, x, y, true});
      continue;
    }
    RealAlgebraic u0 = c.local(x), u1 = c.local(y);
    if (u1 < u0) std::swap(u0, u1);
    out.push_back(Span{j, std::move(u0), std::move(u1), false});
  }
  return out;
}

std::shared_ptr<const SpeedCharts> SpeedCharts::build(const Speed& s, const Curve& c) {
  const std::optional<PeakSplit> split = peak_split(s);
  if (!split) return nullptr;
  auto out = std::make_shared<SpeedCharts>();
  const std::vector<Rational>& k = split->knots;
  for (std::size_t j = 0; j + 1 < k.size(); ++j) {
    // from the end with the feature (the power basis is accurate next to 0)
    const bool backwards = split->feature[j + 1] && !split->feature[j];
    const Rational& k0 = backwards ? k[j + 1] : k[j];
    const Rational& k1 = backwards ? k[j] : k[j + 1];
    const Curve part = restrict_to(c, k0, k1);
    SpeedChart chart{k0, k1, std::nullopt, part, Speed(part, s.kind()), Rational(0)};
    chart.w0_exact = chart_w0(chart);
    chart.speed.lazy_->curve.reset();  // no charts of its own
    out->charts.push_back(std::move(chart));
  }
  return out;
}

namespace {

// A chart of the part [k0, k1] of p from its restriction q = p(k0 + (k1 - k0) u)
// and q's speed sq, balanced where balance() balances q (its speed's charts
// still to be switched off by the caller, a friend of Speed).
SpeedChart balanced_chart(const Rational& k0, const Rational& k1, const Curve& q, Speed sq) {
  std::optional<BalancedCurve> bal = balance(q, sq);
  const SpeedKind kind = sq.kind();
  SpeedChart chart{k0, k1, bal, bal ? bal->q : q, bal ? Speed(bal->q, kind) : std::move(sq), Rational(0)};
  chart.w0_exact = chart_w0(chart);
  return chart;
}

// Root scales above 2^-kScaleBits are the part's own (of order 1), and
// scales within 2^(2 kScaleBits) of each other are one; a ladder's rungs
// zoom by 2^kScaleBits.
constexpr double kScaleBits = 16;

// The bits x of the scales 2^-x at which the roots of the speed's factors
// (g, D, the cofactors K_k) lie about the part's feature (u = 0 of its affine
// chart), from their Newton polygons: the breakpoints above kScaleBits,
// grouped where consecutive ones lie within 2 kScaleBits of each other; each
// group as its [first, last].
std::vector<std::pair<double, double>> feature_scales(const Speed& s) {
  std::vector<double> xs;
  NewtonPolygon(s.g()).breakpoints(xs);
  NewtonPolygon(s.denominator()).breakpoints(xs);
  for (const Poly& k : s.cofactors())
    if (!k.is_zero()) NewtonPolygon(k).breakpoints(xs);
  std::sort(xs.begin(), xs.end());
  std::vector<std::pair<double, double>> groups;
  for (const double x : xs) {
    if (!(x > kScaleBits) || !std::isfinite(x)) continue;
    if (!groups.empty() && x - groups.back().second <= 2 * kScaleBits) groups.back().second = x;
    else groups.emplace_back(x, x);
  }
  return groups;
}

}  // namespace

std::shared_ptr<const SpeedCharts> SpeedCharts::balanced(const SpeedCharts& affine, SpeedKind kind) {
  auto out = std::make_shared<SpeedCharts>();
  auto add = [&out](SpeedChart c) {
    c.speed.lazy_->curve.reset();  // no charts of its own
    out->charts.push_back(std::move(c));
  };
  for (const SpeedChart& a : affine.charts) {
    const std::vector<std::pair<double, double>> scales = feature_scales(a.speed);
    if (scales.size() <= 1) {
      add(balanced_chart(a.k0, a.k1, a.curve, a.speed));  // the affine chart's speed is q's
      continue;
    }
    // A feature with several scales (the bump 1/(1 + C x^2): 1/C, 1/sqrt(C),
    // C^(-1/3)): one balancing map spreads one of them and squeezes the
    // others next to u = 1, and a map balancing a cut between two scales
    // brings the outer one next to the cut's far end. So the part is cut
    // into rungs [2^-(j+1)h, 2^-jh] of u (h = kScaleBits, j = 0, 1, ...)
    // down to the deepest scale, and the innermost [0, 2^-Jh]: each zooms by
    // about 2^h and is balanced where balance() does.
    const long deepest = std::lround(scales.back().second);
    const long rungs = std::max(1L, deepest / static_cast<long>(kScaleBits) - 1);
    std::vector<Rational> cuts{Rational(1)};
    for (long j = 1; j <= rungs; ++j) cuts.push_back(pow2(-static_cast<long>(kScaleBits) * j));
    cuts.push_back(Rational(0));
    std::vector<SpeedChart> pieces;  // from the outermost in
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      const Rational &outer = cuts[i], &inner = cuts[i + 1];
      const Curve rung = restrict_to(a.curve, inner, outer);
      pieces.push_back(balanced_chart(a.k0 + (a.k1 - a.k0) * inner, a.k0 + (a.k1 - a.k0) * outer, rung,
                                      Speed(rung, kind)));
    }
    if (a.k0 < a.k1) std::reverse(pieces.begin(), pieces.end());  // in the order of t
    for (SpeedChart& c : pieces) add(std::move(c));
  }
  return out;
}

const SpeedCharts* Speed::charts() const {
  if (!lazy_->curve) return nullptr;
  std::call_once(lazy_->charts_once, [this] { lazy_->charts = SpeedCharts::build(*this, *lazy_->curve); });
  if (!lazy_->charts) return nullptr;
  if (!own_charts_.charts) own_charts_.charts = std::make_shared<const SpeedCharts>(*lazy_->charts);
  return own_charts_.charts.get();
}

const SpeedCharts* Speed::balanced_charts() const {
  if (!charts()) return nullptr;
  std::call_once(lazy_->balanced_once, [this] { lazy_->balanced = SpeedCharts::balanced(*lazy_->charts, kind_); });
  if (!own_charts_.balanced) own_charts_.balanced = std::make_shared<const SpeedCharts>(*lazy_->balanced);
  return own_charts_.balanced.get();
}

}  // namespace uniparam
