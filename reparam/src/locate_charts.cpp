// Locating on a speed with charts (speed_charts.hpp): where sigma has
// narrow features inside (0, 1), locate() and the exact samples run on a
// track whose parameter v takes each part in two halves: the half at the
// part's feature in its balanced chart u (where the feature is spread over
// [0, 1]), the other half on p's own parameter t (where the chart would
// squeeze it next to u = 1). Each point is carried back to t through the
// exact, increasing map v -> t.
#include <arb.h>
#include <flint/fmpq.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "locate_detail.hpp"
#include "speed_charts.hpp"

namespace uniparam::locate_detail {

namespace {

// p's components at the exact t.
std::vector<Ball> exact_components(const Curve& p, const Rational& t, long prec) {
  std::vector<Ball> out;
  for (const RatFunc& x : p.components()) out.emplace_back(x(t), prec);
  return out;
}

// The track: 2 m halves for m charts, half h on v in [h / (2 m), (h + 1) / (2 m)]
// with the local w = 2 m v - h in [0, 1] increasing with t. Half 2j + f of
// chart j: f = 0 the lower half in t, f = 1 the upper; the one at the
// chart's feature end k0 is in its coordinate u (u = u_mid w or u_mid (1 -
// w), u_mid = phi^-1 of the part's midpoint), the other on t (affine in w).
class ChartTrack final : public Track {
 public:
  ChartTrack(const Curve& p, const Speed& s, const SpeedCharts& ch, long max_prec)
      : p_(p), s_(s), ch_(ch), max_prec_(max_prec) {
    for (const SpeedChart& c : ch.charts) {
      const Rational mid = (c.k0 + c.k1) * Rational(1, 2);
      const bool forward = c.k0 < c.k1;
      // phi^-1(mid): m(x) = 1/2 of the affine part; m^-1(1/2) = b / (a + b)
      Rational um(1, 2);
      if (c.bal) um = Rational(c.bal->b) / Rational(c.bal->a + c.bal->b);
      const Rational lo = forward ? c.k0 : c.k1, hi = forward ? c.k1 : c.k0;
      Half lower{&c, forward, um, lo, mid, forward}, upper{&c, !forward, um, mid, hi, forward};
      halves_.push_back(lower);
      halves_.push_back(upper);
    }
  }

  bool identically_zero() const override { return s_.identically_zero(); }
  SpeedKind kind() const override { return s_.kind(); }
  Ball mu(long bits, const Options& opt) const override { return mean_speed(s_, bits, opt); }

  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    Ball total(0);
    const std::size_t n = halves_.size();
    for (std::size_t h = 0; h < n; ++h) {
      const Rational lo(static_cast<long>(h), static_cast<long>(n)), hi(static_cast<long>(h + 1), static_cast<long>(n));
      if (!(a < hi && lo < b)) continue;
      const Rational w0 = local(std::max(a, lo), h), w1 = local(std::min(b, hi), h);
      const Half& H = halves_[h];
      Ball part;
      if (H.chart_side) {
        Rational u0 = H.u(w0), u1 = H.u(w1);
        if (u1 < u0) std::swap(u0, u1);
        part = integrate_speed(H.c->speed, RealAlgebraic(u0), RealAlgebraic(u1), bits, max_prec_);
      } else {
        part = integrate_speed(s_, RealAlgebraic(H.t(w0)), RealAlgebraic(H.t(w1)), bits, max_prec_);
      }
      arb_add(total.get(), total.get(), part.get(), 2 * bits + 64);
    }
    return total;
  }

  double sigma_estimate(const Rational& v) const override {
    const std::size_t h = half_of(v);
    const Half& H = halves_[h];
    const Rational w = local(v, h);
    const double dv = static_cast<double>(halves_.size());  // dw/dv
    if (H.chart_side) return uniparam::sigma_estimate(H.c->speed, H.u(w)) * fmpq_get_d(H.u_mid.get()) * dv;
    return uniparam::sigma_estimate(s_, H.t(w)) * fmpq_get_d((H.hi - H.lo).get()) * dv;
  }

