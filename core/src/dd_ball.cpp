// Real balls with a double-word midpoint (dd_ball.hpp).
//
// This file must be compiled without floating-point contraction
// (-ffp-contract=off, set in core/CMakeLists.txt): Dekker's product and the
// two-sums below are exact only if every operation is rounded separately.
// tests/test_dd_ball.cpp checks them against exact Arb arithmetic.
//
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
#include "uniparam/core/dd_ball.hpp"

#include <arf.h>
#include <flint/fmpz.h>
#include <mag.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace uniparam {
namespace {

constexpr double kU = 0x1p-53;
constexpr double kEpsC = 0x1p-99;    // double-word op error, relative to the computed result
constexpr double kEpsX = 0x1p-100;   // ... relative to the exact result (Horner's model)
constexpr double kTiny = 0x1p-1000;  // absolute allowance for underflow
constexpr double kBig = 0x1p900;     // factors above this give a non-finite product
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The fused multiply-add path: functions marked UNIPARAM_FMA are compiled
// for processors with FMA and called only where the processor has it
// (cpu_has_fma, once); the templates they instantiate with F = true are
// inlined into them (always_inline), so __builtin_fma is one instruction.
// Elsewhere (other compilers or architectures) there is one path.
#if (defined(__x86_64__) || defined(__i386__)) && defined(__GNUC__)
#define UNIPARAM_FMA [[gnu::target("fma")]]
constexpr bool kHaveFmaTarget = true;
bool cpu_has_fma() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma") != 0;
  }();
  return has;
}
#else
#define UNIPARAM_FMA
constexpr bool kHaveFmaTarget = false;
bool cpu_has_fma() { return false; }
#endif
std::atomic<bool> fma_on{cpu_has_fma()};
inline bool use_fma() { return fma_on.load(std::memory_order_relaxed); }

struct DW {
  double hi, lo;
};

inline DW two_sum(double a, double b) {
  const double s = a + b;
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e};
}

inline DW fast_two_sum(double a, double b) {  // |a| >= |b| (or a == 0)
  const double s = a + b;
  const double e = b - (s - a);
  return {s, e};
}

inline void split(double a, double& h, double& l) {
  const double t = 134217729.0 * a;  // 2^27 + 1
  h = t - (t - a);
  l = a - h;
}

// F: the processor's fused multiply-add (only inside functions compiled for
// it, see UNIPARAM_FMA below); otherwise Dekker's splitting.
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
inline DW dw_add(DW x, DW y) {
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
inline DW dw_add_fp(DW x, double y) {
  const DW s = two_sum(x.hi, y);
  const double v = x.lo + s.lo;
  return fast_two_sum(s.hi, v);
}

inline DW dw_neg(DW x) { return {-x.hi, -x.lo}; }

inline double up(double x) { return x * (1 + 0x1p-48) + kTiny; }
inline double down(double x) { return x * (1 - 0x1p-51); }  // x >= 0, one rounding
inline double mag_up(DW x) { return std::fabs(x.hi) * (1 + 0x1p-52); }
inline double mag_up(const DDBall& x) { return std::fabs(x.hi) * (1 + 0x1p-52); }
inline DW mid(const DDBall& x) { return {x.hi, x.lo}; }
inline DDBall ball(DW m, double rad) { return {m.hi, m.lo, rad}; }
inline DDBall nan_ball() { return {kNaN, kNaN, kNaN}; }

// A lower bound of |y| over the ball y (> 0 only if the ball excludes 0).
inline double lower_abs(const DDBall& y) {
  const double c1 = std::fabs(y.hi) * (1 - 0x1p-51);  // <= |hi + lo|
  return down(c1 - y.rad);
}

// An upper bound of sum v_k s^k (v_k, s >= 0): 2n roundings of non-negative
// terms, each at most u, so the exact sum is at most h (1 - u)^(-2n).
double horner_abs(const std::vector<double>& v, double s) {
  if (v.empty()) return 0;
  double h = v.back();
  for (std::size_t k = v.size() - 1; k-- > 0;) h = h * s + v[k];
  const double n = static_cast<double>(v.size());
  return h * (1 + (4 * n + 8) * kU);
}

// c as a normalized double word; false if it is not exactly one or is at
// least 2^500 in magnitude.
bool fmpz_to_dw(DW& out, const fmpz_t c) {
  if (fmpz_bits(c) > 500) return false;
  fmpz_t t, r;
  fmpz_init(t);
  fmpz_init(r);
  const double hi = fmpz_get_d(c);  // rounds toward zero
  fmpz_set_d(t, hi);                // exact: hi is an integer
  fmpz_sub(r, c, t);
  // r is exactly a double if its significant bits (trailing zeros aside) fit in 53
  const bool ok = fmpz_is_zero(r) || fmpz_bits(r) - fmpz_val2(r) <= 53;
  const double lo = ok ? fmpz_get_d(r) : 0;  // exact (r < 2^500)
  fmpz_clear(t);
  fmpz_clear(r);
  if (!ok) return false;
  out = fast_two_sum(hi, lo);  // |r| < ulp(hi): exact, and normalizes
  return true;
}

double fmpz_abs_up(const fmpz_t c) {
  const double d = std::fabs(fmpz_get_d(c));  // |c| rounded toward zero
  return d == 0 ? 0 : std::nextafter(d, std::numeric_limits<double>::infinity());
}

}  // namespace

