// Internal to the quadrature (not installed): the pieces that
// quadrature.cpp (the driver: precisions, goals, errors), quadrature_adaptive.cpp
// (the subdivision), quadrature_gl.cpp (one Gauss-Legendre step and its node
// cache) and quadrature_ends.cpp (end errors, node_fast at single points)
// share (besides the Arb holders of core/arb_holders.hpp): the state of one
// attempt, and the integrand call that every evaluation goes through
// (inline: it is the hot path).
#pragma once

#include <acb.h>
#include <mag.h>

#include <algorithm>
#include <complex>
#include <cstddef>
#include <exception>
#include <vector>

#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/arb_holders.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/ball_regions.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/core/dd_ball.hpp"

namespace uniparam {
namespace quadrature_detail {


/// count enclosures (an acb vector), freed on scope exit.
struct AcbVec {
  acb_ptr v;
  slong n;
  explicit AcbVec(std::size_t count) : v(_acb_vec_init(static_cast<slong>(count))), n(static_cast<slong>(count)) {}
  ~AcbVec() { _acb_vec_clear(v, n); }
  AcbVec(const AcbVec&) = delete;
  AcbVec& operator=(const AcbVec&) = delete;
};

/// The integrand and its state during one attempt.
struct Context {
  const Integrand* f;
  std::size_t count;         ///< values f writes per call
  std::exception_ptr error;  ///< first exception thrown by *f, rethrown after the attempt
  long wide_prec;            ///< precision for wide balls (see integrate)
  const std::vector<std::complex<double>>* hints = nullptr;  ///< QuadratureOptions::singularity_hints
  const NodeIntegrand* node_fast = nullptr;                  ///< QuadratureOptions::node_fast (may be empty)
  std::vector<DDBall> dd_out;                                ///< node_fast's outputs
};


/// out[0 .. count) = f(z). No exception leaves: the first one is stored, and
/// from then on every call answers exact 0s without calling f, so that
/// every subinterval is accepted at once (indeterminate answers would make
/// the subdivision bisect up to eval_limit); the enclosure of that attempt
/// is discarded and integrate_many() rethrows. `analytic`: f must also
/// certify holomorphy on z (the ellipses of the error bounds).
inline void call(Context& ctx, acb_ptr out, const acb_t z, bool analytic, long prec) {
  if (!ctx.error) {
    try {
      check_time_budget();  // --timeout, noticed within one evaluation
      // A wide ball's enclosure is as wide as f's variation on it: the bits
      // of the goal buy nothing there (only those lost to cancellation do).
      (*ctx.f)(out, z, analytic, is_region_ball(z) ? std::min(prec, ctx.wide_prec) : prec);
      return;
    } catch (...) {
      ctx.error = std::current_exception();
    }
  }
  _acb_vec_zero(out, static_cast<slong>(ctx.count));
}

/// One Gauss-Legendre step on [a, b] for ctx.count integrals at once
/// (quadrature_gl.cpp, where the method is described): ARB_CALC_SUCCESS
/// with enclosures in res[k] whose errors are below tol[k], or
/// ARB_CALC_NO_CONVERGENCE (res indeterminate). *evals counts the calls of f.
int gl_step(acb_ptr res, long* evals, Context& ctx, const acb_t a, const acb_t b, const std::vector<MagVar>& tol,
            long deg_limit, bool use_hints, long prec);

/// Adaptive subdivision of [a, b] into Gauss-Legendre steps
/// (quadrature_adaptive.cpp): rigorous enclosures of the ctx.count
/// integrals in res; ARB_CALC_SUCCESS, or ARB_CALC_NO_CONVERGENCE when
/// eval_limit or depth_limit stopped it (res still rigorous, maybe wide).
int adaptive_integrate(acb_ptr res, Context& ctx, const acb_t a, const acb_t b, long goal, const mag_t tol,
                       long eval_limit, long depth_limit, long prec);

/// node_fast's values at the narrow real ball t as Arb balls in
/// out[0 .. count) (quadrature_ends.cpp): true when it answered finite
/// balls; false otherwise (out unspecified). Exceptions propagate.
bool fast_point(acb_ptr out, const NodeIntegrand& fast, std::size_t count, const arb_t t, long prec);

/// Adds rad(end) * sup |f_k(end)| to the error of each res[k]
/// (quadrature_ends.cpp): the integral between the true end and the
/// midpoint of its enclosure `end`. Exceptions from f propagate.
void add_end_error(acb_ptr res, const Integrand& f, const NodeIntegrand& fast, std::size_t count, const Ball& end,
                   long prec);

}  // namespace quadrature_detail
}  // namespace uniparam