  std::vector<Ball> eval(const Ball& v, long prec) const override {
    if (v.is_exact()) {
      return exact_components(p_, t_exact(mid_rational(v)), prec);
    }
    // the hull over the halves v's ball meets, each on its own curve
    std::vector<Ball> out;
    const std::size_t n = halves_.size();
    for (std::size_t h = 0; h < n; ++h) {
      Ball lo(Rational(static_cast<long>(h), static_cast<long>(n)), prec),
          hi(Rational(static_cast<long>(h + 1), static_cast<long>(n)), prec), w;
      if (arb_lt(v.get(), lo.get()) || arb_gt(v.get(), hi.get())) continue;
      // w = n v - h, clipped to [0, 1]
      arb_mul_ui(w.get(), v.get(), n, prec);
      arb_sub_ui(w.get(), w.get(), h, prec);
      clamp_unit(w.get(), prec);
      const Half& H = halves_[h];
      std::vector<Ball> pt;
      if (H.chart_side) {
        // u = u_mid w, or u_mid (1 - w) where u falls as t grows
        Ball u = w;
        if (!H.u_grows) {
          arb_sub_si(u.get(), w.get(), 1, prec);
          arb_neg(u.get(), u.get());
        }
        arb_mul_fmpz(u.get(), u.get(), H.u_mid.num().get(), prec);
        arb_div_fmpz(u.get(), u.get(), H.u_mid.den().get(), prec);
        pt = H.c->curve.eval(u, prec);
      } else {
        const Rational d = H.hi - H.lo;
        Ball t;
        arb_mul_fmpz(t.get(), w.get(), d.num().get(), prec);
        arb_div_fmpz(t.get(), t.get(), d.den().get(), prec);
        arb_add(t.get(), t.get(), Ball(H.lo, prec).get(), prec);
        pt = p_.eval(t, prec);
      }
      if (out.empty()) out = pt;
      else
        for (std::size_t i = 0; i < out.size(); ++i) arb_union(out[i].get(), out[i].get(), pt[i].get(), prec);
    }
    return out;
  }

  /// An enclosure of t at the track's parameter v in [0, 1] (t increases
  /// with v: the hull of the images of v's ends, each in its half); exact
  /// for an exact v.
  Ball t_of(const Ball& v, long prec) const {
    if (v.is_exact()) return Ball(t_exact(mid_rational(v)), prec);
    arf_t lo, hi;
    arf_init(lo);
    arf_init(hi);
    arb_get_lbound_arf(lo, v.get(), prec);
    arb_get_ubound_arf(hi, v.get(), prec);
    Ball a = t_at(lo, prec), b = t_at(hi, prec), out;
    arf_clear(lo);
    arf_clear(hi);
    arb_union(out.get(), a.get(), b.get(), prec);
    return out;
  }

 private:
  struct Half {
    const SpeedChart* c;
    bool chart_side;  // at the chart's feature end: in u; else on t
    Rational u_mid;
    Rational lo, hi;  // its t-range
    bool u_grows;
    // the chart's u at the local w (chart side): u_mid w where u grows with
    // t (the chart runs forward), u_mid (1 - w) where it runs backwards
    Rational u(const Rational& w) const { return u_grows ? u_mid * w : u_mid * (Rational(1) - w); }
    // t at the local w (t side)
    Rational t(const Rational& w) const { return lo + (hi - lo) * w; }
  };

  std::size_t half_of(const Rational& v) const {
    const long n = static_cast<long>(halves_.size());
    for (long h = 0; h + 1 < n; ++h)
      if (v <= Rational(h + 1, n)) return static_cast<std::size_t>(h);
    return static_cast<std::size_t>(n - 1);
  }
  Rational local(const Rational& v, std::size_t h) const {
    return v * Rational(static_cast<long>(halves_.size())) - Rational(static_cast<long>(h));
  }

