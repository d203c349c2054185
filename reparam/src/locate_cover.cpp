// The Taylor-model cover of G on [0, 1] (regions of ArcCell models and
// integrated gaps, locate_detail.hpp), and a point located in its model by
// one interval Newton step (docs/locate.md, "Taylor models").
#include <arb.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "locate_detail.hpp"

namespace uniparam::locate_detail {

bool meets(const Ball& b, long digits) {
  if (!b.is_finite()) return false;
  const long e = static_cast<long>(std::ceil(static_cast<double>(digits) * 3.3219280948873623)) + 1;
  if (mag_cmp_2exp_si(arb_radref(b.get()), -e) <= 0) return true;
  return b.meets_digits(digits);
}

namespace {

// N within [x - rho, x + rho] (x = x0's exact double midpoint), or
// within *X when given (a clipped interval).
bool inside(const Ball& N, const Ball& x0, double rho, const Ball* X) {
  if (X) return arb_contains(X->get(), N.get());
  if (!N.is_finite()) return false;
  arf_t d;
  arf_init(d);
  arf_sub(d, arb_midref(N.get()), arb_midref(x0.get()), 53, ARF_RND_UP);  // |d| rounded up
  const double dist = std::fabs(arf_get_d(d, ARF_RND_UP));
  arf_clear(d);
  const double reach = std::nextafter(dist + mag_get_d(arb_radref(N.get())), INFINITY);
  return reach <= rho;
}

}  // namespace

// Cells over [A, B] of segment sg's parameter (no zero of sigma inside):
// as long as possible (doubling after a success, halving after a
// failure); where cells would have to become very short, or too many
// (512), or too many attempts fail (more than 12 + twice the cells), the
// rest is a gap.
template <class AddGap>
void Cover::stretch(const ArcModeller& mod, const Track::Segment& sg, const Rational& A, const Rational& B,
                    Ball& G, AddGap& add_gap) {
  const long prec = 2 * bits_ + 64;
  const Rational d = sg.hi - sg.lo;
  const Rational min_w = (B - A) * pow2(-30);
  Rational u = A, w = B - A;
  int cells = 0, failures = 0;
  while (u < B) {
    check_time_budget();
    if (B - u < w) w = B - u;
    Region r;
    if (cells < 512 && failures < 64 && mod.build(u, u + w, bits_, r.cell)) {
      r.lo = sg.lo + d * u;
      r.hi = sg.lo + d * (u + w);
      r.G0 = G;
      r.model = true;
      r.off = sg.lo;
      r.scale = d;
      arb_add(G.get(), G.get(), r.cell.integral.get(), prec);
      regions_.push_back(std::move(r));
      u = u + w;
      w = w * Rational(2);
      ++cells;
      continue;
    }
    if (cells >= 512 || ++failures > 12 + 2 * cells || w <= min_w) {
      add_gap(u, B);
      return;
    }
    w = w / Rational(2);
  }
}

bool Cover::build(const Track& tr, long bits) {
  const std::vector<Track::Segment> segs = tr.segments();
  if (segs.empty()) return false;
  std::vector<std::unique_ptr<ArcModeller>> mods;
  bool any = false;
  for (const Track::Segment& sg : segs) {
    mods.push_back(sg.speed->identically_zero() ? nullptr : std::make_unique<ArcModeller>(*sg.speed));
    any = any || (mods.back() && mods.back()->worthwhile());
  }
  if (!any) return false;
  bits_ = bits;
  const long prec = 2 * bits + 64;
  Ball G(0);
  for (std::size_t si = 0; si < segs.size(); ++si) {
    const Track::Segment& sg = segs[si];
    const Rational d = sg.hi - sg.lo;
    auto global = [&](const Rational& u) { return sg.lo + d * u; };
    auto add_gap = [&](const Rational& a, const Rational& b) {
      Region r;
      r.lo = global(a);
      r.hi = global(b);
      r.G0 = G;
      const Ball I = tr.integral(r.lo, r.hi, bits);
      arb_add(G.get(), G.get(), I.get(), prec);
      regions_.push_back(std::move(r));
    };
    if (sg.speed->identically_zero()) {
      add_gap(Rational(0), Rational(1));
      continue;
    }
    const ArcModeller& mod = *mods[si];
    if (!mod.worthwhile()) {
      add_gap(Rational(0), Rational(1));
      continue;
    }
    // The stretches between zeros of sigma: a rational zero is a cell
    // boundary (the continuation of sigma is analytic across it, only
    // its sign flips there), an irrational one lies in a short gap.
    std::vector<std::pair<Rational, Rational>> gaps;
    std::vector<Rational> pts = {Rational(0), Rational(1)};
    for (const SpeedZero& z : sg.speed->zeros()) {
      if (z.t.is_rational()) {
        pts.push_back(z.t.rational());
        continue;
      }
      // [lo, hi] around the zero, dyadic with 32 fractional bits (the
      // isolating interval may have been refined far, to huge rationals;
      // an integral over a gap of width 2^-200 around a zero would be
      // too small to certify to a relative accuracy)
      RealAlgebraic r = z.t;
      r.refine(30);
      Rational lo = grid_floor(r.lo(), -32), hi = -grid_floor(-r.hi(), -32);
      if (lo.sign() < 0) lo = Rational(0);
      if (Rational(1) < hi) hi = Rational(1);
      gaps.emplace_back(lo, hi);
      pts.push_back(lo);
      pts.push_back(hi);
    }
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    std::size_t gap_from = 0;
    bool in_gap = false;
    for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
      const Rational &A = pts[i], &B = pts[i + 1];
      const Rational mid = (A + B) / Rational(2);
      bool gap = false;
      for (const auto& g : gaps) gap = gap || (g.first < mid && mid < g.second);
      if (gap) {
        if (!in_gap) gap_from = i;
        in_gap = true;
        if (i + 2 < pts.size()) continue;
      }
      if (in_gap) {
        add_gap(pts[gap_from], gap ? B : A);
        in_gap = false;
        if (gap) continue;
      }
      stretch(mod, sg, A, B, G, add_gap);
    }
  }
  mu_ = G;
  bool models = false;
  for (const Region& r : regions_) models = models || r.model;
  if (!models) return false;
  return true;
}

