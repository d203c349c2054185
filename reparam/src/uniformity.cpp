#include "uniparam/reparam/uniformity.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/scaling.hpp"
#include "speed_charts.hpp"

namespace uniparam {

void validate(const Options& o) {
  if (o.digits < 1 || o.digits > kMaxEngineDigits)
    throw InvalidArgument("--digits must be between 1 and " + std::to_string(kMaxDigits) + ", got " +
                          std::to_string(o.digits));
  if (o.max_prec < 64 || o.max_prec > (1L << 24))
    throw InvalidArgument("--max-prec must be between 64 and 16777216 bits, got " + std::to_string(o.max_prec));
  if (o.max_degree < 1)
    throw InvalidArgument("--max-degree must be positive, got " + std::to_string(o.max_degree));
}

long digits_to_bits(long digits) { return static_cast<long>(std::ceil(digits * 3.3219280948873623)) + 8; }

long default_max_prec(long digits) { return std::max(Options{}.max_prec, 2 * digits_to_bits(digits)); }

long speed_scale_bits(const Speed& s) { return s.scale_bits(); }

long speed_coefficient_bits(const Speed& s) {
  long b = std::max(s.denominator().max_bits(), s.g().max_bits());
  for (const Poly& k : s.cofactors()) b = std::max(b, k.max_bits());
  return b;
}

namespace {

// The weight 1 / m'(s) = (a s + b (1 - s))^2 / (a b) of a balanced curve's
// integral of sigma^2 (scaling.hpp).
struct SquareWeight {
  Integer a, b;
};

// out = (a z + b (1 - z))^2 / (a b): a sum of two positive terms on [0, 1]
// (no cancellation, whatever the sizes of a and b).
void eval_weight(acb_t out, const acb_t z, const SquareWeight& w, long prec) {
  acb_t t;
  acb_init(t);
  acb_neg(t, z);
  acb_add_si(t, t, 1, prec);
  acb_mul_fmpz(t, t, w.b.get(), prec);
  acb_mul_fmpz(out, z, w.a.get(), prec);
  acb_add(out, out, t, prec);
  acb_mul(out, out, out, prec);
  acb_div_fmpz(out, out, w.a.get(), prec);
  acb_div_fmpz(out, out, w.b.get(), prec);
  acb_clear(t);
}

// The integral of sigma over one piece [a, b] free of zeros of sigma inside
// and, with square, that of sigma^2 in the same quadrature (sigma squared at
// every point: one evaluation of the speed for both), with the
// weight on sigma^2 where given, to relative accuracy 2^-rel_goal_bits or
// absolute 2^-abs_goal_bits (0: none) of the scaled integrands below; on
// s's own parameter (not its charts).
std::vector<Ball> integrate_speed_piece_direct(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b,
                                               long rel_goal_bits, long max_prec, bool square, long abs_goal_bits,
                                               const SquareWeight* weight, const long* exps) {
  // The integrands times 2^-exps[k] (exact), so that a total of about
  // 2^exps[k] becomes about 1 and one absolute goal fits both.
  const long e0 = exps ? exps[0] : 0, e1 = exps && square ? exps[1] : 0;
  const Speed::PieceSigns sign = s.piece_signs(a, b);
  // Every narrow real point (nodes, the start's probes, the ends) goes to
  // node_fast below first; f gets the points it refused and the wide balls,
  // so eval's own double-word attempt is skipped (it would refuse too).
  // With a weight, every point goes to f (the double-word path has no weight).
  Integrand f = [&s, sign, square, weight, e0, e1](acb_ptr out, const acb_t z, bool analytic, long prec) {
    s.eval(out, z, sign, analytic, prec, weight != nullptr);
    if (square) acb_mul(out + 1, out, out, prec);
    if (square && weight) {
      acb_t w;
      acb_init(w);
      eval_weight(w, z, *weight, prec);
      acb_mul(out + 1, out + 1, w, prec);
      acb_clear(w);
    }
    acb_mul_2exp_si(out, out, -e0);
    if (square) acb_mul_2exp_si(out + 1, out + 1, -e1);
  };
  QuadratureOptions qo;
  qo.rel_goal_bits = rel_goal_bits;
  qo.abs_goal_bits = abs_goal_bits;
  qo.max_prec = max_prec;
  qo.scale_bits = speed_scale_bits(s);
  qo.what = "the integral of the " + to_string(s.kind()) + " speed" + (square ? " and of its square" : "");
  qo.singularity_hints = s.singularity_hints(false);
  // Double words scale exactly by 2^e for |e| <= 64 only.
  if (!weight && std::abs(e0) <= 64 && std::abs(e1) <= 64)
    qo.node_fast = [&s, sign, square, e0, e1](DDBall* out, const DDBall& t, long prec) {
      if (!s.eval_dd(out[0], t, sign, false, prec)) return false;
      if (square) out[1] = dd_mul_2exp(dd_mul(out[0], out[0]), static_cast<int>(-e1));
      out[0] = dd_mul_2exp(out[0], static_cast<int>(-e0));
      return dd_is_finite(out[0]) && (!square || dd_is_finite(out[1]));
    };
  std::vector<Ball> r = integrate_many(f, square ? 2 : 1, a, b, qo);
  arb_mul_2exp_si(r[0].get(), r[0].get(), e0);
  if (square) arb_mul_2exp_si(r[1].get(), r[1].get(), e1);
  return r;
}

// integrate_speed_piece_direct, where s has charts (speed_charts.hpp) span
// by span in them, as a balanced curve's integrals are taken (the weight
// is then the chart's: weight must be null).
std::vector<Ball> integrate_speed_piece(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b,
                                        long rel_goal_bits, long max_prec, bool square = false,
                                        long abs_goal_bits = 0, const SquareWeight* weight = nullptr,
                                        const long* exps = nullptr) {
  const SpeedCharts* ch = weight ? nullptr : s.charts();
  if (!ch) return integrate_speed_piece_direct(s, a, b, rel_goal_bits, max_prec, square, abs_goal_bits, weight, exps);
  const long e0 = exps ? exps[0] : 0, e1 = exps && square ? exps[1] : 0;
  const std::vector<SpeedCharts::Span> spans = ch->spans(a, b);
  // the spans' absolute errors add up
  const long extra = abs_goal_bits ? static_cast<long>(std::ceil(std::log2(static_cast<double>(spans.size())))) : 0;
  const long abs_bits = abs_goal_bits ? abs_goal_bits + extra : 0;
  std::vector<Ball> total(square ? 2 : 1, Ball(0));
  const long prec = 2 * rel_goal_bits + 64;
  for (const SpeedCharts::Span& sp : spans) {
    std::vector<Ball> r;
    if (sp.plain) {
      const long pe[2] = {e0, e1};
      r = integrate_speed_piece_direct(s, sp.u0, sp.u1, rel_goal_bits, max_prec, square, abs_bits, nullptr, pe);
    } else {
      const SpeedChart& c = ch->charts[sp.chart];
      const Rational len = c.length();
      // int sigma^2 dt = int sigma_phi^2 / |phi'| du: the weight 1 / m' of
      // the balanced chart's integrand over |k1 - k0|, integrated to
      // |k1 - k0| times the part's total (its scale too, within a factor 2)
      const long len_exp = static_cast<long>(fmpz_bits(len.num().get())) - static_cast<long>(fmpz_bits(len.den().get()));
      const long ce[2] = {e0, e1 + len_exp};
      const SquareWeight cw{c.bal ? c.bal->a : Integer(1), c.bal ? c.bal->b : Integer(1)};
      r = integrate_speed_piece_direct(c.speed, sp.u0, sp.u1, rel_goal_bits, max_prec, square, abs_bits,
                                       c.bal ? &cw : nullptr, ce);
      if (square) {
        arb_mul_fmpz(r[1].get(), r[1].get(), len.den().get(), prec);
        arb_div_fmpz(r[1].get(), r[1].get(), len.num().get(), prec);
      }
    }
    for (std::size_t k = 0; k < total.size(); ++k) arb_add(total[k].get(), total[k].get(), r[k].get(), prec);
  }
  return total;
}

// a, the zeros of sigma strictly inside (a, b), b.
std::vector<RealAlgebraic> speed_piece_ends(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b) {
  std::vector<RealAlgebraic> ends{a};
  for (const auto& z : s.zeros())
    if (a < z.t && z.t < b) ends.push_back(z.t);
  ends.push_back(b);
  return ends;
}

// Equal parts of [0, 1] the integrals are split into, as independent tasks
// for the worker threads: 8 from degree 100 of sigma^2's numerator
// g^2 sum K^2 (in the factored form; a long, wavy curve: each part costs far
// more than the split, and 8 parts balance two workers), else 1.
// A function of the curve alone, never of the thread count, so results do
// not depend on the threads.
long split_parts(const Speed& s) {
  if (s.identically_zero()) return 1;
  long k = 0;  // deg sum K^2 = 2 max deg K (the leading terms add, squares)
  for (const auto& c : s.cofactors()) k = std::max(k, c.degree());
  return 2 * s.g().degree() + 2 * k >= 100 ? 8 : 1;
}

}  // namespace

namespace detail {

std::vector<RealAlgebraic> with_split_points(std::vector<RealAlgebraic> ends, long parts) {
  const RealAlgebraic lo = ends.front(), hi = ends.back();  // ends grows unsorted below
  for (long j = 1; j < parts; ++j) {
    const RealAlgebraic q(Rational(j, parts));
    if (!(lo < q && q < hi)) continue;
    bool present = false;
    for (const auto& e : ends) present = present || e == q;
    if (!present) ends.push_back(q);
  }
  std::sort(ends.begin(), ends.end(), [](const RealAlgebraic& x, const RealAlgebraic& y) { return x < y; });
  return ends;
}

}  // namespace detail

Ball integrate_speed(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b, long rel_goal_bits,
                     long max_prec) {
  Ball total(0);
  if (s.identically_zero() || a == b) return total;
  const std::vector<RealAlgebraic> ends = speed_piece_ends(s, a, b);
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) {
    const Ball piece = integrate_speed_piece(s, ends[i], ends[i + 1], rel_goal_bits, max_prec).front();
    arb_add(total.get(), total.get(), piece.get(), 2 * rel_goal_bits + 64);
  }
  return total;
}

