// speed_enclosure.hpp -- the enclosure arithmetics that speed_formula.hpp's
// templates run on (internal to uniparam_reparam): Arb's complex balls
// (AcbArith, with the RAII value AcbBox), complex discs in double
// (DiskArith, core/cdisk.hpp) and double-word real balls (DDArith,
// core/dd_inline.hpp: include this header only from files compiled with
// -ffp-contract=off, see reparam/CMakeLists.txt).
#pragma once

#include <acb.h>

#include <cmath>
#include <cstddef>
#include <vector>

#include "uniparam/core/cdisk.hpp"

namespace uniparam {

/// An acb_t that initialises and clears itself: the temporaries of the
/// evaluation paths are released on every exit, a thrown exception
/// included.
class AcbBox {
 public:
  AcbBox() { acb_init(v_); }
  ~AcbBox() { acb_clear(v_); }
  AcbBox(const AcbBox& o) {
    acb_init(v_);
    acb_set(v_, o.v_);
  }
  AcbBox& operator=(const AcbBox& o) {
    acb_set(v_, o.v_);
    return *this;
  }
  acb_ptr get() { return v_; }
  acb_srcptr get() const { return v_; }
  operator acb_ptr() { return v_; }
  operator acb_srcptr() const { return v_; }

 private:
  acb_t v_;
};

/// Arb's complex balls at precision prec. sqrt: the principal square root,
/// with acb_sqrt_analytic's holomorphy check when analytic; with real_nonneg
/// (a quantity known to be >= 0 on a real segment, imaginary parts exactly
/// 0), arb_sqrtpos of the real part ([max(0, lo), hi]) and real division.
struct AcbArith {
  using T = AcbBox;
  long prec;
  bool analytic = false;
  bool real_nonneg = false;
  void zero(T& r) const { acb_zero(r); }
  void mul(T& r, const T& a, const T& b) const { acb_mul(r, a, b, prec); }
  void sub(T& r, const T& a, const T& b) const { acb_sub(r, a, b, prec); }
  void neg(T& r, const T& a) const { acb_neg(r, a); }
  void mul_2exp(T& r, const T& a, long e) const { acb_mul_2exp_si(r, a, e); }
  void addmul(T& r, const T& a, const T& b) const { acb_addmul(r, a, b, prec); }
  void submul(T& r, const T& a, const T& b) const { acb_submul(r, a, b, prec); }
  void inv(T& r, const T& a) const { acb_inv(r, a, prec); }
  void div(T& r, const T& a, const T& b) const {
    if (real_nonneg) {
      arb_div(acb_realref(r.get()), acb_realref(a.get()), acb_realref(b.get()), prec);
      arb_zero(acb_imagref(r.get()));
    } else {
      acb_div(r, a, b, prec);
    }
  }
  void sqrt(T& r, const T& a) const {
    if (real_nonneg) {
      arb_sqrtpos(acb_realref(r.get()), acb_realref(a.get()), prec);
      arb_zero(acb_imagref(r.get()));
    } else {
      acb_sqrt_analytic(r, a, analytic, prec);
    }
  }
  void mul_pow(T& r, const T& h, int m) const {
    AcbBox p;
    acb_pow_ui(p, h, static_cast<ulong>(m), prec);
    acb_mul(r, r, p, prec);
  }
  static bool finite(const T& a) { return acb_is_finite(a); }
};

/// n AcbBox values in one allocation (RAII, as AcbBox).
class AcbVec {
 public:
  explicit AcbVec(std::size_t n) : n_(static_cast<slong>(n)), v_(_acb_vec_init(n_)) {}
  ~AcbVec() { _acb_vec_clear(v_, n_); }
  AcbVec(const AcbVec&) = delete;
  AcbVec& operator=(const AcbVec&) = delete;
  acb_ptr operator+(std::size_t i) const { return v_ + i; }

 private:
  slong n_;
  acb_ptr v_;
};

/// Complex discs in double (core/cdisk.hpp): not finite where a magnitude
/// leaves the discs' range or a divisor's disc holds 0.
struct DiskArith {
  using T = CDisk;
  static void zero(T& r) { r = CDisk{0, 0, 0}; }
  static void mul(T& r, const T& a, const T& b) { r = cdisk_mul(a, b); }
  static void sub(T& r, const T& a, const T& b) { r = cdisk_add(a, cdisk_neg(b)); }
  static void neg(T& r, const T& a) { r = cdisk_neg(a); }
  static void addmul(T& r, const T& a, const T& b) { r = cdisk_add(r, cdisk_mul(a, b)); }
  static void submul(T& r, const T& a, const T& b) { r = cdisk_add(r, cdisk_neg(cdisk_mul(a, b))); }
  static void inv(T& r, const T& a) { r = cdisk_inv(a); }
  static void div(T& r, const T& a, const T& b) { r = cdisk_div(a, b); }
  static void sqrt(T& r, const T& a) { r = cdisk_sqrt_analytic(a); }
  static void mul_pow(T& r, const T& h, int m) {
    for (int k = 0; k < m; ++k) r = cdisk_mul(r, h);
  }
  static bool finite(const T& a) { return cdisk_is_finite(a); }
};

}  // namespace uniparam

#ifdef UNIPARAM_SPEED_DD_ARITH
#include "uniparam/core/dd_inline.hpp"

namespace uniparam {

/// Double-word real balls (core/dd_inline.hpp), F as there: a failed
/// division or square root gives a NaN ball, which every later operation
/// keeps.
template <bool F>
struct DDArith {
  using T = DDBall;
  static void zero(T& r) { r = DDBall{0, 0, 0}; }
  [[gnu::always_inline]] static void mul(T& r, const T& a, const T& b) { r = dd_detail::ball_mul<F>(a, b); }
  [[gnu::always_inline]] static void sub(T& r, const T& a, const T& b) { r = dd_detail::ball_sub(a, b); }
  [[gnu::always_inline]] static void neg(T& r, const T& a) { r = dd_detail::ball_neg(a); }
  [[gnu::always_inline]] static void addmul(T& r, const T& a, const T& b) {
    r = dd_detail::ball_add(r, dd_detail::ball_mul<F>(a, b));
  }
  [[gnu::always_inline]] static void submul(T& r, const T& a, const T& b) {
    r = dd_detail::ball_sub(r, dd_detail::ball_mul<F>(a, b));
  }
  [[gnu::always_inline]] static void div(T& r, const T& a, const T& b) { dd_detail::ball_div<F>(r, a, b); }
  [[gnu::always_inline]] static void sqrt(T& r, const T& a) { dd_detail::ball_sqrt<F>(r, a); }
  static bool finite(const T& a) { return dd_is_finite(a); }
};

}  // namespace uniparam
#endif
