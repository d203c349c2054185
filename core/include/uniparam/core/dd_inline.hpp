// uniparam/core/dd_inline.hpp -- the double-word ball operations of
// dd_ball.hpp as inline templates, for evaluation loops that inline them.
//
// INTERNAL (namespace uniparam::dd_detail): dd_ball.hpp is the interface.
// A hot loop (a speed at a quadrature node) that calls dd_add, dd_mul, ...
// pays a call and a 24-byte return per operation, and its FMA products sit
// behind a run-time switch per call. Here the operations are templates on
// F (the processor's fused multiply-add, see two_prod) that a caller
// instantiates twice: once with F = true inside a function marked
// UNIPARAM_DD_FMA (compiled for processors with FMA), called only where
// dd_fma_in_use(), and once with F = false. The results are bit for bit the
// same either way, and the same as dd_ball.hpp's functions (which are these
// templates).
//
// Every translation unit that includes this header must be compiled with
// -ffp-contract=off (and without -ffast-math): the error-free
// transformations below are exact only if every operation is rounded on its
// own, and inside an FMA-compiled function the compiler would otherwise fuse
// a * b + c. CMake sets the flag on the files that include it.
#pragma once

#ifdef __FAST_MATH__
#error "uniparam/core/dd_inline.hpp needs IEEE arithmetic: compile without -ffast-math"
#endif

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "uniparam/core/dd_ball.hpp"

// UNIPARAM_DD_FMA marks a function compiled for processors with FMA; the
// templates it instantiates with F = dd_detail::kHaveFmaTarget are inlined into it
// (always_inline), so __builtin_fma is one instruction. Elsewhere (other
// compilers or architectures) there is one path, F = false.
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define UNIPARAM_DD_FMA [[gnu::target("fma")]]
#define UNIPARAM_DD_HAVE_FMA_TARGET 1
#else
#define UNIPARAM_DD_FMA
#define UNIPARAM_DD_HAVE_FMA_TARGET 0
#endif