Ball integrate_speed_squared(const Speed& s, const RealAlgebraic& a, const RealAlgebraic& b,
                             long rel_goal_bits, long max_prec) {
  if (s.identically_zero() || a == b) return Ball(0);
  // the quadrature's options for sigma^2 of `speed` (s's or a chart's)
  const auto options = [&](const Speed& speed) {
    QuadratureOptions qo;
    qo.rel_goal_bits = rel_goal_bits;
    qo.max_prec = max_prec;
    qo.scale_bits = speed_scale_bits(speed);
    qo.what = "the integral of the squared " + to_string(s.kind()) + " speed";
    qo.singularity_hints = speed.singularity_hints(true);
    return qo;
  };
  if (const SpeedCharts* ch = s.charts()) {
    // span by span in the charts: sigma^2 dt = sigma_phi^2 / |phi'| du
    Ball total(0);
    for (const SpeedCharts::Span& sp : ch->spans(a, b)) {
      const SpeedChart& c = ch->charts[sp.chart];
      const Speed& speed = sp.plain ? s : c.speed;
      Integrand f = [&c, &speed, plain = sp.plain](acb_t out, const acb_t z, bool, long prec) {
        speed.eval_squared(out, z, prec);
        if (plain) return;
        acb_t d;
        acb_init(d);
        c.denominator(d, z, prec);
        acb_mul(d, d, d, prec);
        acb_mul_arb(d, d, c.w0(prec).get(), prec);
        acb_mul(out, out, d, prec);
        acb_clear(d);
      };
      arb_add(total.get(), total.get(), integrate(f, sp.u0, sp.u1, options(speed)).get(), 2 * rel_goal_bits + 64);
    }
    return total;
  }
  Integrand f = [&s](acb_t out, const acb_t z, bool, long prec) { s.eval_squared(out, z, prec); };
  return integrate(f, a, b, options(s));
}

