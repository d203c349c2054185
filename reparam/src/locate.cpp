#include "uniparam/reparam/locate.hpp"

#include <acb.h>
#include <arb.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "arc_model.hpp"
#include "track.hpp"

namespace uniparam {

namespace {

// G(x) - T is decided at rational points x only, from a bracket
//     lo <= t <= hi,  G(lo) in Glo,
// where G(x) = G(lo) + int_lo^x sigma (integrate_speed: split at the zeros
// of sigma inside, each part analytic). Moving lo forward adds the integral
// over [lo, x] to Glo: the parts are disjoint, so their radii add up to at
// most 2^-bits of the integral over what was covered.
struct Bracket {
  Rational lo, hi;
  Ball Glo;
};

// The dyadic rational nearest to y's midpoint with `bits` significant bits.
Rational dyadic_near(const arb_t y, long bits) {
  arf_t m;
  arf_init(m);
  arf_set_round(m, arb_midref(y), bits, ARF_RND_NEAR);
  fmpq_t q;
  fmpq_init(q);
  arf_get_fmpq(q, m);
  Rational r(q);
  fmpq_clear(q);
  arf_clear(m);
  return r;
}

Rational two_pow(long e) {  // 2^e, e may be negative
  fmpq_t q;
  fmpq_init(q);
  fmpq_one(q);
  if (e >= 0) fmpq_mul_2exp(q, q, static_cast<ulong>(e));
  else fmpq_div_2exp(q, q, static_cast<ulong>(-e));
  Rational r(q);
  fmpq_clear(q);
  return r;
}

// floor(x 2^e) / 2^e and ceil(x 2^e) / 2^e.
Rational floor_dyadic(const Rational& x, long e) {
  fmpz_t n;
  fmpz_init(n);
  fmpq_t y;
  fmpq_init(y);
  fmpq_mul_2exp(y, x.get(), static_cast<ulong>(e));
  fmpz_fdiv_q(n, fmpq_numref(y), fmpq_denref(y));
  fmpz_set(fmpq_numref(y), n);
  fmpz_one(fmpq_denref(y));
  fmpq_div_2exp(y, y, static_cast<ulong>(e));
  Rational r(y);
  fmpq_clear(y);
  fmpz_clear(n);
  return r;
}
Rational ceil_dyadic(const Rational& x, long e) { return -floor_dyadic(-x, e); }

// b.meets_digits(digits), first by a cheap sufficient test (rad <=
// 2^-e <= 10^-digits, so rad <= 10^-digits max(1, |mid|)).
bool meets(const Ball& b, long digits) {
  if (!b.is_finite()) return false;
  const long e = static_cast<long>(std::ceil(static_cast<double>(digits) * 3.3219280948873623)) + 1;
  if (mag_cmp_2exp_si(arb_radref(b.get()), -e) <= 0) return true;
  return b.meets_digits(digits);
}

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

// The last decided probe: x, G(x) - T and sigma's estimate there.
struct Seed {
  bool valid = false;
  Rational x;
  Ball v;
  double sx = 0;
};

class Narrower {
 public:
  Narrower(const Track& tr, long bits) : tr_(tr), bits_(bits) {}

