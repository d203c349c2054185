// speed_dd.cpp -- the speed at the quadrature's nodes in double-word ball
// arithmetic (Speed::eval_dd, Speed::eval_double_word): the components over
// one common denominator by Horner's rule (or a Bezier curve's Bernstein
// sums), the arithmetic of speed_formula.hpp on DDArith. Compiled with -ffp-contract=off
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
// make_speed_dd_bernstein: the significant bits kept of each coefficient of
// a Bernstein sum H (times (k + 1) (k + 2) <= 2^16 for H'', within a double
// word's 106).
constexpr long kBernKeepBits = 88;
// make_speed_dd_bernstein: the highest degree. The Bernstein sums cost O(n)
// double-word operations a node, the cells O(K) balls with K ~ 40: measured
// (callgrind, one thread, 15 digits, docs/stable-evaluation.md) the gain
// shrinks with n, to about 0 at degree 150 (plane radical -1%).
constexpr long kBernDDMaxDegree = 160;

}  // namespace

namespace detail {

std::shared_ptr<const SpeedDD> make_speed_dd(const std::vector<RatFunc>& comps, SpeedKind kind) {
  // The double-word path for the nodes (eval_double_word): only where
  // Horner's rule on the power basis keeps enough bits on [0, 1] (high
  // degree Bezier curves lose more than 24: their Bernstein sums serve
  // them, make_speed_dd_bernstein; other curves the local expansions). The components over one common denominator L (the lcm of the
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

std::shared_ptr<const SpeedDD> make_speed_dd_bernstein(const BernsteinForm& b) {
  // up to 3 components, degree 2 .. kBernDDMaxDegree
  if (b.num.size() > 3 || b.den.size() < 3 || static_cast<long>(b.den.size()) - 1 > kBernDDMaxDegree) return nullptr;
  auto dd = std::make_shared<SpeedDD>();
  const long n = static_cast<long>(b.den.size()) - 1;
  std::vector<const std::vector<Integer>*> rows;
  for (const auto& r : b.num) rows.push_back(&r);
  rows.push_back(&b.den);
  for (const std::vector<Integer>* row : rows) {
    std::vector<Integer> c = *row;  // (n)_j Delta^j of the coefficients, degree m = n - j
    for (int j = 0; j <= 2; ++j) {
      const long m = n - j;
      std::vector<Integer> h, r;  // h_k = c_k binom(m, k); r reversed
      Integer bin(1);
      for (long k = 0; k <= m; ++k) {
        h.push_back(c[static_cast<std::size_t>(k)] * bin);
        fmpz_mul_si(bin.get(), bin.get(), m - k);
        fmpz_divexact_si(bin.get(), bin.get(), k + 1);
      }
      r.assign(h.rbegin(), h.rend());
      for (const auto* v : {&h, &r}) {
        // H's coefficients cut to kBernKeepBits significant bits (so that H,
        // H', H'' are exact double words), the rest bounded: drop_k >= |h_k - cut h_k|
        std::vector<Integer> cut;
        std::vector<double> drop;
        for (const Integer& a : *v) {
          const long e = static_cast<long>(fmpz_bits(a.get())) - kBernKeepBits;
          Integer t = a;
          if (e > 0) {
            fmpz_tdiv_q_2exp(t.get(), t.get(), static_cast<ulong>(e));
            fmpz_mul_2exp(t.get(), t.get(), static_cast<ulong>(e));
          }
          drop.push_back(e > 0 ? std::ldexp(1.0, static_cast<int>(e)) : 0.0);
          cut.push_back(std::move(t));
        }
        dd->bern_drop.push_back(std::move(drop));
        dd->bern.emplace_back(Poly(cut));
        const DDPoly& q = dd->bern.back();
        if (!q.usable() || q.cancellation_bits() > kDDMaxLoss) return nullptr;
        std::vector<double> sl;  // (k + 1) |h_(k+1)|, rounded up (fmpz_get_d rounds towards 0)
        for (std::size_t k = 1; k < v->size(); ++k) {
          Integer a = (*v)[k] * Integer(static_cast<long>(k));
          sl.push_back(std::fabs(fmpz_get_d(a.get())) * (1 + 0x1p-50));
        }
        dd->bern_slope.push_back(std::move(sl));
      }
      std::vector<Integer> next;
      for (long k = 0; k < m; ++k)
        next.push_back((c[static_cast<std::size_t>(k) + 1] - c[static_cast<std::size_t>(k)]) * Integer(m));
      c = std::move(next);
    }
  }
  dd->bern_n = n;
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

// speed_dd for Bezier input (SpeedDD::bern): N_i, Q and their derivatives
// as Bernstein sums, (1 - t)^(n - j) H(t / (1 - t)) where t <= 1/2 (about
// x's midpoint), else t^(n - j) H((1 - t) / t), s and the powers in ball
// arithmetic; then A_i, B_i, S, C_ij as speed_dd's general case.
template <bool F>
[[gnu::always_inline]] inline bool speed_dd_bern(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign,
                                                 bool squared, const DDBall& x) {
  const std::size_t np = dd.bern.size() / 6, n = np - 1;  // polynomials (Q last), components
  const int top = angular ? 2 : 1;
  const bool left = x.hi <= 0.5;
  const int side = left ? 0 : 1;
  const DDBall omx = ball_sub(DDBall{1, 0, 0}, x);
  const DDBall& base = left ? omx : x;
  DDBall s;
  if (!ball_div<F>(s, left ? x : omx, base)) return false;
  DDBall v[4][3];
  const DDPoly* lp[DDPoly::kMaxLanes];
  int lj[DDPoly::kMaxLanes];
  DDBall* lo[DDPoly::kMaxLanes];
  int k = 0;
  for (std::size_t p = 0; p < np; ++p)
    for (int j = 0; j <= top; ++j) {
      lp[k] = &dd.bern[(3 * p + static_cast<std::size_t>(j)) * 2 + static_cast<std::size_t>(side)];
      lj[k] = 0;
      lo[k++] = &v[p][j];
    }
  // Horner at s's midpoint (the Bernstein terms' rounding), plus s's radius
  // times a bound of |H'| on s's ball, plus the cut coefficients' part
  if (!DDPoly::eval_lanes<F>(k, lp, lj, lo, DDBall{s.hi, s.lo, 0})) return false;
  const double mr = up(mag_up(s) + s.rad);
  k = 0;
  for (std::size_t p = 0; p < np; ++p)
    for (int j = 0; j <= top; ++j, ++k) {
      const std::size_t idx = (3 * p + static_cast<std::size_t>(j)) * 2 + static_cast<std::size_t>(side);
      v[p][j].rad = up(v[p][j].rad + s.rad * horner_abs(dd.bern_slope[idx], mr) + horner_abs(dd.bern_drop[idx], mr));
    }
  // base^(n - top) by squaring, then base^(n - j) for j = top .. 0
  DDBall pw{1, 0, 0}, sq = base;
  for (unsigned long e = static_cast<unsigned long>(dd.bern_n - top); e; e >>= 1) {
    if (e & 1) pw = ball_mul<F>(pw, sq);
    if (e > 1) sq = ball_mul<F>(sq, sq);
  }
  for (int j = top; j >= 0; --j) {
    for (std::size_t p = 0; p < np; ++p) v[p][j] = ball_mul<F>(v[p][j], pw);
    if (j) pw = ball_mul<F>(pw, base);
  }
  using namespace speed_formula;
  DDArith<F> ar;
  DDBall A[3], B[3];
  const DDBall* q = v[n];
  for (std::size_t i = 0; i < n; ++i)
    scaled_derivatives(ar, A[i], angular ? B + i : nullptr, v[i][0], v[i][1], &v[i][2], q[0], q[1], &q[2]);
  DDBall S, Fs{0, 0, 0}, r, l2;
  sum_of_squares(ar, S, n, [&A](std::size_t i) -> const DDBall& { return A[i]; });
  const Form form = !angular ? Form::Parametric : n == 2 ? Form::Plane : Form::Space;
  if (angular) cross_terms(ar, Fs, A, B, n);
  if (!angular) ar.mul(l2, q[0], q[0]);
  if (squared) speed_squared(ar, r, S, Fs, form, angular ? nullptr : &l2);
  else speed_value(ar, r, S, Fs, form, sign, angular ? nullptr : &l2);
  out = r;
  return dd_is_finite(r);
}

UNIPARAM_DD_FMA bool speed_dd_bern_fma(DDBall& out, const detail::SpeedDD& dd, bool angular, int sign, bool squared,
                                       const DDBall& x) {
  return speed_dd_bern<kHaveFmaTarget>(out, dd, angular, sign, squared, x);
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
  bool ok;
  if (dd_->bern_n >= 0)
    ok = dd_fma_in_use() ? speed_dd_bern_fma(r, *dd_, angular, p.component, squared, x)
                         : speed_dd_bern<false>(r, *dd_, angular, p.component, squared, x);
  else
    ok = dd_fma_in_use() ? speed_dd_fma(r, *dd_, angular, p.component, squared, x)
                         : speed_dd<false>(r, *dd_, angular, p.component, squared, x);
  if (!ok || !(dd_rel_rad(r) <= std::ldexp(1.0, -static_cast<int>(prec - kNodeFastSlackBits)))) return false;
  out = r;
  return true;
}

}  // namespace uniparam
