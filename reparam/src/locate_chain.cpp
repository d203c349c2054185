// The chain of certified integrals: a bracket lo <= t <= hi of the unique t
// with G(t) = T, narrowed by safeguarded Newton probes whose signs of
// G(x) - T are decided by certified integrals from lo (docs/locate.md).
#include <arb.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "uniparam/core/budget.hpp"
#include "locate_detail.hpp"

namespace uniparam::locate_detail {

namespace {

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
    const Rational w = pow2(-wbits), quarter = w / Rational(4);
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

Seed seed_at(const Track& tr, const Bracket& b, const Ball& T, long prec) {
  Seed sd;
  sd.valid = true;
  sd.x = b.lo;
  arb_sub(sd.v.get(), b.Glo.get(), T.get(), prec);
  sd.sx = tr.sigma_estimate(b.lo);
  return sd;
}

}  // namespace

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
    out.t = interval_ball(b.lo, b.hi, prec);
    out.point = tr.eval(out.t, prec);
    if (out.t.meets_digits(opt.digits + 1) && all_meet_digits(out.point, opt.digits + 1)) return true;
  }
  return false;
}

}  // namespace uniparam::locate_detail
