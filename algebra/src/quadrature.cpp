// The quadrature's driver (integrate_many, integrate): argument checks,
// the start precision above the cancellation in f, the precision doubling,
// the goals and the error of an integral that cannot be certified. The
// subdivision and the Gauss-Legendre steps are in quadrature_adaptive.cpp
// and quadrature_gl.cpp, the end errors in quadrature_ends.cpp.
#include "uniparam/algebra/quadrature.hpp"

#include <acb_calc.h>
#include <arf.h>
#include <mag.h>

#include <algorithm>
#include <deque>
#include <exception>
#include <string>
#include <vector>

#include "quadrature_internal.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

using namespace quadrature_detail;

namespace {

// Guard bits of the relative goal over the caller's goal: the
// per-subinterval tolerances add up over at most a few thousand
// subintervals (~12 bits). More only raises the Gauss-Legendre degrees.
constexpr long kGoalGuardBits = 12;

/// radius <= 2^-rel * |mid| (with a lower bound of |mid|), or radius <=
/// 2^-abs when abs > 0; false for a non-finite ball.
bool meets_goal(const Ball& r, const QuadratureOptions& opt) {
  if (!r.is_finite()) return false;
  const mag_struct* rad = arb_radref(r.get());
  if (opt.abs_goal_bits > 0 && mag_cmp_2exp_si(rad, -opt.abs_goal_bits) <= 0) return true;
  MagVar m;
  arf_get_mag_lower(m.v, arb_midref(r.get()));
  mag_mul_2exp_si(m.v, m.v, -opt.rel_goal_bits);
  return mag_cmp(rad, m.v) <= 0;
}

/// Bits that evaluating f loses to cancellation on [a, b] (e.g. a power-basis
/// polynomial of high degree with large alternating coefficients): f at 7
/// interior points at precision `prec`, absolute radius against the largest
/// |f_k| seen, the worst k. The first attempt then starts that much higher
/// instead of failing and doubling. 0 when nothing can be measured; an
/// exception from f propagates (as from the quadrature itself).
/// A point node_fast answers is asked of node_fast alone and counts as no
/// loss: its answers meet the nodes' accuracy contract at this precision,
/// and the nodes it answers never reach f. (Its accepted radius,
/// 2^-(prec - kNodeFastSlackBits), read as cancellation, would raise the
/// start precision by that much, often past kNodeFastMaxPrec, where every
/// node then went to f.)
long cancellation_bits(const Integrand& f, const NodeIntegrand& fast, std::size_t count, const Ball& a,
                       const Ball& b, long prec) {
  long worst = 0;
  AcbVar z;
  AcbVec fz(count);
  std::vector<MagVar> big(count), rads(7 * count);
  for (int j = 0; j < 7; ++j) {
    // z = a + (b - a) (j + 1) / 8 at exact dyadic midpoints
    arb_sub(acb_realref(z.v), b.get(), a.get(), prec);
    arb_mul_si(acb_realref(z.v), acb_realref(z.v), j + 1, prec);
    arb_mul_2exp_si(acb_realref(z.v), acb_realref(z.v), -3);
    arb_add(acb_realref(z.v), acb_realref(z.v), a.get(), prec);
    mag_zero(arb_radref(acb_realref(z.v)));
    arb_zero(acb_imagref(z.v));
    const bool answered = fast_point(fz.v, fast, count, acb_realref(z.v), prec);
    if (!answered) f(fz.v, z.v, false, prec);
    for (std::size_t k = 0; k < count; ++k) {
      if (!acb_is_finite(fz.v + k)) return prec;  // everything lost (or a true pole: the real run reports it)
      MagVar m;
      acb_get_mag(m.v, fz.v + k);
      if (mag_cmp(m.v, big[k].v) > 0) mag_set(big[k].v, m.v);
      if (!answered)  // (zero: no loss)
        mag_hypot(rads[j * count + k].v, arb_radref(acb_realref(fz.v + k)), arb_radref(acb_imagref(fz.v + k)));
    }
  }
  for (std::size_t k = 0; k < count; ++k) {
    if (mag_is_zero(big[k].v)) continue;
    for (int j = 0; j < 7; ++j) {
      const MagVar& r = rads[j * count + k];
      if (mag_is_zero(r.v)) continue;
      // accuracy = log2(big / rad); loss = prec - accuracy
      const long acc = fmpz_get_si(MAG_EXPREF(big[k].v)) - fmpz_get_si(MAG_EXPREF(r.v));
      worst = std::max(worst, prec - acc);
    }
  }
  return std::max(0L, worst);
}

std::string goal_text(const QuadratureOptions& opt) {
  std::string s = std::to_string(opt.rel_goal_bits) + " bits";
  if (opt.abs_goal_bits > 0) s += " (or absolute error 2^-" + std::to_string(opt.abs_goal_bits) + ")";
  return s;
}



}  // namespace