namespace uniparam {

/// Whether dd_ball.hpp's operations currently use the FMA path (dd_set_fma):
/// the switch that callers of the templates below follow.
bool dd_fma_in_use();

namespace dd_detail {

constexpr bool kHaveFmaTarget = UNIPARAM_DD_HAVE_FMA_TARGET != 0;

// Why the balls are rigorous. All doubles are IEEE binary64, rounded to
// nearest; u = 2^-53.
// * Error-free transformations: TwoSum (Knuth), FastTwoSum (Dekker, when
//   |a| >= |b|) and TwoProd (Dekker's splitting; |a|, |b| < 2^996) return
//   s + e equal to the exact a + b (a * b) when nothing over- or underflows.
//   Where the processor has a fused multiply-add, TwoProd is p = a * b,
//   e = fma(a, b, -p) instead: exact under the same conditions, so e is the
//   same double (the exact a * b - p, which is representable) and every
//   result below is bit for bit the same on both paths (the FMA path is
//   chosen at run time; -ffp-contract=off keeps every other operation
//   unfused).
// * Double-word operations on normalized pairs (|lo| <= ulp(hi) / 2): the
//   accurate sum DWPlusDW and the product DWTimesDW1 of Joldes, Muller and
//   Popescu (Tight and rigorous error bounds for basic building blocks of
//   double-word arithmetic, ACM TOMS 44(2), 2017; algorithms 6 and 10) have
//   relative errors below 3u^2 + 13u^3 and 7u^2 (< 2^-103); their sum of a
//   double word and a double, DWPlusFP (algorithm 4), below 2u^2. We use
//   kEps = 2^-100 for the error relative to the exact result and 2^-99
//   relative to the computed one, a margin of 8x, plus an absolute 2^-1000
//   per operation for underflow (an underflowing operation errs by at most a
//   few 2^-1074).
// * Radii are sums and products of non-negative doubles, each rounding
//   adding a relative error of at most u; up() multiplies by 1 + 2^-48 (which
//   covers up to 29 such roundings and its own) and adds 2^-1000. Lower
//   bounds of positive quantities are multiplied by 1 - 2^-51 the same way.
// * |hi + lo| <= |hi| (1 + u) for a normalized pair: mag_up.
// * Overflow gives an infinity or a NaN, which every later operation keeps
//   (a finite result never comes from a non-finite input here: divisions and
//   square roots check their inputs), and callers reject non-finite balls.

constexpr double kU = 0x1p-53;
constexpr double kEpsC = 0x1p-99;    // double-word op error, relative to the computed result
constexpr double kEpsX = 0x1p-100;   // ... relative to the exact result (Horner's model)
constexpr double kTiny = 0x1p-1000;  // absolute allowance for underflow
constexpr double kBig = 0x1p900;     // factors above this give a non-finite product
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

struct DW {
  double hi, lo;
};

[[gnu::always_inline]] inline DW two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}

[[gnu::always_inline]] inline DW fast_two_sum(double a, double b) {  // |a| >= |b| (or a == 0)
  const double s = a + b;
  const double e = b - (s - a);
  return {s, e};
}

[[gnu::always_inline]] inline void split(double a, double& h, double& l) {
  const double t = 134217729.0 * a;  // 2^27 + 1
  h = t - (t - a);
  l = a - h;
}

// F: the processor's fused multiply-add (only inside functions compiled for
// it, see UNIPARAM_DD_FMA above); otherwise Dekker's splitting.
template <bool F>
[[gnu::always_inline]] inline DW two_prod(double a, double b) {
  const double p = a * b;
  if constexpr (F) {
    return {p, __builtin_fma(a, b, -p)};
  } else {
    double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    const double e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
    return {p, e};
  }
}

// JMP 2017, algorithm 6 (AccurateDWPlusDW)
[[gnu::always_inline]] inline DW dw_add(DW x, DW y) {
  const DW s = two_sum(x.hi, y.hi);
  const DW t = two_sum(x.lo, y.lo);
  const double c = s.lo + t.hi;
  const DW v = fast_two_sum(s.hi, c);
  const double w = t.lo + v.lo;
  return fast_two_sum(v.hi, w);
}

// JMP 2017, algorithm 10 (DWTimesDW1)
template <bool F>
[[gnu::always_inline]] inline DW dw_mul(DW x, DW y) {
  const DW c = two_prod<F>(x.hi, y.hi);
  const double tl = x.hi * y.lo;
  const double tr = x.lo * y.hi;
  const double cl2 = tl + tr;
  const double cl3 = c.lo + cl2;
  return fast_two_sum(c.hi, cl3);
}

// JMP 2017, algorithm 4 (DWPlusFP): a double word plus a double
[[gnu::always_inline]] inline DW dw_add_fp(DW x, double y) {
  const DW s = two_sum(x.hi, y);
  const double v = x.lo + s.lo;
  return fast_two_sum(s.hi, v);
}

[[gnu::always_inline]] inline DW dw_neg(DW x) { return {-x.hi, -x.lo}; }

[[gnu::always_inline]] inline double up(double x) { return x * (1 + 0x1p-48) + kTiny; }
[[gnu::always_inline]] inline double down(double x) { return x * (1 - 0x1p-51); }  // x >= 0, one rounding
[[gnu::always_inline]] inline double mag_up(DW x) { return std::fabs(x.hi) * (1 + 0x1p-52); }
[[gnu::always_inline]] inline double mag_up(const DDBall& x) { return std::fabs(x.hi) * (1 + 0x1p-52); }
[[gnu::always_inline]] inline DW mid(const DDBall& x) { return {x.hi, x.lo}; }
[[gnu::always_inline]] inline DDBall ball(DW m, double rad) { return {m.hi, m.lo, rad}; }
[[gnu::always_inline]] inline DDBall nan_ball() { return {kNaN, kNaN, kNaN}; }

// A lower bound of |y| over the ball y (> 0 only if the ball excludes 0).
[[gnu::always_inline]] inline double lower_abs(const DDBall& y) {
  const double c1 = std::fabs(y.hi) * (1 - 0x1p-51);  // <= |hi + lo|
  return down(c1 - y.rad);
}

// An upper bound of sum v_k s^k (v_k, s >= 0): 2n roundings of non-negative
// terms, each at most u, so the exact sum is at most h (1 - u)^(-2n).
[[gnu::always_inline]] inline double horner_abs(const std::vector<double>& v, double s) {
  if (v.empty()) return 0;
  double h = v.back();
  for (std::size_t k = v.size() - 1; k-- > 0;) h = h * s + v[k];
  const double n = static_cast<double>(v.size());
  return h * (1 + (4 * n + 8) * kU);
}

// The ball operations (dd_ball.hpp's contracts).

[[gnu::always_inline]] inline DDBall ball_neg(const DDBall& a) { return {-a.hi, -a.lo, a.rad}; }

[[gnu::always_inline]] inline DDBall ball_add(const DDBall& a, const DDBall& b) {
  const DW m = dw_add(mid(a), mid(b));
  return ball(m, up(a.rad + b.rad + kEpsC * mag_up(m)));
}

[[gnu::always_inline]] inline DDBall ball_sub(const DDBall& a, const DDBall& b) { return ball_add(a, ball_neg(b)); }

template <bool F>
[[gnu::always_inline]] inline DDBall ball_mul(const DDBall& a, const DDBall& b) {
  if (!(std::fabs(a.hi) <= kBig && std::fabs(b.hi) <= kBig)) return nan_ball();
  const DW m = dw_mul<F>(mid(a), mid(b));
  return ball(m, up(mag_up(a) * b.rad + mag_up(b) * a.rad + a.rad * b.rad + kEpsC * mag_up(m)));
}
template <bool F>
[[gnu::always_inline]] inline bool ball_div(DDBall& out, const DDBall& a_in, const DDBall& b_in) {
  const DDBall a = a_in, b = b_in;  // out may alias either
  out = nan_ball();
  if (!dd_is_finite(a) || !dd_is_finite(b) || !(std::fabs(a.hi) <= kBig && std::fabs(b.hi) <= kBig)) return false;
  const double lb = lower_abs(b);  // <= |y| for every y in b
  if (!(lb > 0)) return false;
  // q ~ a.m / b.m by one correction step; then a rigorous bound of its error
  const double q0 = a.hi / b.hi;
  const DW r0 = dw_add(mid(a), dw_neg(dw_mul<F>({q0, 0}, mid(b))));
  const DW q = fast_two_sum(q0, r0.hi / b.hi);
  if (!std::isfinite(q.hi) || !(std::fabs(q.hi) <= kBig)) return false;
  // |a.m - q b.m| <= |res| + 2^-99 (|res| + |q b.m|) for the computed res, q b.m
  const DW qb = dw_mul<F>(q, mid(b));
  const DW res = dw_add(mid(a), dw_neg(qb));
  const double num = up(mag_up(res) + kEpsC * (mag_up(res) + mag_up(qb)));
  const double lbm = std::fabs(b.hi) * (1 - 0x1p-51);  // <= |b.m|
  const double eq = up(num / lbm);                      // >= |a.m / b.m - q|
  // x / y - a.m / b.m = ((x - a.m) - (a.m / b.m) (y - b.m)) / y
  out = ball(q, up(eq + up(a.rad + up(mag_up(q) + eq) * b.rad) / lb));
  return dd_is_finite(out);
}
template <bool F>
[[gnu::always_inline]] inline bool ball_sqrt(DDBall& out, const DDBall& a_in) {
  const DDBall a = a_in;  // out may alias a
  out = nan_ball();
  if (!dd_is_finite(a) || !(a.hi > 0) || !(a.hi <= kBig)) return false;
  const double la = lower_abs(a);  // <= every x in a
  if (!(la > 0)) return false;
  const double s0 = std::sqrt(a.hi);
  const DW r0 = dw_add(mid(a), dw_neg(two_prod<F>(s0, s0)));
  const DW s = fast_two_sum(s0, r0.hi / (2 * s0));
  if (!(s.hi > 0)) return false;
  // |sqrt(a.m) - s| = |a.m - s^2| / (sqrt(a.m) + s) <= |a.m - s^2| / s
  const DW ss = dw_mul<F>(s, s);
  const DW res = dw_add(mid(a), dw_neg(ss));
  const double num = up(mag_up(res) + kEpsC * (mag_up(res) + mag_up(ss)));
  const double es = up(num / (s.hi * (1 - 0x1p-51)));
  // |sqrt(x) - sqrt(a.m)| = |x - a.m| / (sqrt(x) + sqrt(a.m)) <= a.rad / (2 sqrt(la))
  const double sl = down(std::sqrt(la));
  out = ball(s, up(es + a.rad / (2 * sl)));
  return dd_is_finite(out);
}
}  // namespace dd_detail