void check_degree(const Curve& c, const Options& opt) {
  if (c.degree() > opt.max_degree)
    throw BudgetExceeded("the curve has degree " + std::to_string(c.degree()) + ", above the degree limit of " +
                         std::to_string(opt.max_degree) + " (raise it with --max-degree)");
}

namespace {

// UNCERTIFIED: estimates of (mu, int sigma^2) from sigma^2 at 64 bits
// (Speed::eval_squared: any exponent range, unlike double) on the midpoints
// of 64 equal cells of [0, 1] and, since sigma may vary on a scale down to
// 2^-scale_bits at the ends (speed_scale_bits), on those of the cells
// [2^-(k+1), 2^-k] next to 0 and to 1 for 7 <= k < scale_bits + 8 (a peak
// of width 2^-k at an end is a smooth bump in k). Non-finite or
// non-positive samples are skipped (0 where none is left). Only steers the
// parts' scaling and absolute goal (a narrow peak between the samples
// makes an estimate too small: a stricter goal, as without it; one too
// large: the second pass of speed_integrals).
std::pair<Ball, Ball> integral_estimate(const Speed& s, long scale_bits, const SquareWeight* weight) {
  constexpr int kSamples = 64;
  constexpr long kPrec = 64;
  Ball sum(0), sum_sq(0), v;
  acb_t z, w;
  acb_init(z);
  acb_init(w);
  auto add = [&](long weight_exp) {  // the sample at z, over a cell of width 2^weight_exp
    s.eval_squared(w, z, kPrec);
    if (!acb_is_finite(w) || !arb_is_positive(acb_realref(w))) return;
    arb_set_arf(v.get(), arb_midref(acb_realref(w)));
    if (weight) {
      acb_t ww;
      acb_init(ww);
      eval_weight(ww, z, *weight, kPrec);
      arb_mul(v.get(), v.get(), acb_realref(ww), kPrec);
      acb_clear(ww);
    }
    arb_mul_2exp_si(v.get(), v.get(), weight_exp);
    arb_add(sum_sq.get(), sum_sq.get(), v.get(), kPrec);
    arb_set_arf(v.get(), arb_midref(acb_realref(w)));
    arb_sqrt(v.get(), v.get(), kPrec);
    arb_mul_2exp_si(v.get(), v.get(), weight_exp);
    arb_add(sum.get(), sum.get(), v.get(), kPrec);
  };
  for (int i = 0; i < kSamples; ++i) {
    acb_set_si(z, 2 * i + 1);
    acb_mul_2exp_si(z, z, -7);  // (2i + 1) / 128
    add(-6);
  }
  for (long k = 7; k < scale_bits + 8; ++k) {
    acb_set_si(z, 3);
    acb_mul_2exp_si(z, z, -(k + 2));  // 3 * 2^-(k+2), the middle of [2^-(k+1), 2^-k]
    add(-(k + 1));
    acb_neg(z, z);
    acb_add_si(z, z, 1, kPrec + k);  // exact: 1 - 3 * 2^-(k+2)
    add(-(k + 1));
  }
  acb_clear(z);
  acb_clear(w);
  return {sum, sum_sq};
}

// e with x >= 2^e, from x's midpoint (lower = false) or lower bound (lower =
// true); false where that is not finite and positive.
bool exponent_below(long& e, const Ball& x, bool lower) {
  if (!x.is_finite()) return false;
  arf_t t;
  arf_init(t);
  if (lower) arb_get_lbound_arf(t, x.get(), 64);
  else arf_set(t, arb_midref(x.get()));
  const bool ok = arf_sgn(t) > 0;
  if (ok) e = arf_abs_bound_lt_2exp_si(t) - 1;  // 2^(e + 1) > t >= 2^e
  arf_clear(t);
  return ok;
}

// rad(x) <= 2^-bits * |lower bound of x|.
bool meets_rel(const Ball& x, long bits) {
  if (!x.is_finite()) return false;
  mag_t m;
  mag_init(m);
  arf_get_mag_lower(m, arb_midref(x.get()));
  mag_mul_2exp_si(m, m, -bits);
  const bool ok = mag_cmp(arb_radref(x.get()), m) <= 0;
  mag_clear(m);
  return ok;
}

// mu (and, with squares, the integral of sigma^2) over [0, 1] at relative
// accuracy 2^-bits: the pieces between the zeros of sigma and the split
// points are independent tasks (with squares, each integrates sigma and
// sigma^2 together), spread over worker threads, each extra worker with its
// own copies of the speed and the ends (both keep mutable caches), made
// before any starts. The zeros are refined once before the workers start
// (copies share their refinement; this keeps two workers from refining one
// number at once); value-neutral: RealAlgebraic::to_ball depends on (t, prec)
// alone. The first attempt asks for bits + 32 + RealAlgebraic::kToBallExtraBits
// bits (integrate's working precision bits + 32, and to_ball's refinement).
void speed_integrals(const Speed& s, long bits, long max_prec, bool squares, Ball& mu, Ball& mean_square,
                     const SquareWeight* weight = nullptr) {
  const RealAlgebraic zero(0), one(1);
  for (const SpeedZero& z : s.zeros()) z.t.refine(bits + 32 + RealAlgebraic::kToBallExtraBits);
  // The tasks' quadratures start by asking for the singularity hints (one
  // computation, shared): made here, its two root sets on two workers,
  // instead of by the first task while the others wait.
  s.singularity_hints(false);
  // At least two parts with squares: the two tasks of a curve without
  // zeros were mu and the integral of sigma^2 side by side, and a part is
  // about what the quadrature's first bisection makes anyway.
  const long parts = std::max(split_parts(s), squares ? 2L : 1L);
  const std::vector<RealAlgebraic> ends = detail::with_split_points(speed_piece_ends(s, zero, one), parts);
  const std::size_t tasks = ends.size() - 1;
  const std::size_t workers = std::min(worker_count(), tasks);
  // Extra workers' copies (made only when the loop wakes them).
  std::vector<Speed> speeds;
  std::vector<std::vector<RealAlgebraic>> ends_copies;
  std::vector<std::vector<Ball>> results(tasks);
  // One pass over the parts: each integrand scaled by 2^-exps[k] (exact)
  // and, when abs_goal, to an absolute accuracy of 2^-share besides the
  // relative one.
  auto run = [&](const long* exps, bool abs_goal, long share) {
    parallel_for(
        tasks, workers,
        [&](std::size_t w, std::size_t i) {
          const Speed& sw = w == 0 ? s : speeds[w - 1];
          const std::vector<RealAlgebraic>& ew = w == 0 ? ends : ends_copies[w - 1];
          results[i] = integrate_speed_piece(sw, ew[i], ew[i + 1], bits, max_prec, squares, abs_goal ? share : 0,
                                             weight, exps);
        },
        [&](std::size_t k) {
          if (speeds.size() + 1 >= k) return;  // the copies of an earlier pass serve
          speeds.assign(k - 1, s);
          ends_copies.assign(k - 1, ends);
        });
    // sigma and sigma^2 are >= 0: the parts' radii add up to at most
    // 2^-bits times the sum plus tasks times the absolute goal.
    mu = Ball(0);
    mean_square = Ball(0);
    for (const std::vector<Ball>& r : results) {
      arb_add(mu.get(), mu.get(), r[0].get(), 2 * bits + 64);
      if (squares) arb_add(mean_square.get(), mean_square.get(), r[1].get(), 2 * bits + 64);
    }
  };
  // Only the sums need relative accuracy 2^-bits: a part where sigma is
  // negligible (t^1998 on [0, 1/8], or 1/(2 C t^2) away from the peak of
  // (t, C t^2)) may stop at an absolute accuracy of 2^-bits times a share of
  // the total, instead of costing as much as a significant part (or more:
  // the precision its own relative accuracy would need). Each integrand is
  // scaled exactly by a power of 2 that brings its estimated total
  // (integral_estimate) to [1, 2), so that one absolute goal 2^-share fits
  // both integrals, whatever their size. Where the sums then miss twice
  // their goal (an estimate too large), the parts are integrated again with
  // the sums' certified lower bounds in place of the estimates, which makes
  // the absolute goal at most a quarter of the relative one.
  const long share = bits + 2 + static_cast<long>(std::ceil(std::log2(static_cast<double>(tasks))));
  const std::pair<Ball, Ball> est = integral_estimate(s, speed_scale_bits(s), weight);
  long exps[2] = {0, 0};
  bool known = exponent_below(exps[0], est.first, false) && (!squares || exponent_below(exps[1], est.second, false));
  run(exps, known, share);
  if (!(meets_rel(mu, bits - 1) && (!squares || meets_rel(mean_square, bits - 1)))) {
    known = exponent_below(exps[0], mu, true) && (!squares || exponent_below(exps[1], mean_square, true));
    if (!known) exps[0] = exps[1] = 0;
    run(exps, known, share);
  }
}

// BudgetExceeded when `digits` need more bits than max_prec: the integrals
// cannot reach a relative accuracy finer than the working precision, so
// refuse at once rather than after hopeless attempts.
void check_digits_fit(const Options& opt) {
  if (digits_to_bits(opt.digits) > opt.max_prec)
    throw BudgetExceeded(std::to_string(opt.digits) + " digits need more than " +
                         std::to_string(digits_to_bits(opt.digits)) + " bits of working precision, above the " +
                         "precision limit of " + std::to_string(opt.max_prec) + " bits (raise it with --max-prec)");
}

}  // namespace