DDBall dd_from_double(double v) { return {v, 0, 0}; }

bool dd_set_arb(DDBall& out, const arb_t x) {
  const arf_struct* m = arb_midref(x);
  if (!arf_is_finite(m) || !mag_is_finite(arb_radref(x))) return false;
  if (mag_cmp_2exp_si(arb_radref(x), 900) >= 0) return false;
  if (!arf_is_zero(m) && (arf_cmpabs_2exp_si(m, 900) >= 0 || arf_cmpabs_2exp_si(m, -900) < 0)) return false;
  arf_t h, r;
  arf_init(h);
  arf_init(r);
  const double hi = arf_get_d(m, ARF_RND_NEAR);
  arf_set_d(h, hi);
  arf_sub(r, m, h, ARF_PREC_EXACT, ARF_RND_DOWN);  // exact
  const double lo = arf_get_d(r, ARF_RND_NEAR);    // |lo| <= ulp(hi) / 2
  arf_set_d(h, lo);
  arf_sub(r, r, h, ARF_PREC_EXACT, ARF_RND_DOWN);  // what hi + lo leaves out
  const double left = std::fabs(arf_get_d(r, ARF_RND_UP));
  arf_clear(h);
  arf_clear(r);
  out = {hi, lo, up(mag_get_d(arb_radref(x)) + left)};  // mag_get_d rounds up
  return true;
}

void dd_get_arb(arb_t out, const DDBall& x) {
  arf_t l;
  arf_init(l);
  arf_set_d(arb_midref(out), x.hi);
  arf_set_d(l, x.lo);
  arf_add(arb_midref(out), arb_midref(out), l, ARF_PREC_EXACT, ARF_RND_DOWN);  // exact
  mag_set_d(arb_radref(out), x.rad);                                            // upper bound
  arf_clear(l);
}

DDBall dd_neg(const DDBall& a) { return {-a.hi, -a.lo, a.rad}; }

DDBall dd_add(const DDBall& a, const DDBall& b) {
  const DW m = dw_add(mid(a), mid(b));
  return ball(m, up(a.rad + b.rad + kEpsC * mag_up(m)));
}

DDBall dd_sub(const DDBall& a, const DDBall& b) { return dd_add(a, dd_neg(b)); }

namespace {

template <bool F>
[[gnu::always_inline]] inline DDBall mul_impl(const DDBall& a, const DDBall& b) {
  if (!(std::fabs(a.hi) <= kBig && std::fabs(b.hi) <= kBig)) return nan_ball();
  const DW m = dw_mul<F>(mid(a), mid(b));
  return ball(m, up(mag_up(a) * b.rad + mag_up(b) * a.rad + a.rad * b.rad + kEpsC * mag_up(m)));
}
UNIPARAM_FMA DDBall mul_fma(const DDBall& a, const DDBall& b) { return mul_impl<kHaveFmaTarget>(a, b); }

}  // namespace

DDBall dd_mul(const DDBall& a, const DDBall& b) { return use_fma() ? mul_fma(a, b) : mul_impl<false>(a, b); }

DDBall dd_mul_2exp(const DDBall& a, int e) {
  if (e >= -64 && e <= 64) {  // by the exact double 2^e: the same roundings as ldexp, no call
    const std::uint64_t bits = static_cast<std::uint64_t>(1023 + e) << 52;
    double f;
    std::memcpy(&f, &bits, sizeof f);
    return {a.hi * f, a.lo * f, a.rad * f + kTiny};
  }
  return {std::ldexp(a.hi, e), std::ldexp(a.lo, e), std::ldexp(a.rad, e) + kTiny};
}