// The radius of p^(j)'s Horner value on a ball of radius rad: Horner with
// 2 (len - 1) double-word operations of relative error <= kEpsX gives
// |acc - p^(j)(m)| <= gamma sum |c_k| |m|^k (habs bounds the sum), and moving
// m over the ball adds at most rad * sup |p^(j+1)| <= rad * sum |c'_k| mr^k,
// which is at most rad * abs1_[j + 1] (>= sum |c'_k|) when mr <= 1.
[[gnu::always_inline]] inline double DDPoly::horner_radius(int j, std::size_t len, double habs, double mr,
                                                           double rad) const {
  using namespace dd_detail;
  const double steps = 2.0 * static_cast<double>(len - 1);
  const double gamma = steps * kEpsX * (1 + 0x1p-40);  // >= steps eps / (1 - steps eps)
  const double slope = mr <= 1 ? abs1_[j + 1] : horner_abs(abs_[j + 1], mr);
  return up(gamma * habs + rad * slope);
}

template <bool F>
[[gnu::always_inline]] inline bool DDPoly::eval_t(DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) const {
  using namespace dd_detail;
  DDBall* outs[3] = {v, d1, d2};
  const DW m = mid(x);
  const double mu = mag_up(x);        // >= |m|
  const double mr = up(mu + x.rad);   // >= |t| for every t in x
  bool ok = std::isfinite(mr);
  for (int j = 0; j < 3; ++j) {
    if (!outs[j]) continue;
    const std::vector<double>& h = hi_[j];
    const std::vector<double>& l = lo_[j];
    if (h.empty()) {  // p^(j) == 0
      *outs[j] = {0, 0, 0};
      continue;
    }
    DW acc{h.back(), l.back()};
    if (single_[j])  // every coefficient is a double: DWPlusFP, more accurate and cheaper
      for (std::size_t k = h.size() - 1; k-- > 0;) acc = dw_add_fp(dw_mul<F>(acc, m), h[k]);
    else
      for (std::size_t k = h.size() - 1; k-- > 0;) acc = dw_add(dw_mul<F>(acc, m), {h[k], l[k]});
    *outs[j] = ball(acc, horner_radius(j, h.size(), horner_abs(abs_[j], mu), mr, x.rad));
    ok = ok && dd_is_finite(*outs[j]);
  }
  return ok;
}

