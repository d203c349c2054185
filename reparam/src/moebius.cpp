#include "uniparam/reparam/moebius.hpp"

#include <string>

#include "uniparam/core/error.hpp"

namespace uniparam {

MoebiusResult moebius_c0(const Curve& c, SpeedKind kind, const std::vector<RealAlgebraic>& T,
                         const Options& opt) {
  validate(opt);
  check_degree(c, opt);
  const Speed s(c, kind);
  // mark_zeros validates T (0 = t_0 < ... < t_N = 1); the rational method then
  // integrates every piece with ZeroSide::None, so the multiplicities are reset.
  std::vector<Breakpoint> bp = mark_zeros(s, T);
  for (auto& b : bp) b = Breakpoint{b.t, 0, 0, 0};
  const UniformityResult base = uniformity(s, opt);

  MoebiusResult r;
  r.kind = kind;
  r.T = bp;
  r.mu = base.mu;
  r.u_before = base.u;
  r.identically_zero = base.identically_zero;
  r.speed_vanishes = !s.zeros().empty();
  const std::size_t N = r.T.size() - 1;

  if (r.identically_zero) {
    const long prec = digits_to_bits(opt.digits) + 64;
    r.S.clear();
    for (std::size_t i = 0; i <= N; ++i)
      r.S.push_back(i == 0 ? Ball(0) : i == N ? Ball(1) : r.T[i].t.to_ball(prec));
    for (std::size_t i = 0; i < N; ++i) r.integrals.push_back(piece_integrals(s, r.T[i], r.T[i + 1], 64, opt.max_prec));
    r.u_after = Ball(1);
    return r;
  }

  for (long bits = digits_to_bits(opt.digits) + 8;; bits += 32) {
    const long prec = 2 * bits + 64;
    r.integrals.clear();
    std::vector<Ball> sqrtM(N);
    Ball sum(0);
    for (std::size_t i = 0; i < N; ++i) {
      r.integrals.push_back(piece_integrals(s, r.T[i], r.T[i + 1], bits, opt.max_prec));
      arb_sqrt(sqrtM[i].get(), r.integrals[i].M.get(), prec);
      arb_add(sum.get(), sum.get(), sqrtM[i].get(), prec);
    }
    // S_i = cumulative sqrt M / sum, with the ends exact.
    r.S.assign(1, Ball(0));
    Ball acc(0);
    for (std::size_t k = 0; k + 1 < N; ++k) {
      arb_add(acc.get(), acc.get(), sqrtM[k].get(), prec);
      Ball q;
      arb_div(q.get(), acc.get(), sum.get(), prec);
      r.S.push_back(q);
    }
    r.S.push_back(Ball(1));
    Ball mu2, sum2;
    arb_mul(mu2.get(), r.mu.get(), r.mu.get(), prec);
    arb_mul(sum2.get(), sum.get(), sum.get(), prec);
    arb_div(r.u_after.get(), mu2.get(), sum2.get(), prec);

    const long d = opt.digits + 1;
    bool ok = r.u_after.meets_digits(d);
    for (const auto& b : r.S) ok = ok && b.meets_digits(d);
    for (const auto& pi : r.integrals)
      ok = ok && pi.A.meets_digits(d) && pi.B.meets_digits(d) && pi.C.meets_digits(d) && pi.L.meets_digits(d) &&
           pi.M.meets_digits(d) && pi.alpha.meets_digits(d);
    if (ok) return r;
    if (bits > opt.max_prec)
      throw BudgetExceeded("could not certify the piecewise Moebius reparameterization to " +
                           std::to_string(opt.digits) + " digits within " + std::to_string(opt.max_prec) +
                           " bits of working precision (raise it with --max-prec)");
  }
}

MoebiusResult moebius_optimal(const Curve& c, SpeedKind kind, const Options& opt) {
  return moebius_c0(c, kind, {RealAlgebraic(0), RealAlgebraic(1)}, opt);
}

}  // namespace uniparam
