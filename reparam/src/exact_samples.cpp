// K points at exactly equal steps of G: the Taylor-model cover where it
// certifies, the chain of certified integrals from the previous point's
// bracket elsewhere.
#include <arb.h>

#include <optional>
#include <string>

#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "locate_detail.hpp"

namespace uniparam {

using namespace locate_detail;

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
  if (const SpeedCharts* ch = s.balanced_charts()) {
    exact_samples_charts(c, s, *ch, K, opt, mu, sink);
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

}  // namespace uniparam