  Rational t_exact(const Rational& v) const {
    const std::size_t h = half_of(v);
    const Half& H = halves_[h];
    const Rational w = local(v, h);
    return H.chart_side ? H.c->at(H.u(w)) : H.t(w);
  }

  // t at the exact v (an arf in [0, 1] after clipping)
  Ball t_at(const arf_t v0, long prec) const {
    arf_t v;
    arf_init(v);
    arf_set(v, v0);
    if (arf_sgn(v) < 0) arf_zero(v);
    if (arf_cmp_si(v, 1) > 0) arf_one(v);
    Rational x;
    {
      fmpq_t q;
      fmpq_init(q);
      arf_get_fmpq(q, v);
      fmpq_set(x.get(), q);
      fmpq_clear(q);
    }
    arf_clear(v);
    const std::size_t h = half_of(x);
    const Half& H = halves_[h];
    const Rational w = local(x, h);
    if (!H.chart_side) return Ball(H.t(w), prec);
    // u exact (a rational of the size of w and u_mid), t = phi(u) enclosed
    const Ball ub(H.u(w), prec);
    // phi is increasing or decreasing in u; its enclosure at the ball u is
    // the hull at u's ends
    arf_t l, hh;
    arf_init(l);
    arf_init(hh);
    arb_get_lbound_arf(l, ub.get(), prec);
    arb_get_ubound_arf(hh, ub.get(), prec);
    if (arf_sgn(l) < 0) arf_zero(l);
    if (arf_cmp_si(hh, 1) > 0) arf_one(hh);
    Ball a = H.c->at(l, prec), b = H.c->at(hh, prec), out;
    arb_union(out.get(), a.get(), b.get(), prec);
    arf_clear(l);
    arf_clear(hh);
    return out;
  }

  std::vector<Half> halves_;
  const Curve& p_;
  const Speed& s_;
  const SpeedCharts& ch_;
  long max_prec_;
};

// The digits to ask of the track's v so that t meets `digits`, after a try
// with `asked` gave t with the radius of `t` (as for a balanced curve).
long more_track_digits(const Ball& t, long digits, long asked) {
  const double excess = static_cast<double>(mag_get_d_log2_approx(arb_radref(t.get()))) / 3.3219280948873623 +
                        static_cast<double>(digits);
  return asked + std::max(1L, static_cast<long>(std::ceil(excess)) + 1);
}

}  // namespace

LocateResult locate_charts(const Curve& p, const Speed& s, const SpeedCharts& ch, const Rational& value,
                           LocateTarget target, const Options& opt) {
  const ChartTrack tr(p, s, ch, opt.max_prec);
  Options o = opt;
  for (;;) {
    LocateResult r = locate_on(tr, value, target, o);
    r.at.t = tr.t_of(r.at.t, 2 * digits_to_bits(o.digits) + 64);
    if (meets(r.at.t, opt.digits)) return r;
    o.digits = more_track_digits(r.at.t, opt.digits, o.digits);
    if (digits_to_bits(o.digits) > opt.max_prec) throw_budget("the located parameter", opt);
  }
}

void exact_samples_charts(const Curve& p, const Speed& s, const SpeedCharts& ch, long K, const Options& opt,
                          Ball& mu, const LocatedSink& sink) {
  const ChartTrack tr(p, s, ch, opt.max_prec);
  const long prec = 2 * digits_to_bits(opt.digits) + 64;
  exact_samples_on(tr, K, opt, mu, [&](long k, const LocatedPoint& on_track) {
    LocatedPoint pt = on_track;
    pt.t = tr.t_of(on_track.t, prec);
    // a point whose t misses the digits (where v -> t stretches) is located
    // again alone, with v to more digits
    if (!meets(pt.t, opt.digits)) pt = locate_charts(p, s, ch, Rational(k, K - 1), LocateTarget::Fraction, opt).at;
    sink(k, pt);
  });
}

}  // namespace uniparam::locate_detail