Ball mean_speed(const Speed& s, long rel_goal_bits, const Options& opt) {
  validate(opt);
  if (s.identically_zero()) return Ball(0);
  check_digits_fit(opt);
  Ball mu, unused;
  speed_integrals(s, rel_goal_bits, opt.max_prec, false, mu, unused);
  return mu;
}

namespace {

// r's exact parts from s: kind, sigma^2, zeros; for an identically zero
// speed also mu = int sigma^2 = 0 and u = 1, and true (nothing to
// integrate).
bool exact_parts(const Speed& s, UniformityResult& r) {
  r.kind = s.kind();
  r.speed_squared = s.squared();
  r.zeros = s.zeros();
  r.identically_zero = s.identically_zero();
  if (!r.identically_zero) return false;
  r.mu = Ball(0);
  r.mean_square = Ball(0);
  r.u = Ball(1);
  return true;
}

// uniformity() of the speed `reported` (its exact parts: sigma^2, zeros),
// with the integrals taken from `integrated`: the same speed, or a balanced
// curve's with the weight of its integral of sigma^2 (scaling.hpp): the
// same mu and integral of sigma^2 exactly.
UniformityResult uniformity_of(const Speed& reported, const Speed& integrated, const SquareWeight* weight,
                               const Options& opt) {
  validate(opt);
  UniformityResult r;
  if (exact_parts(reported, r)) return r;
  check_digits_fit(opt);
  // Each integral to relative accuracy 2^-bits gives u to about 4 * 2^-bits.
  for (long bits = digits_to_bits(opt.digits); ; bits += 32) {
    check_time_budget();
    speed_integrals(integrated, bits, opt.max_prec, true, r.mu, r.mean_square, weight);
    const long prec = 2 * bits + 64;
    arb_mul(r.u.get(), r.mu.get(), r.mu.get(), prec);
    arb_div(r.u.get(), r.u.get(), r.mean_square.get(), prec);
    // One digit of margin, so that the decimal printing of the balls (which
    // adds its rounding error to the radius) still meets opt.digits.
    if (r.mu.meets_digits(opt.digits + 1) && r.mean_square.meets_digits(opt.digits + 1) &&
        r.u.meets_digits(opt.digits + 1))
      return r;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the uniformity to " + std::to_string(opt.digits) +
                           " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

}  // namespace

UniformityResult uniformity(const Curve& c, SpeedKind kind, const Options& opt) {
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  // Weights growing geometrically (a rational Bezier curve with weights
  // 1, 8e40, 1e82): the integrals of the balanced curve q = p o m, whose
  // speed is spread over [0, 1] instead of within 1 / lambda of one end.
  if (!s.identically_zero()) {
    if (const std::optional<BalancedCurve> bal = balance(c, s)) return uniformity_balanced(s, *bal, Speed(bal->q, kind), opt);
  }
  // Mass at narrow features inside (0, 1) (a huge C in (t, C (t - 1/2)^2)),
  // or at both ends: the integrals run part by part in s's charts.
  return uniformity_of(s, s, nullptr, opt);
}

UniformityResult uniformity_balanced(const Speed& s, const BalancedCurve& bal, const Speed& q_speed,
                                     const Options& opt) {
  const SquareWeight w{bal.a, bal.b};
  return uniformity_of(s, q_speed, &w, opt);
}

UniformityResult uniformity(const Speed& s, const Options& opt) { return uniformity_of(s, s, nullptr, opt); }

}  // namespace uniparam