namespace dd_detail {
// eval_lanes' loop for K lanes (acc[q] from {0, 0}; lane q's coefficient i
// is 0 at and above size[q]).
// habs[q] = horner_abs(lane q's |coefficients|, mu), the same way
// interleaved (from 0, exactly as horner_abs from its top coefficient).
template <bool F, int K>
[[gnu::always_inline]] inline void horner_lanes(DW* acc, const double* const* h, const std::size_t* size,
                                                std::size_t len, DW m, double* habs, const double* const* ha,
                                                double mu) {
  DW a[K];
  double b[K];
  for (int q = 0; q < K; ++q) {
    a[q] = {0, 0};
    b[q] = 0;
  }
  for (std::size_t i = len; i-- > 0;)
    for (int q = 0; q < K; ++q) {
      const bool in = i < size[q];
      a[q] = dw_add_fp(dw_mul<F>(a[q], m), in ? h[q][i] : 0.0);
      b[q] = b[q] * mu + (in ? ha[q][i] : 0.0);
    }
  for (int q = 0; q < K; ++q) {
    acc[q] = a[q];
    habs[q] = b[q] * (1 + (4 * static_cast<double>(size[q]) + 8) * kU);
  }
}
}  // namespace dd_detail

template <bool F>
[[gnu::always_inline]] inline bool DDPoly::eval_lanes(int k, const DDPoly* const* p, const int* j, DDBall* const* out,
                                                      const DDBall& x) {
  using namespace dd_detail;
  bool single = k >= 1 && k <= kMaxLanes;
  std::size_t len = 0;
  for (int q = 0; q < k && single; ++q) {
    single = p[q]->single_[j[q]];
    len = std::max(len, p[q]->hi_[j[q]].size());
  }
  if (!single) {  // double-word coefficients (or a bad k): lane by lane
    bool ok = k >= 1 && k <= kMaxLanes;
    for (int q = 0; q < k && ok; ++q) {
      DDBall* o[3] = {nullptr, nullptr, nullptr};
      o[j[q]] = out[q];
      ok = p[q]->eval_t<F>(o[0], o[1], o[2], x);
    }
    return ok;
  }
  // Each lane's Horner loop from degree len - 1, its coefficients above its
  // own degree 0: those steps keep acc = 0 exactly (0 * m and 0 + 0 are
  // exact), and the first real one gives {c_top, 0} as eval_t starts, so
  // every lane's acc is eval_t's, and so is its error bound (below). The
  // lane count is a template argument below, so the accumulators stay in
  // registers.
  DW acc[kMaxLanes];
  std::size_t size[kMaxLanes];
  const double *h[kMaxLanes], *ha[kMaxLanes];
  double habs[kMaxLanes];
  for (int q = 0; q < k; ++q) {
    size[q] = p[q]->hi_[j[q]].size();
    h[q] = p[q]->hi_[j[q]].data();
    ha[q] = p[q]->abs_[j[q]].data();
  }
  const DW m = mid(x);
  const double mu = mag_up(x);  // >= |m|
  switch (k) {
#define UNIPARAM_DD_LANES(K) \
  case K: dd_detail::horner_lanes<F, K>(acc, h, size, len, m, habs, ha, mu); break;
    UNIPARAM_DD_LANES(1) UNIPARAM_DD_LANES(2) UNIPARAM_DD_LANES(3) UNIPARAM_DD_LANES(4)
    UNIPARAM_DD_LANES(5) UNIPARAM_DD_LANES(6) UNIPARAM_DD_LANES(7) UNIPARAM_DD_LANES(8)
    UNIPARAM_DD_LANES(9) UNIPARAM_DD_LANES(10) UNIPARAM_DD_LANES(11) UNIPARAM_DD_LANES(12)
#undef UNIPARAM_DD_LANES
    default: return false;
  }
  const double mr = up(mu + x.rad);  // >= |t| for every t in x
  bool ok = std::isfinite(mr);
  for (int q = 0; q < k; ++q) {
    if (size[q] == 0) {  // p^(j) == 0
      *out[q] = {0, 0, 0};
      continue;
    }
    // eval_t's bound (habs[q] = horner_abs(abs_[j[q]], mu))
    *out[q] = ball(acc[q], p[q]->horner_radius(j[q], size[q], habs[q], mr, x.rad));
    ok = ok && dd_is_finite(*out[q]);
  }
  return ok;
}

}  // namespace uniparam
