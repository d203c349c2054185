// Real balls with a double-word midpoint (dd_ball.hpp).
//
// This file must be compiled without floating-point contraction
// (-ffp-contract=off, set in core/CMakeLists.txt): Dekker's product and the
// two-sums below are exact only if every operation is rounded separately.
// tests/test_dd_ball.cpp checks them against exact Arb arithmetic.
//
// The operations themselves, and why their balls are rigorous, are in
// uniparam/core/dd_inline.hpp; this file holds the conversions, the
// polynomial set-up and the run-time choice of the FMA path.
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/dd_inline.hpp"
#include "uniparam/core/horner_loss.hpp"

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

using namespace dd_detail;

#if UNIPARAM_DD_HAVE_FMA_TARGET
bool cpu_has_fma() {
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma") != 0;
  }();
  return has;
}
#else
bool cpu_has_fma() { return false; }
#endif
std::atomic<bool> fma_on{cpu_has_fma()};
inline bool use_fma() { return fma_on.load(std::memory_order_relaxed); }

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

DDBall dd_neg(const DDBall& a) { return ball_neg(a); }
DDBall dd_add(const DDBall& a, const DDBall& b) { return ball_add(a, b); }
DDBall dd_sub(const DDBall& a, const DDBall& b) { return ball_sub(a, b); }

namespace {

UNIPARAM_DD_FMA DDBall mul_fma(const DDBall& a, const DDBall& b) { return ball_mul<kHaveFmaTarget>(a, b); }

}  // namespace

DDBall dd_mul(const DDBall& a, const DDBall& b) { return use_fma() ? mul_fma(a, b) : ball_mul<false>(a, b); }

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

UNIPARAM_DD_FMA bool div_fma(DDBall& out, const DDBall& a, const DDBall& b) { return ball_div<kHaveFmaTarget>(out, a, b); }

UNIPARAM_DD_FMA bool sqrt_fma(DDBall& out, const DDBall& a) { return ball_sqrt<kHaveFmaTarget>(out, a); }

}  // namespace

bool dd_div(DDBall& out, const DDBall& a, const DDBall& b) {
  return use_fma() ? div_fma(out, a, b) : ball_div<false>(out, a, b);
}

bool dd_sqrt(DDBall& out, const DDBall& a) { return use_fma() ? sqrt_fma(out, a) : ball_sqrt<false>(out, a); }

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
  for (int j = 0; j <= 3; ++j) abs1_[j] = horner_abs(abs_[j], 1);
  // UNCERTIFIED estimate of Horner's loss on [0, 1] (a choice of path only)
  loss_ = ok ? horner_loss_bits(p, 0, 1, 2) : 0;
}

namespace {

UNIPARAM_DD_FMA bool poly_eval_fma(const DDPoly& p, DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) {
  return p.eval_t<kHaveFmaTarget>(v, d1, d2, x);
}

UNIPARAM_DD_FMA bool lanes_eval_fma(int k, const DDPoly* const* p, const int* j, DDBall* const* out, const DDBall& x) {
  return DDPoly::eval_lanes<kHaveFmaTarget>(k, p, j, out, x);
}

}  // namespace

bool DDPoly::eval(DDBall* v, DDBall* d1, DDBall* d2, const DDBall& x) const {
  return use_fma() ? poly_eval_fma(*this, v, d1, d2, x) : eval_t<false>(v, d1, d2, x);
}

bool DDPoly::eval_many(int k, const DDPoly* const* p, const int* j, DDBall* const* out, const DDBall& x) {
  return use_fma() ? lanes_eval_fma(k, p, j, out, x) : eval_lanes<false>(k, p, j, out, x);
}

bool dd_fma_available() { return cpu_has_fma(); }

bool dd_fma_in_use() { return use_fma(); }

bool dd_set_fma(bool on) {
  fma_on.store(on && cpu_has_fma(), std::memory_order_relaxed);
  return use_fma();
}

}  // namespace uniparam