  // Narrows b (G(lo) <= T <= G(hi), t unique) to hi - lo <= 2^-wbits.
  // \return false when G(x) - T could not be decided at some x at this
  //         precision (more bits are needed); b stays a valid bracket.
  bool narrow(Bracket& b, const Ball& T, long wbits, Seed seed) {
    const Rational w = two_pow(-wbits), quarter = w / Rational(4);
    const long prec = 2 * bits_ + 64;
    bool newton = seed.valid;
    bool have_undecided = false;
    Rational undecided;
    bool last_newton = false;  // the previous round was a Newton round
    Rational last_width;       // the width before the previous round
    for (long round = 0; round < 8 * (wbits + bits_) + 200; ++round) {
      check_time_budget();
      const Rational width = b.hi - b.lo;
      if (width <= w) return true;
      std::vector<Rational> probes;
      const bool undecided_round = have_undecided;
      if (have_undecided) {
        probes = {undecided - quarter, undecided + quarter};
        have_undecided = false;
      } else if (newton && seed.valid && seed.sx > 0) {
        // y = x - (G(x) - T) / sigma(x) is within e of t when the step's own
        // error (about (sigma'/2 sigma) d^2, with d the step) and the value's
        // radius are below e. One probe, y + e or y - e: the one that, when
        // the prediction holds, moves the end farther from y to within 2e
        // of t. The next round's Newton step starts there and probes the
        // other side, so every integral shrinks the bracket like a Newton
        // step (a missed prediction still moves an end, and a round that
        // does not shrink the bracket fourfold is followed by a bisection).
        arb_t y, d, e, tmp;
        arb_init(y);
        arb_init(d);
        arb_init(e);
        arb_init(tmp);
        arb_set_d(tmp, seed.sx);
        arb_div(d, seed.v.get(), tmp, prec);
        arb_set_fmpq(y, seed.x.get(), prec);
        arb_sub(y, y, d, prec);
        const double dd = std::fabs(arf_get_d(arb_midref(d), ARF_RND_UP));
        const double rd = mag_get_d(arb_radref(d));
        const double ed = std::max({4 * dd * dd, 2 * rd, dd * 0x1p-20});
        const Rational ctr = dyadic_near(y, wbits + 16);
        Rational er = quarter;
        if (std::isfinite(ed) && ed > 0) {
          arb_set_d(e, ed);
          const Rational ed_q = dyadic_near(e, 30);
          if (quarter < ed_q) er = ed_q;
        }
        if (ctr - b.lo < b.hi - ctr) probes = {ctr + er};
        else probes = {ctr - er};
        arb_clear(y);
        arb_clear(d);
        arb_clear(e);
        arb_clear(tmp);
      }
      std::vector<Rational> inside;
      for (const Rational& p : probes)
        if (b.lo < p && p < b.hi) inside.push_back(p);
      if (inside.empty()) inside.push_back((b.lo + b.hi) / Rational(2));
      bool newton_round = newton && !undecided_round;
      for (const Rational& p : inside) {
        if (!(b.lo < p && p < b.hi)) continue;  // the first probe moved an end past it
        Ball piece = tr_.integral(b.lo, p, bits_);
        Ball v;
        arb_add(v.get(), b.Glo.get(), piece.get(), prec);
        arb_sub(v.get(), v.get(), T.get(), prec);
        if (v.certainly_negative()) {
          arb_add(b.Glo.get(), b.Glo.get(), piece.get(), prec);
          b.lo = p;
        } else if (v.certainly_positive()) {
          b.hi = p;
        } else {
          if (undecided_round) return false;
          have_undecided = true;
          undecided = p;
          continue;
        }
        seed.valid = true;
        seed.x = p;
        seed.v = v;
        seed.sx = tr_.sigma_estimate(p);
      }
      // Newton again after a round that shrank the bracket fourfold, or
      // two Newton rounds that did together (one probe moves one end; the
      // other may still be where the search started); one bisection
      // otherwise (at least halving every three rounds).
      const Rational shrunk = b.hi - b.lo;
      const bool shrank = shrunk * Rational(4) <= width || (newton_round && last_newton && shrunk * Rational(4) <= last_width);
      last_newton = newton_round;
      last_width = width;
      newton = !newton_round || shrank;
    }
    return false;
  }