bool Cover::locate(const Track& tr, const Ball& T, const Options& opt, LocatedPoint& pt, Bracket& br) {
  const long prec = 2 * bits_ + 64;
  const std::size_t n = regions_.size();
  auto G0 = [&](std::size_t i) -> const Ball& { return i < n ? regions_[i].G0 : mu_; };
  auto below = [&](const Ball& x, const Ball& y) {  // x < y certainly
    Ball d;
    arb_sub(d.get(), y.get(), x.get(), prec);
    return d.certainly_positive();
  };
  while (cursor_ + 1 < n && below(G0(cursor_ + 1), T)) ++cursor_;
  const std::size_t i = cursor_;
  if (!(below(G0(i), T) && below(T, G0(i + 1)) && regions_[i].model)) {
    std::size_t j = i, m = i + 1;
    while (j > 0 && !below(G0(j), T)) --j;
    while (m < n && !below(T, G0(m))) ++m;
    br = Bracket{regions_[j].lo, m < n ? regions_[m].lo : Rational(1), regions_[j].G0};
    return false;
  }
  const Region& r = regions_[i];
  br = Bracket{r.lo, r.hi, r.G0};
  const ArcCell& cl = r.cell;
  const long wp = bits_ + 40;
  // Newton's guess in double on P(x) - P(xa) = T - G(a).
  Ball rhs;
  arb_sub(rhs.get(), T.get(), r.G0.get(), wp);
  const double xa = arf_get_d(arb_midref(cl.xa.get()), ARF_RND_NEAR);
  const double xb = arf_get_d(arb_midref(cl.xb.get()), ARF_RND_NEAR);
  auto horner = [](const std::vector<double>& p, double x) {
    double v = 0;
    for (std::size_t j = p.size(); j-- > 0;) v = v * x + p[j];
    return v;
  };
  const double pa = horner(cl.Pd, xa), pb = horner(cl.Pd, xb);
  const double target = arf_get_d(arb_midref(rhs.get()), ARF_RND_NEAR) + pa;
  double x = xa + (target - pa) / (pb - pa) * (xb - xa);
  for (int it = 0; it < 40; ++it) {
    const double sx = horner(cl.Td, x);
    if (!(sx > 0)) break;
    const double dx = (horner(cl.Pd, x) - target) / sx;
    x = std::min(xb, std::max(xa, x - dx));
    if (std::fabs(dx) <= 1e-17 * (std::fabs(x) + (xb - xa))) break;
  }
  if (!std::isfinite(x)) return false;
  Ball x0;
  arb_set_d(x0.get(), x);
  {  // x within the cell (xa, xb may be inexact balls): the model holds there only
    Ball lo_d, hi_d;
    arb_sub(lo_d.get(), x0.get(), cl.xa.get(), wp);
    arb_sub(hi_d.get(), cl.xb.get(), x0.get(), wp);
    if (!(arb_is_nonnegative(lo_d.get()) && arb_is_nonnegative(hi_d.get()))) return false;
  }
  // One interval Newton step on X = [x - rho, x + rho] (within the cell):
  // N = x - F(x) / F'(X) inside X proves the root t - c in N (G is
  // increasing on the cell, the root is unique). F'(X) = sigma(X) is
  // within sigma(x) +- rho L.
  Ball F;
  double sx, sr;
  if (!cl.at_double(x, F, sx, sr)) return false;
  arb_sub(F.get(), F.get(), rhs.get(), wp);
  double rho = 2 * (std::fabs(arf_get_d(arb_midref(F.get()), ARF_RND_UP)) + mag_get_d(arb_radref(F.get()))) /
               std::max(sx, 1e-300);
  rho = std::max(rho, 1e-30 * (xb - xa));
  for (int attempt = 0; attempt < 4; ++attempt, rho *= 16) {
    // X within [xa, xb]: the model's bounds hold there only (checked on
    // the balls; where X sticks out, it is clipped to the cell).
    Ball X;
    {
      arf_t lo, hi, t;
      arf_init(lo);
      arf_init(hi);
      arf_init(t);
      arf_set_d(t, rho);
      arf_sub(lo, arb_midref(x0.get()), t, 64, ARF_RND_DOWN);
      arf_add(hi, arb_midref(x0.get()), t, 64, ARF_RND_UP);
      arb_set_interval_arf(X.get(), lo, hi, wp);
      arf_clear(lo);
      arf_clear(hi);
      arf_clear(t);
    }
    bool clipped = false;
    {
      Ball lo_d, hi_d;
      arb_sub(lo_d.get(), X.get(), cl.xa.get(), wp);
      arb_sub(hi_d.get(), cl.xb.get(), X.get(), wp);
      if (!(arb_is_nonnegative(lo_d.get()) && arb_is_nonnegative(hi_d.get()))) {
        clipped = true;
        Ball cellb;
        arb_union(cellb.get(), cl.xa.get(), cl.xb.get(), wp);
        if (!arb_intersection(X.get(), X.get(), cellb.get(), wp)) return false;
        arb_sub(lo_d.get(), X.get(), cl.xa.get(), wp);
        arb_sub(hi_d.get(), cl.xb.get(), X.get(), wp);
        if (!(arb_is_nonnegative(lo_d.get()) && arb_is_nonnegative(hi_d.get()))) return false;
        if (!arb_contains(X.get(), x0.get())) return false;  // the step's point is in X
      }
    }
    // sigma on X: within sx +- (sr + 2 rho L) (|x' - x| <= 2 rho on X,
    // whose ends were rounded outward)
    const double dr = std::nextafter(std::nextafter(sr + std::nextafter(2 * rho * cl.L, INFINITY), INFINITY), INFINITY);
    if (!(sx - dr > 0) || !std::isfinite(dr)) continue;
    Ball dF;
    arb_set_d(dF.get(), sx);
    {
      mag_t m;
      mag_init(m);
      mag_set_d(m, dr);
      arb_add_error_mag(dF.get(), m);
      mag_clear(m);
    }
    if (!dF.certainly_positive()) continue;
    Ball N;
    arb_div(N.get(), F.get(), dF.get(), wp);
    arb_sub(N.get(), x0.get(), N.get(), wp);
    if (!inside(N, x0, rho, clipped ? &X : nullptr)) continue;
    // t = lo_j + d (c + N)
    Ball t(cl.c, wp);
    arb_add(t.get(), t.get(), N.get(), wp);
    if (r.scale != Rational(1)) {
      const Ball sc(r.scale, prec);
      arb_mul(t.get(), t.get(), sc.get(), prec);
    }
    if (!r.off.is_zero()) {
      const Ball of(r.off, prec);
      arb_add(t.get(), t.get(), of.get(), prec);
    }
    if (!meets(t, opt.digits + 1)) return false;
    pt.t = t;
    pt.point = tr.eval(t, wp);
    for (const Ball& v : pt.point)
      if (!meets(v, opt.digits + 1)) return false;
    br.hi = Rational(1);
    return true;
  }
  return false;
}

}  // namespace uniparam::locate_detail