std::vector<Ball> integrate_many(const Integrand& f, std::size_t count, const RealAlgebraic& a,
                                 const RealAlgebraic& b, const QuadratureOptions& opt) {
  if (!f) throw InvalidArgument("integrate: empty integrand");
  if (count == 0) throw InvalidArgument("integrate: at least one integral is needed");
  if (opt.rel_goal_bits < 0 || opt.abs_goal_bits < 0)
    throw InvalidArgument("integrate: accuracy goals must be non-negative");
  if (opt.max_prec < 2) throw InvalidArgument("integrate: max_prec must be at least 2 bits");
  if (opt.initial_prec < 0) throw InvalidArgument("integrate: initial_prec must be non-negative");
  if (opt.scale_bits < 0) throw InvalidArgument("integrate: scale_bits must be non-negative");
  const int c = compare(a, b);
  if (c > 0) throw InvalidArgument("integrate: lower end " + a.str() + " exceeds upper end " + b.str());
  if (c == 0) return std::vector<Ball>(count, Ball(0L));

  // The end enclosures at each precision used, converted once: the probe and
  // the first attempt share a precision, and RealAlgebraic::to_ball keeps
  // only its last precision (which the integrand may change in between, e.g.
  // when it evaluates the same algebraic number). to_ball depends on
  // (x, prec) alone, so these are the balls a direct call gives.
  struct EndBalls {
    long prec;
    Ball a, b;
  };
  std::deque<EndBalls> end_balls;  // references stay valid as it grows
  auto ends_at = [&](long p) -> const EndBalls& {
    for (const EndBalls& e : end_balls)
      if (e.prec == p) return e;
    end_balls.push_back(EndBalls{p, a.to_ball(p), b.to_ball(p)});
    return end_balls.back();
  };

  long start = opt.initial_prec > 0 ? opt.initial_prec : opt.rel_goal_bits + 32;
  start = std::min(std::max(start, 2L), opt.max_prec);
  if (opt.initial_prec == 0) {
    // Start above the precision that cancellation in f would eat, measured
    // at the precision that is then used (a total loss doubles it first).
    const long base = start;
    for (int round = 0; round < 4 && start < opt.max_prec; ++round) {
      const EndBalls& e = ends_at(start);
      const long lost = cancellation_bits(f, opt.node_fast, count, e.a, e.b, start);
      const long need = lost >= start ? 2 * start : base + lost;
      if (need <= start + 16) break;
      start = std::min(need, opt.max_prec);
    }
  }

  std::vector<Ball> last(count);
  bool converged = false;
  long prec = start;
  for (;;) {
    check_time_budget();
    // eval_limit 0: Arb's default (1000 prec + prec^2), capped so that one
    // hopeless attempt at thousands of bits cannot run for hours.
    // scale_bits adds its levels' evaluations (and depth) beyond that cap.
    const long eval_limit = opt.eval_limit > 0 ? opt.eval_limit
                                               : std::min(1000 * prec + prec * prec, 2000000L) +
                                                     kEvalsPerScaleBit * opt.scale_bits;
    const long depth_limit = opt.depth_limit > 0 ? opt.depth_limit : 2 * prec + opt.scale_bits;
    const EndBalls& ends = ends_at(prec);
    const Ball& ea = ends.a;
    const Ball& eb = ends.b;
    AcbVar ma, mb;
    AcbVec res(count);
    arb_set_arf(acb_realref(ma.v), arb_midref(ea.get()));  // exact dyadic midpoints
    arb_set_arf(acb_realref(mb.v), arb_midref(eb.get()));

    // Relative goal: rel_goal_bits + kGoalGuardBits (for the sum over
    // subintervals), raised with each retry; never the extra precision that
    // only pays for cancellation in f (asking for it would double the nodes
    // and subintervals for nothing). Absolute tolerance: 2^-prec, or
    // 2^-(abs_goal_bits + 32 + growth) when an absolute goal is set,
    // tightened with the precision so a retry helps.
    long tol_bits = prec;
    if (opt.abs_goal_bits > 0) tol_bits = std::min(prec, opt.abs_goal_bits + 32 + (prec - start));
    MagVar tol;
    mag_set_ui_2exp_si(tol.v, 1, -tol_bits);
    const long goal = std::min(prec, opt.rel_goal_bits + kGoalGuardBits + (prec - start));

    // Wide balls (error bounds) at the bits lost to cancellation plus 64:
    // prec - rel_goal_bits is what the start precision added for them.
    Context ctx{&f, count, nullptr, std::max(64L, prec - opt.rel_goal_bits + 32), &opt.singularity_hints,
                &opt.node_fast, std::vector<DDBall>(count)};
    const int status = adaptive_integrate(res.v, ctx, ma.v, mb.v, goal, tol.v, eval_limit, depth_limit, prec);
    if (ctx.error) std::rethrow_exception(ctx.error);
    // The enclosures are valid whatever the status; NO_CONVERGENCE only
    // means they may be wide, which the goal check below sees.
    converged = status == ARB_CALC_SUCCESS;

    add_end_error(res.v, f, opt.node_fast, count, ea, prec);
    add_end_error(res.v, f, opt.node_fast, count, eb, prec);

    bool met = true;
    for (std::size_t k = 0; k < count; ++k) {
      if (!arb_contains_zero(acb_imagref(res.v + k)))
        throw DomainError("integrate: " + opt.what + " is not real: the integrand is not real-valued on [" +
                          a.str() + ", " + b.str() + "]");
      last[k] = Ball(acb_realref(res.v + k));
      met = met && meets_goal(last[k], opt);
    }
    if (met) return last;
    if (prec >= opt.max_prec) break;
    prec = prec > opt.max_prec / 2 ? opt.max_prec : 2 * prec;
  }
  std::string enclosures;
  for (std::size_t k = 0; k < count; ++k) enclosures += (k ? ", " : "") + last[k].str(10);
  throw BudgetExceeded("could not certify " + opt.what + " to " + goal_text(opt) + " within " +
                       std::to_string(prec) + " bits of working precision (last enclosure" +
                       (count > 1 ? "s " : " ") + enclosures + (converged ? "" : ", quadrature did not converge") +
                       "); raise --max-prec");
}

Ball integrate(const Integrand& f, const RealAlgebraic& a, const RealAlgebraic& b, const QuadratureOptions& opt) {
  return std::move(integrate_many(f, 1, a, b, opt).front());
}

}  // namespace uniparam
