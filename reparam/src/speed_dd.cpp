// speed_dd.cpp -- the speed at the quadrature's nodes in double-word ball
// arithmetic (Speed::eval_dd, Speed::eval_double_word): the components over
// one common denominator by Horner's rule, the arithmetic of
// speed_formula.hpp on DDArith. Compiled with -ffp-contract=off
// (reparam/CMakeLists.txt: core/dd_inline.hpp's proof).
#include <cmath>
#include <memory>

#include "speed_detail.hpp"
#include "uniparam/core/ball_regions.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/reparam/speed.hpp"
#define UNIPARAM_SPEED_DD_ARITH
#include "speed_enclosure.hpp"
#include "speed_formula.hpp"

namespace uniparam {

namespace {

// eval_double_word: the largest working precision it serves (double words
// carry ~100 bits); the largest loss of Horner's rule on [0, 1] (an
// estimate, cancellation_bits) for which it is tried; and the largest
// degree of a component's N or Q. Horner's rule costs O(degree) double-word
// operations where the local expansions cost O(terms) balls: measured
// (callgrind and probe, one thread, 15 digits), dense-plane degree 50
// uniformity gained 25%, degree 100 lost 22%.
constexpr long kDDMaxPrec = 110;
constexpr double kDDMaxLoss = 24;
constexpr long kDDMaxDegree = 64;

}  // namespace

namespace detail {

std::shared_ptr<const SpeedDD> make_speed_dd(const std::vector<RatFunc>& comps, SpeedKind kind) {
  // The double-word path for the nodes (eval_double_word): only where
  // Horner's rule on the power basis keeps enough bits on [0, 1] (high
  // degree Bezier curves lose more than 24; the local expansions serve
  // them). The components over one common denominator L (the lcm of the
  // Q_i; L = 1 for a polynomial curve): x_i = M_i / L, M_i = N_i L / Q_i.
  auto dd = std::make_shared<SpeedDD>();
  bool ok = comps.size() <= 3;  // eval_dd's bound
  Poly L(1);
  for (const auto& x : comps) {
    if (!ok) break;
    L = divexact(L * x.den(), gcd(L, x.den()));
    ok = L.degree() <= kDDMaxDegree;
  }
  std::vector<Poly> Ms;  // M_i, exactly
  for (const auto& x : comps) {
    if (!ok) break;
    Ms.push_back(x.num() * divexact(L, x.den()));
    ok = Ms.back().degree() <= kDDMaxDegree;
    if (ok) dd->M.emplace_back(Ms.back());
  }
  if (ok) {
    dd->unit_den = L == Poly(1);
    dd->L = DDPoly(L);
    ok = dd->L.usable() && dd->L.cancellation_bits() <= kDDMaxLoss;
  }
  for (const DDPoly& m : dd->M) ok = ok && m.usable() && m.cancellation_bits() <= kDDMaxLoss;
  if (ok && kind == SpeedKind::Angular && !dd->unit_den) {
    const Poly L1 = L.derivative();
    bool a_ok = true;
    for (const Poly& M : Ms) {
      const Poly A = M.derivative() * L - M * L1;
      if (!(a_ok = A.degree() <= kDDMaxDegree)) break;
      dd->A.emplace_back(A);
      a_ok = dd->A.back().usable() && dd->A.back().cancellation_bits() <= kDDMaxLoss;
      if (!a_ok) break;
    }
    if (!a_ok) dd->A.clear();
    if (a_ok) {  // speed_dd takes A_i alone: M_i and L only had to pass the checks above
      dd->M.clear();
      dd->L = DDPoly();
    }
  }
  if (!ok) return nullptr;
  return dd;
}

}  // namespace detail

bool Speed::eval_double_word(acb_t out, const acb_t z, const PieceSigns& p, bool squared, long prec) const {
  if (!dd_ || zero_ || prec > kDDMaxPrec || !arb_is_zero(acb_imagref(z)) ||
      mag_cmp_2exp_si(arb_radref(acb_realref(z)), kRegionBallLog2) >= 0)
    return false;
  DDBall x, r;
  if (!dd_set_arb(x, acb_realref(z)) || !eval_dd(r, x, p, squared, prec)) return false;
  dd_get_arb(acb_realref(out), r);
  arb_zero(acb_imagref(out));
  return true;
}

namespace {

using namespace dd_detail;

// The angular (angular = true) or parametric speed, or its square, at the
// double-word ball x: Speed::eval_dd's arithmetic, with the operations of
// core/dd_inline.hpp inlined (F: the processor's FMA).
//
// With x_i = M_i / L, speed_formula.hpp's A_i, B_i, S, C_ij with Q = L; L
// cancels from the angular speed, the parametric one is sqrt(S) / L^2. A
// polynomial curve (L = 1) has A_i = M_i', B_i = M_i''; a rational one's
// angular speed takes A_i and A_i' = B_i from A_i's own power basis where
// SpeedDD::A holds it.
// False where a ball is not finite, a divisor's ball holds 0 or a square
// root's holds a non-positive number.
template <bool F>
[[gnu::always_inline]] inline bool speed_dd(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign,
                                            bool squared, const DDBall& x) {
  const bool direct = angular && !dd.A.empty();  // A_i and B_i = A_i' from their own polynomials
  const std::size_t n = direct ? dd.A.size() : dd.M.size();
  DDBall A[3], B[3];  // curves of up to 3 components take this path
  DDBall q, q1, q2;
  // Every polynomial value the speed needs, as lanes of one interleaved
  // Horner loop (DDPoly::eval_lanes): A_i, A_i' (direct); M_i', M_i''
  // (polynomial curves); or L, M_i and their first two derivatives.
  const DDPoly* lp[DDPoly::kMaxLanes];
  int lj[DDPoly::kMaxLanes];
  DDBall* lo[DDPoly::kMaxLanes];
  DDBall m[3][3];  // the general case's M_i, M_i', M_i''
  int k = 0;
  auto lane = [&](const DDPoly& poly, int deriv, DDBall* o) {
    lp[k] = &poly;
    lj[k] = deriv;
    lo[k++] = o;
  };
  const int top = angular ? 2 : 1;  // the highest derivative of M_i and L needed
  if (!direct && !dd.unit_den)
    for (int d = 0; d <= top; ++d) lane(dd.L, d, d == 0 ? &q : d == 1 ? &q1 : &q2);
  for (std::size_t i = 0; i < n; ++i) {
    if (direct) {
      lane(dd.A[i], 0, A + i);
      lane(dd.A[i], 1, B + i);
    } else if (dd.unit_den) {
      lane(dd.M[i], 1, A + i);
      if (angular) lane(dd.M[i], 2, B + i);
    } else {
      for (int d = 0; d <= top; ++d) lane(dd.M[i], d, &m[i][d]);
    }
  }
  if (!DDPoly::eval_lanes<F>(k, lp, lj, lo, x)) return false;
  using namespace speed_formula;
  DDArith<F> ar;
  if (!direct && !dd.unit_den)
    for (std::size_t i = 0; i < n; ++i)
      scaled_derivatives(ar, A[i], angular ? B + i : nullptr, m[i][0], m[i][1], &m[i][2], q, q1, &q2);
  DDBall S, Fs{0, 0, 0}, r, l2;
  sum_of_squares(ar, S, n, [&A](std::size_t i) -> const DDBall& { return A[i]; });
  const Form form = !angular ? Form::Parametric : n == 2 ? Form::Plane : Form::Space;
  if (angular) cross_terms(ar, Fs, A, B, n);
  const bool scaled = !angular && !dd.unit_den;  // the parametric speed of M_i / L: S = L^4 sum x_i'^2
  if (scaled) ar.mul(l2, q, q);
  if (squared) speed_squared(ar, r, S, Fs, form, scaled ? &l2 : nullptr);
  else speed_value(ar, r, S, Fs, form, sign, scaled ? &l2 : nullptr);
  out = r;
  return dd_is_finite(r);
}

UNIPARAM_DD_FMA bool speed_dd_fma(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign, bool squared,
                                  const DDBall& x) {
  return speed_dd<kHaveFmaTarget>(out, dd, angular, sign, squared, x);
}

}  // namespace

bool Speed::eval_dd(DDBall& out, const DDBall& x, const PieceSigns& p, bool squared, long prec) const {
  if (!dd_ || zero_ || prec > kDDMaxPrec || !dd_is_finite(x) || !(x.rad < std::ldexp(1.0, kRegionBallLog2))) return false;
  const bool angular = kind_ == SpeedKind::Angular;
  DDBall r;
  const bool ok = dd_fma_in_use() ? speed_dd_fma(r, *dd_, angular, p.component, squared, x)
                                  : speed_dd<false>(r, *dd_, angular, p.component, squared, x);
  if (!ok || !(dd_rel_rad(r) <= std::ldexp(1.0, -static_cast<int>(prec - kNodeFastSlackBits)))) return false;
  out = r;
  return true;
}

}  // namespace uniparam
