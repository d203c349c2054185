// The adaptive subdivision of the quadrature: each subinterval gets a
// Gauss-Legendre step first, bisection where it fails, and the direct
// enclosure (f on the whole segment) deep in the subdivision or when the
// budget of evaluations is spent.
#include <acb_calc.h>
#include <mag.h>

#include <algorithm>
#include <memory>
#include <vector>

#include "quadrature_internal.hpp"

namespace uniparam {
namespace quadrature_detail {
namespace {

/// f on the whole segment [a, b] (a ball) times b - a: the direct
/// enclosure of each integral, crude but rigorous for any f that answers
/// finite enclosures on the segment.
void direct_estimate(acb_ptr res, Context& ctx, const acb_t a, const acb_t b, long prec) {
  AcbVar mid, delta, wide;
  MagVar m;
  acb_sub(delta.v, b, a, prec);
  acb_mul_2exp_si(delta.v, delta.v, -1);  // (b - a) / 2
  acb_add(mid.v, a, b, prec);
  acb_mul_2exp_si(mid.v, mid.v, -1);
  acb_set(wide.v, mid.v);
  arb_get_mag(m.v, acb_realref(delta.v));
  arb_add_error_mag(acb_realref(wide.v), m.v);
  arb_get_mag(m.v, acb_imagref(delta.v));
  arb_add_error_mag(acb_imagref(wide.v), m.v);
  call(ctx, res, wide.v, false, prec);
  for (std::size_t k = 0; k < ctx.count; ++k) {
    acb_mul(res + k, res + k, delta.v, prec);
    acb_mul_2exp_si(res + k, res + k, 1);
  }
}

/// Depth from which a subinterval where Gauss-Legendre failed is also tried
/// with the direct enclosure (accepted when its radius is below the
/// tolerance). Above it the interval is at least 2^-kDirectDepth of the
/// whole, and a direct enclosure (width times |f|) cannot meet a tolerance
/// of 2^-goal of the integral unless f is tiny there.
constexpr long kDirectDepth = 12;

/// Raises tol[k] to 2^-goal times a lower bound of |u[k]| (Arb's rule: the
/// tolerance follows the largest piece seen).
void raise_tolerances(std::vector<MagVar>& tol, acb_srcptr u, long goal) {
  MagVar lower;
  for (std::size_t k = 0; k < tol.size(); ++k) {
    acb_get_mag_lower(lower.v, u + k);
    mag_mul_2exp_si(lower.v, lower.v, -goal);
    mag_max(tol[k].v, tol[k].v, lower.v);
  }
}

}  // namespace

/// Adaptive Gauss-Legendre quadrature of count integrals at once: Arb's
/// acb_calc_integrate without its direct evaluation of f on every
/// subinterval before the Gauss-Legendre attempt. Arb uses that evaluation
/// to skip hopeless attempts and to accept tiny subintervals; on the
/// quadrature of a speed it is the costliest kind of call (a wide real
/// segment: new local expansions of every factor, and often the factored
/// form), and it is wasted on every subinterval where Gauss-Legendre
/// succeeds. Here each subinterval goes to gl_step (which bounds f on
/// ellipses and evaluates it at its nodes) first; where that fails it is
/// bisected, and from depth kDirectDepth on the direct enclosure is tried
/// first. Every accepted piece is a rigorous enclosure (Arb's error bound
/// included), so the sums are. The tolerances follow Arb, per integral: an
/// absolute tolerance `tol` per subinterval, raised to 2^-goal times the
/// largest lower bound of an accepted piece (or of the direct enclosure on
/// [a, b]); a subinterval is accepted when every integral meets its own.
/// Returns ARB_CALC_SUCCESS, or ARB_CALC_NO_CONVERGENCE when eval_limit or
/// depth_limit stopped the subdivision (the remaining subintervals then hold
/// their direct enclosures: still rigorous, maybe wide or not finite).
int adaptive_integrate(acb_ptr res, Context& ctx, const acb_t a, const acb_t b, long goal, const mag_t tol,
                       long eval_limit, long depth_limit, long prec) {
  const std::size_t count = ctx.count;
  goal = std::max(goal, 0L);
  const long deg_limit = static_cast<long>(0.5 * static_cast<double>(goal) + 10);  // Arb's default
  if (depth_limit <= 0) depth_limit = 2 * prec;
  if (eval_limit <= 0) eval_limit = 1000 * prec + prec * prec;

  struct Interval {
    AcbVar a, b;
    long depth = 0;
  };
  std::vector<std::unique_ptr<Interval>> stack;
  auto push = [&](const acb_t x, const acb_t y, long depth) {
    auto iv = std::make_unique<Interval>();
    acb_set(iv->a.v, x);
    acb_set(iv->b.v, y);
    iv->depth = depth;
    stack.push_back(std::move(iv));
  };

  AcbVar diff;
  AcbVec sum(count), u(count);
  MagVar rad;
  std::vector<MagVar> new_tol(count);
  for (auto& t : new_tol) mag_set(t.v, tol);
  // Tolerances from a lower bound of the whole integrals (as Arb does).
  direct_estimate(u.v, ctx, a, b, prec);
  long evals = 1;
  raise_tolerances(new_tol, u.v, goal);

  int status = ARB_CALC_SUCCESS;
  push(a, b, 0);
  while (!stack.empty()) {
    std::unique_ptr<Interval> iv = std::move(stack.back());
    stack.pop_back();
    acb_sub(diff.v, iv->b.v, iv->a.v, prec);
    const bool stop = status != ARB_CALC_SUCCESS;
    if (stop || acb_contains_zero(diff.v)) {
      // Out of budget, or an interval narrower than its ends' enclosures.
      direct_estimate(u.v, ctx, iv->a.v, iv->b.v, prec);
      ++evals;
      _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
      continue;
    }
    long feval = 0;
    const int gl = gl_step(u.v, &feval, ctx, iv->a.v, iv->b.v, new_tol, deg_limit, iv->depth < kDirectDepth, prec);
    evals += feval;
    if (gl == ARB_CALC_SUCCESS) {
      _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
      raise_tolerances(new_tol, u.v, goal);
      continue;
    }
    if (iv->depth >= kDirectDepth) {
      direct_estimate(u.v, ctx, iv->a.v, iv->b.v, prec);
      ++evals;
      bool small = true;
      for (std::size_t k = 0; k < count && small; ++k) {
        mag_hypot(rad.v, arb_radref(acb_realref(u.v + k)), arb_radref(acb_imagref(u.v + k)));
        small = mag_cmp(rad.v, new_tol[k].v) < 0;
      }
      if (small) {
        _acb_vec_add(sum.v, sum.v, u.v, static_cast<slong>(count), prec);
        continue;
      }
    }
    if (iv->depth + 1 >= depth_limit || evals >= eval_limit) {
      status = ARB_CALC_NO_CONVERGENCE;
      push(iv->a.v, iv->b.v, iv->depth);  // taken again, with its direct enclosure
      continue;
    }
    AcbVar m;
    acb_add(m.v, iv->a.v, iv->b.v, prec);
    acb_mul_2exp_si(m.v, m.v, -1);
    push(m.v, iv->b.v, iv->depth + 1);  // right half after the left one
    push(iv->a.v, m.v, iv->depth + 1);
  }
  _acb_vec_set(res, sum.v, static_cast<slong>(count));
  return status;
}

}  // namespace quadrature_detail
}  // namespace uniparam
