// reparam/src/moebius_opt.cpp -- ImUp's ReparameterizationN: the C0 piecewise
// Moebius map with N pieces and optimised breakpoints (docs/math.md section 3).
//
// The breakpoints are *chosen* by a quasi-Newton method on Phi(T) = sum
// sqrt M_i evaluated in floating point (uncertified: breakpoints.hpp, fed
// with the integrals of float_quadrature.hpp); everything reported is then
// certified by moebius_c0 on the chosen rational T. A wrong choice can only
// cost optimality, never correctness.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "float_quadrature.hpp"
#include "moebius_detail.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/breakpoints.hpp"
#include "uniparam/reparam/moebius.hpp"

namespace uniparam {

namespace {

// The simplest rational within tol * (local spacing) of each interior t_j,
// keeping 0 and 1 exact and the order strict.
std::vector<RealAlgebraic> round_breakpoints(const std::vector<double>& t, double tol) {
  std::vector<RealAlgebraic> out;
  out.emplace_back(Rational(0));
  Rational prev(0);
  for (std::size_t j = 1; j + 1 < t.size(); ++j) {
    const double w = tol * std::min(t[j] - t[j - 1], t[j + 1] - t[j]);
    const long scale = 1L << 52;
    Rational lo(static_cast<long>(std::floor((t[j] - w) * scale)), scale);
    Rational hi(static_cast<long>(std::ceil((t[j] + w) * scale)), scale);
    Rational q = Rational::simplest_between(lo, hi);
    if (q <= prev || q >= Rational(1)) q = Rational(static_cast<long>(std::llround(t[j] * scale)), scale);
    out.emplace_back(q);
    prev = q;
  }
  out.emplace_back(Rational(1));
  return out;
}

// reparam_c0 for the speed s (N and opt checked).
MoebiusResult reparam_c0_on(const Speed& s, long N, const Options& opt) {
  std::vector<RealAlgebraic> equal;
  for (long i = 0; i <= N; ++i) equal.emplace_back(Rational(i, N));
  if (N == 1 || s.identically_zero()) {
    MoebiusResult r = detail::moebius_c0(s, detail::mu_only(s, opt), equal, opt);
    r.optimiser.emplace();
    r.optimiser->phi = r.optimiser->phi_equal = detail::phi_of(r, 2 * digits_to_bits(opt.digits) + 64);
    return r;
  }
  // mu (its own parallel loop) and the optimised breakpoints
  // with their piece integrals do not depend on each other: side by side,
  // each fills the cores the other's last tasks leave idle. The second
  // works on its own copy of the speed (caches are shared and locked, see
  // LocalPoly and RealAlgebraic). The results do not depend on the threads.
  // The pieces of the chosen T (moebius_c0's first round) and of the equally
  // spaced T (the certified comparison below, at modest accuracy, enough to
  // order them) go in one parallel loop: 2N tasks keep the workers busier
  // than N and N one after the other.
  // The breakpoints are item 0, the one the calling thread starts and
  // keeps; another thread can take item 1 only once the calling thread has
  // spent a while on item 0 (parallel_for). At low degree mu is the shorter
  // step (dense-plane degree 50: 1.1 ms against 6 ms): with mu first, the
  // other thread took the breakpoints late and the calling thread waited
  // for them, which on a busy machine cost more than one thread (1.21x).
  // From degree 100 on the two take about as long.
  constexpr long kCompareBits = 40;
  UniformityResult base;
  BreakpointChoice o;
  std::vector<RealAlgebraic> T;
  std::vector<std::vector<PieceIntegrals>> batch;
  {
    const Speed s_copy = s;
    parallel_for(2, std::min<std::size_t>(worker_count(), 2), [&](std::size_t, std::size_t i) {
      if (i == 1) {
        base = detail::mu_only(s, opt);  // u_before: from the pieces (moebius_c0)
        return;
      }
      o = optimise_breakpoints(
          N,
          [&s_copy](double a, double b) {
            const detail::FloatABC v = detail::float_abc(s_copy, a, b);
            return PieceMoments{v.A, v.B, v.C};
          },
          [&s_copy](double t) { return detail::sigma2_double(s_copy, t); });
      T = round_breakpoints(o.t, 1e-9);
      batch = all_piece_integrals(s_copy,
                                  {PieceJob{detail::moebius_breakpoints(s_copy, T), detail::moebius_first_bits(opt)},
                                   PieceJob{detail::moebius_breakpoints(s_copy, equal), kCompareBits}},
                                  opt.max_prec);
    });
  }
  MoebiusResult r = detail::moebius_c0(s, base, T, opt, &batch[0]);
  const long prec = 2 * digits_to_bits(opt.digits) + 64;
  Ball phi = detail::phi_of(r, prec);
  // Never worse than the equally spaced T: the optimiser only accepts
  // decreasing steps, but its values are floating point; a certified
  // comparison decides.
  const Ball phi_eq = detail::certified_phi(batch[1], kCompareBits);
  if (arb_gt(phi.get(), phi_eq.get())) {
    r = detail::moebius_c0(s, base, equal, opt);
    phi = detail::phi_of(r, prec);
  }
  r.optimiser.emplace();
  r.optimiser->iterations = o.iterations;
  r.optimiser->phi = phi;
  r.optimiser->phi_equal = phi_eq;
  r.optimiser->stationarity = o.stationarity;
  return r;
}

}  // namespace

MoebiusResult reparam_c0(const Curve& c, SpeedKind kind, long N, const Options& opt) {
  if (N < 1 || N > 1000) throw InvalidArgument("the number of pieces must be in [1, 1000], got " + std::to_string(N));
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  if (const auto bal = detail::balanced_for(c, s)) {
    const Speed sq(bal->q, kind);
    const MoebiusResult rq = reparam_c0_on(sq, N, opt);
    return detail::compose_balanced(bal, rq, uniformity_balanced(s, *bal, sq, opt).u, opt.digits);
  }
  return reparam_c0_on(s, N, opt);
}

}  // namespace uniparam