 private:
  const Track& tr_;
  long bits_;
};

Ball unit_ball_of(const Rational& lo, const Rational& hi, long prec) {
  Ball a(lo, prec), b(hi, prec), u;
  arb_union(u.get(), a.get(), b.get(), prec);
  return u;
}

bool points_meet(const std::vector<Ball>& pt, long digits) {
  for (const Ball& x : pt)
    if (!x.meets_digits(digits + 1)) return false;
  return true;
}

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

Seed seed_at(const Track& tr, const Bracket& b, const Ball& T, long prec) {
  Seed sd;
  sd.valid = true;
  sd.x = b.lo;
  arb_sub(sd.v.get(), b.Glo.get(), T.get(), prec);
  sd.sx = tr.sigma_estimate(b.lo);
  return sd;
}

// Narrows b to a t ball meeting digits with p(t) meeting digits too, at
// integral accuracy `bits`. False when more bits are needed.
bool finish_point(const Track& tr, Bracket& b, const Ball& T, long bits, const Options& opt,
                  LocatedPoint& out) {
  const long prec = 2 * bits + 64;
  // First to kLowGoalBits at kLowBits, where the quadrature takes its
  // double-word path: the signs decided there are as certain as any, so
  // the bracket stays valid; only G(lo) is carried at the full precision,
  // by one integral from the old lo. Then usually one Newton pair at the
  // full precision finishes. An undecided sign at the low precision just
  // ends this stage.
  constexpr long kLowBits = 60, kLowGoalBits = 40;
  if (bits > kLowBits + 16 && digits_to_bits(opt.digits) > kLowGoalBits + 8) {
    Bracket low = b;
    Narrower coarse(tr, kLowBits);
    coarse.narrow(low, T, kLowGoalBits, seed_at(tr, low, T, 2 * kLowBits + 64));
    if (b.lo != low.lo) {
      const Ball piece = tr.integral(b.lo, low.lo, bits);
      arb_add(b.Glo.get(), b.Glo.get(), piece.get(), prec);
      b.lo = low.lo;
    }
    b.hi = low.hi;
  }
  Narrower nr(tr, bits);
  for (long wbits = digits_to_bits(opt.digits) + 1; wbits <= bits; wbits += 16) {
    if (!nr.narrow(b, T, wbits, seed_at(tr, b, T, prec))) return false;
    out.t = unit_ball_of(b.lo, b.hi, prec);
    out.point = tr.eval(out.t, prec);
    if (out.t.meets_digits(opt.digits + 1) && points_meet(out.point, opt.digits)) return true;
  }
  return false;
}

// G on [0, 1] as a chain of regions, each either a Taylor model (ArcCell,
// arc_model.hpp) of one segment's speed or, where no model certifies (an
// irrational zero of sigma, a singularity of sigma's continuation too close
// to the real axis), a gap integrated by the track. G at each region's
// start is the sum of the regions before it (disjoint: their radii add up
// to about 2^-bits of the sum, as the chain of integrals does).
class Cover {
 public:
  // Builds the regions at integral accuracy `bits`. False (the cover is
  // not to be used) when the track has no segments, no segment's speed is
  // worth modelling (ArcModeller::worthwhile) or no model certifies.
  bool build(const Track& tr, long bits) {
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
        Rational lo = floor_dyadic(r.lo(), 32), hi = ceil_dyadic(r.hi(), 32);
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
        stretch(tr, mod, sg, A, B, G, add_gap);
      }
    }
    mu_ = G;
    bool models = false;
    for (const Region& r : regions_) models = models || r.model;
    if (!models) return false;
    return true;
  }

  const Ball& mu() const { return mu_; }