namespace {

template <bool F>
[[gnu::always_inline]] inline bool div_impl(DDBall& out, const DDBall& a_in, const DDBall& b_in) {
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
UNIPARAM_FMA bool div_fma(DDBall& out, const DDBall& a, const DDBall& b) { return div_impl<kHaveFmaTarget>(out, a, b); }

template <bool F>
[[gnu::always_inline]] inline bool sqrt_impl(DDBall& out, const DDBall& a_in) {
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
UNIPARAM_FMA bool sqrt_fma(DDBall& out, const DDBall& a) { return sqrt_impl<kHaveFmaTarget>(out, a); }

}  // namespace

bool dd_div(DDBall& out, const DDBall& a, const DDBall& b) {
  return use_fma() ? div_fma(out, a, b) : div_impl<false>(out, a, b);
}

bool dd_sqrt(DDBall& out, const DDBall& a) { return use_fma() ? sqrt_fma(out, a) : sqrt_impl<false>(out, a); }

double dd_rel_rad(const DDBall& x) {
  if (!dd_is_finite(x) || x.hi == 0) return std::numeric_limits<double>::infinity();
  return x.rad / (std::fabs(x.hi) * (1 - 0x1p-51)) * (1 + 0x1p-50);
}

DDPoly::DDPoly(const Poly& p) {
  n_ = p.degree();
  if (n_ < 0) {  // the zero polynomial: exact zeros
    usable_ = true;
    return;
  }
  bool ok = true;
  fmpz_t c;
  fmpz_init(c);
  const fmpz* a = p.get()->coeffs;
  for (int j = 0; j <= 3; ++j) {
    const long len = n_ + 1 - j;
    if (len <= 0) continue;
    abs_[j].resize(static_cast<std::size_t>(len));
    if (j < 3) {
      hi_[j].resize(static_cast<std::size_t>(len));
      lo_[j].resize(static_cast<std::size_t>(len));
    }
    for (long k = 0; k < len; ++k) {
      // c = k! / (k - j)! ... the j-th derivative's coefficient of t^k
      fmpz_set(c, a + k + j);
      for (long i = 1; i <= j; ++i) fmpz_mul_ui(c, c, static_cast<ulong>(k + i));
      abs_[j][static_cast<std::size_t>(k)] = fmpz_abs_up(c);
      if (j < 3) {
        DW w{0, 0};
        if (!fmpz_to_dw(w, c)) ok = false;
        hi_[j][static_cast<std::size_t>(k)] = w.hi;
        lo_[j][static_cast<std::size_t>(k)] = w.lo;
      }
    }
  }
  fmpz_clear(c);
  usable_ = ok;
  for (int j = 0; j < 3; ++j) single_[j] = std::all_of(lo_[j].begin(), lo_[j].end(), [](double l) { return l == 0; });
  // UNCERTIFIED estimate of Horner's loss on [0, 1] (a choice of path only)
  loss_ = 0;
  for (int j = 0; j < 3 && ok; ++j) {
    if (hi_[j].empty()) continue;
    double peak = 0;
    for (int i = 0; i <= 16; ++i) {
      const double t = i / 16.0;
      double h = hi_[j].back();
      for (std::size_t k = hi_[j].size() - 1; k-- > 0;) h = h * t + hi_[j][k];
      peak = std::max(peak, std::fabs(h));
    }
    double sum = 0;
    for (double v : abs_[j]) sum += v;
    loss_ = std::max(loss_, peak > 0 ? std::log2(sum / peak) : 1000.0);
  }
}

namespace {

// DDPoly::eval's body (its members passed in).
template <bool F>
[[gnu::always_inline]] inline bool poly_eval(const std::vector<double>* hi_, const std::vector<double>* lo_,
                                             const std::vector<double>* abs_, const bool* single, DDBall* v,
                                             DDBall* d1, DDBall* d2, const DDBall& x) {
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
    if (single[j])  // every coefficient is a double: DWPlusFP, more accurate and cheaper
      for (std::size_t k = h.size() - 1; k-- > 0;) acc = dw_add_fp(dw_mul<F>(acc, m), h[k]);
    else
      for (std::size_t k = h.size() - 1; k-- > 0;) acc = dw_add(dw_mul<F>(acc, m), {h[k], l[k]});
    // Horner with 2 n_j double-word operations of relative error <= kEpsX:
    // |acc - p^(j)(m)| <= gamma_{2 n_j} sum |c_k| |m|^k, and moving m over
    // the ball adds at most rad * sup |p^(j+1)| <= rad * sum |c'_k| mr^k.
    const double steps = 2.0 * static_cast<double>(h.size() - 1);
    const double gamma = steps * kEpsX * (1 + 0x1p-40);  // >= steps eps / (1 - steps eps)
    const double r = up(gamma * horner_abs(abs_[j], mu) + x.rad * horner_abs(abs_[j + 1], mr));
    *outs[j] = ball(acc, r);
    ok = ok && dd_is_finite(*outs[j]);
  }
  return ok;
}

UNIPARAM_FMA bool poly_eval_fma(const std::vector<double>* hi, const std::vector<double>* lo,
                                const std::vector<double>* abs, const bool* single, DDBall* v, DDBall* d1,
                                DDBall* d2, const DDBall& x) {
  return poly_eval<kHaveFmaTarget>(hi, lo, abs, single, v, d1, d2, x);
}

}  // namespace

bool DDPoly::eval(DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) const {
  return use_fma() ? poly_eval_fma(hi_, lo_, abs_, single_, v, d1, d2, x)
                   : poly_eval<false>(hi_, lo_, abs_, single_, v, d1, d2, x);
}

bool dd_fma_available() { return cpu_has_fma(); }

bool dd_set_fma(bool on) {
  fma_on.store(on && cpu_has_fma(), std::memory_order_relaxed);
  return use_fma();
}

}  // namespace uniparam