  // The point with G(t) = T, from the region holding T. True: pt is
  // certified and meets opt.digits, and br is a bracket for any larger
  // target (the region's start). False: br is a bracket lo <= t <= hi with
  // G(lo) in br.Glo for the track's own narrowing.
  bool locate(const Track& tr, const Ball& T, const Options& opt, LocatedPoint& pt, Bracket& br) {
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

  long bits() const { return bits_; }

 private:
  struct Region {
    Rational lo, hi;      // in the track's parameter
    Ball G0;              // G(lo)
    bool model = false;   // cell holds a model; else a gap
    ArcCell cell;         // in the segment's parameter u
    Rational off, scale;  // t = off + scale u
  };

  // Cells over [A, B] of segment sg's parameter (no zero of sigma inside):
  // as long as possible (doubling after a success, halving after a
  // failure); where cells would have to become very short, or too many
  // (512), or too many attempts fail (more than 12 + twice the cells), the
  // rest is a gap.
  template <class AddGap>
  void stretch(const Track&, const ArcModeller& mod, const Track::Segment& sg, const Rational& A,
               const Rational& B, Ball& G, AddGap& add_gap) {
    const long prec = 2 * bits_ + 64;
    const Rational d = sg.hi - sg.lo;
    const Rational min_w = (B - A) * two_pow(-30);
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

  std::vector<Region> regions_;
  Ball mu_;
  std::size_t cursor_ = 0;
  long bits_ = 0;
};

LocatedPoint exact_point(const Track& tr, long t) {
  LocatedPoint p;
  p.t = Ball(t);
  p.point = tr.eval(p.t, 128);
  return p;
}

// int sigma of one speed (no curve: eval is not available).
class SpeedTrack : public Track {
 public:
  SpeedTrack(const Speed& s, long max_prec) : s_(s), max_prec_(max_prec) {}
  bool identically_zero() const override { return s_.identically_zero(); }
  SpeedKind kind() const override { return s_.kind(); }
  Ball mu(long bits, const Options& opt) const override { return mean_speed(s_, bits, opt); }
  Ball integral(const Rational& a, const Rational& b, long bits) const override {
    return integrate_speed(s_, RealAlgebraic(a), RealAlgebraic(b), bits, max_prec_);
  }
  double sigma_estimate(const Rational& x) const override { return uniparam::sigma_estimate(s_, x); }
  std::vector<Segment> segments() const override { return {Segment{Rational(0), Rational(1), &s_}}; }
  std::vector<Ball> eval(const Ball&, long) const override {
    throw std::logic_error("SpeedTrack::eval: no curve");
  }

 private:
  const Speed& s_;
  long max_prec_;
};

// int sigma and p of one curve.
class CurveTrack final : public SpeedTrack {
 public:
  CurveTrack(const Curve& c, const Speed& s, long max_prec) : SpeedTrack(s, max_prec), c_(c) {}
  std::vector<Ball> eval(const Ball& t, long prec) const override { return c_.eval(t, prec); }

 private:
  const Curve& c_;
};

}  // namespace

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

namespace {

// The point of the balanced curve q = p o m (scaling.hpp) located at s
// carried to p: t = m(s), and p(t) = q(s) as located, except at the ends
// s = 0, 1 (t = s exactly), where p is evaluated as on the unbalanced path
// (q's coefficients may be far larger than p's). Whether t meets `digits`
// is the caller's check (m stretches s where m' > 1).
LocatedPoint mapped_point(const Curve& p, const BalancedCurve& bal, const LocatedPoint& on_q, long digits) {
  LocatedPoint out = on_q;
  if (on_q.t.is_exact() && (arb_is_zero(on_q.t.get()) || arb_is_one(on_q.t.get()))) {
    out.point = p.eval(on_q.t, 128);
    return out;
  }
  out.t = balance_map_ball(bal, on_q.t, 2 * digits_to_bits(digits) + 64);
  return out;
}

// The digits to ask of q's parameter s so that t = m(s) meets `digits`,
// after a try with `asked` gave t with the radius of `t`.
long more_digits(const Ball& t, long digits, long asked) {
  const double excess = static_cast<double>(mag_get_d_log2_approx(arb_radref(t.get()))) / 3.3219280948873623 +
                        static_cast<double>(digits);
  return asked + std::max(1L, static_cast<long>(std::ceil(excess)) + 1);
}

// locate() on the balanced curve: G_q(s) = G_p(m(s)) (sigma_q ds = sigma_p
// dt), so t = m(s) for q's s, with s to more digits where m stretches it.
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

}  // namespace

LocateResult locate(const Curve& c, const Speed& s, const Rational& value, LocateTarget target,
                    const Options& opt) {
  validate(opt);
  // A speed concentrated next to one end (huge coefficients, weights
  // growing geometrically): located on the balanced curve q = p o m.
  if (const std::optional<BalancedCurve> bal = balance(c, s))
    return locate_balanced(c, *bal, Speed(bal->q, s.kind()), value, target, opt);
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

void exact_samples_each(const Curve& c, const Speed& s, long K, const Options& opt, Ball& mu,
                        const LocatedSink& sink) {
  validate(opt);
  if (const std::optional<BalancedCurve> bal = balance(c, s)) {
    // On the balanced curve q = p o m, each point carried by t = m(s); a
    // point whose t misses the digits (where m stretches s) is located
    // again alone, with s to more digits.
    const Speed sq(bal->q, s.kind());
    exact_samples_on(CurveTrack(bal->q, sq, opt.max_prec), K, opt, mu, [&](long k, const LocatedPoint& on_q) {
      LocatedPoint pt = mapped_point(c, *bal, on_q, opt.digits);
      if (!meets(pt.t, opt.digits)) pt = locate_balanced(c, *bal, sq, Rational(k, K - 1), LocateTarget::Fraction, opt).at;
      sink(k, pt);
    });
    return;
  }
  exact_samples_on(CurveTrack(c, s, opt.max_prec), K, opt, mu, sink);
}

void exact_samples_on(const Track& tr, long K, const Options& opt, Ball& mu, const LocatedSink& sink) {
  if (K < 2 || K > 1000000)
    throw InvalidArgument("the number of points must be between 2 and 1000000, got " + std::to_string(K));
  check_not_zero_speed(tr.identically_zero());
  check_digits_fit(opt);
  // The chain's precision: every G(lo) is a sum of disjoint integrals, so
  // its radius stays below about 2^-bits mu whatever K, as does the
  // targets' k mu / (K - 1). 12 bits above the goal width leave t's
  // uncertainty 2^-bits mu / sigma(t) below it where sigma(t) > mu / 2^10,
  // and keep the quadrature's double-word path for up to 16 digits; where
  // a point needs more, the chain goes on at more bits.
  long bits = digits_to_bits(opt.digits) + 12;
  auto compute_mu = [&]() {
    for (;; bits = next_bits(bits)) {
      if (bits > opt.max_prec) throw_budget("the exact samples", opt);
      mu = tr.mu(bits, opt);
      if (mu.meets_digits(opt.digits + 1)) return;
    }
  };
  // Taylor models of G where they certify (Cover); each point found in
  // its model by one interval Newton step, else (no segments, a gap, a
  // target too close to a region's end, a model not accurate enough) by the
  // chain of certified integrals below, from the bracket the cover gives.
  Cover cover;
  const bool use_cover = cover.build(tr, bits) && cover.mu().meets_digits(opt.digits + 1);
  if (use_cover) mu = cover.mu();
  else compute_mu();
  sink(0, exact_point(tr, 0));
  Bracket b{Rational(0), Rational(1), Ball(0)};
  long glo_bits = bits;  // b.Glo's accuracy (the cover's brackets carry the cover's)
  for (long k = 1; k + 1 < K; ++k) {
    // t_k > t_{k-1} >= lo: the previous bracket's lower end and G there
    // start this point; hi = 1 holds as G(1) = mu > k mu / (K - 1).
    LocatedPoint pt;
    b.hi = Rational(1);
    for (bool first = true;; first = false) {
      check_time_budget();
      const long prec = 2 * bits + 64;
      Ball T;
      arb_mul_si(T.get(), mu.get(), k, prec);
      arb_div_si(T.get(), T.get(), K - 1, prec);
      if (first && use_cover) {
        Bracket cb;
        const bool found = cover.locate(tr, T, opt, pt, cb);
        // the larger of the two lower ends (both <= t_k)
        if (b.lo < cb.lo) {
          b.lo = cb.lo;
          b.Glo = cb.Glo;
          glo_bits = cover.bits();
        }
        if (found) break;
        b.hi = cb.hi;
      }
      if (glo_bits < bits) {  // G(lo) again at the chain's precision
        b.Glo = b.lo.is_zero() ? Ball(0) : tr.integral(Rational(0), b.lo, bits);
        glo_bits = bits;
      }
      if (finish_point(tr, b, T, bits, opt, pt)) break;
      // More bits: mu and G(lo) again at the higher precision (the bracket
      // holds at any). The cover stays: its points are certified whatever
      // the chain's precision (and checked against the digits asked).
      bits = next_bits(bits);
      compute_mu();
      b.Glo = b.lo.is_zero() ? Ball(0) : tr.integral(Rational(0), b.lo, bits);
      glo_bits = bits;
      b.hi = Rational(1);
    }
    sink(k, pt);
  }
  sink(K - 1, exact_point(tr, 1));
}

ExactSamples exact_samples(const Curve& c, const Speed& s, long K, const Options& opt) {
  ExactSamples out;
  exact_samples_each(c, s, K, opt, out.mu, [&out](long, const LocatedPoint& p) { out.points.push_back(p); });
  return out;
}

ArcFraction::ArcFraction(const Speed& s, long bits, const Options& opt)
    : track_(std::make_shared<SpeedTrack>(s, opt.max_prec)), bits_(bits), max_prec_(opt.max_prec), last_(0),
      G_last_(0) {
  check_not_zero_speed(s.identically_zero());
  mu_ = mean_speed(s, bits, opt);
}

ArcFraction::ArcFraction(const CompositeCurve& c, const std::vector<Speed>& speeds, long bits, const Options& opt)
    : track_(composite_track(c, speeds, opt.max_prec)), bits_(bits), max_prec_(opt.max_prec), last_(0), G_last_(0) {
  check_not_zero_speed(track_->identically_zero());
  mu_ = track_->mu(bits, opt);
}

Ball ArcFraction::G(const Rational& x) {
  const long prec = 2 * bits_ + 64;
  if (x == last_) return G_last_;
  Ball g;
  if (last_ < x) {
    const Ball piece = track_->integral(last_, x, bits_);
    arb_add(g.get(), G_last_.get(), piece.get(), prec);
  } else {
    const Ball piece = track_->integral(x, last_, bits_);
    arb_sub(g.get(), G_last_.get(), piece.get(), prec);
  }
  last_ = x;
  G_last_ = g;
  return g;
}

Ball ArcFraction::at(const Ball& t) {
  if (!t.is_finite()) throw DomainError("ArcFraction::at: the parameter's enclosure is not finite");
  const long prec = 2 * bits_ + 64;
  Ball tc = t;
  clamp_unit(tc.get(), prec);
  arf_t lo, hi;
  arf_init(lo);
  arf_init(hi);
  arb_get_lbound_arf(lo, tc.get(), prec);
  arb_get_ubound_arf(hi, tc.get(), prec);
  fmpq_t q;
  fmpq_init(q);
  arf_get_fmpq(q, lo);
  Rational ql(q);
  arf_get_fmpq(q, hi);
  Rational qh(q);
  fmpq_clear(q);
  arf_clear(lo);
  arf_clear(hi);
  if (ql.sign() < 0) ql = Rational(0);
  if (Rational(1) < qh) qh = Rational(1);
  // G is increasing: G(t) lies in [G(ql), G(qh)] (G(qh) last, so that the
  // next, larger t starts from the upper end).
  const Ball gl = G(ql), gh = G(qh);
  Ball a, b, u;
  arb_div(a.get(), gl.get(), mu_.get(), prec);
  arb_div(b.get(), gh.get(), mu_.get(), prec);
  arb_union(u.get(), a.get(), b.get(), prec);
  return u;
}

Ball fraction_deviation(const Speed& s, const Reparameterization& r, long K, const Options& opt) {
  validate(opt);
  if (K < 2 || K > 1000000)
    throw InvalidArgument("the number of points must be between 2 and 1000000, got " + std::to_string(K));
  check_not_zero_speed(s.identically_zero());
  const long bits = digits_to_bits(opt.digits) + 8;
  const long prec = 2 * bits + 64;
  ArcFraction frac(s, bits, opt);
  Ball worst(0);
  for (long k = 0; k < K; ++k) {
    check_time_budget();
    const Ball sk(Rational(k, K - 1), prec);
    Ball d = frac.at(r.eval_r(sk, prec));
    arb_sub(d.get(), d.get(), sk.get(), prec);
    arb_abs(d.get(), d.get());
    arb_max(worst.get(), worst.get(), d.get(), prec);
  }
  return worst;
}

}  // namespace uniparam
