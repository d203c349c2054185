// tests/support/quadrature.hpp -- integrands with exact or independent
// reference integrals, and exact checks of a quadrature's balls, for the
// tests of uniparam/algebra/quadrature.hpp (tests/algebra/test_quadrature*.cpp).
#pragma once

#include <acb.h>
#include <arb.h>
#include <arf.h>

#include <string>
#include <vector>

#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam::test_support {

inline Rational to_rational(const arf_t x) {
  Rational q;
  arf_get_fmpq(q.get(), x);
  return q;
}

/// rad <= 2^-bits * |mid|, decided exactly on rationals (independent of the
/// mag arithmetic used by the implementation).
inline bool meets_rel(const Ball& r, long bits) {
  if (!r.is_finite()) return false;
  arf_t rad;
  arf_init(rad);
  arf_set_mag(rad, arb_radref(r.get()));
  Rational rr = to_rational(rad);
  arf_clear(rad);
  Rational mid = to_rational(arb_midref(r.get()));
  if (mid.sign() < 0) mid = -mid;
  Integer p;
  fmpz_one(p.get());
  fmpz_mul_2exp(p.get(), p.get(), static_cast<ulong>(bits));
  return rr * Rational(p) <= mid;
}

inline bool meets_abs(const Ball& r, long bits) {
  return r.is_finite() && mag_cmp_2exp_si(arb_radref(r.get()), -bits) <= 0;
}

/// The balls share a point: the only way a correct enclosure and a correct
/// reference value can relate.
inline bool overlaps(const Ball& r, const arb_t ref) { return arb_overlaps(r.get(), ref); }

/// p(t) = sum c[k] t^k by Horner; entire, so the ball evaluation certifies
/// holomorphy by itself.
inline Integrand poly_integrand(const std::vector<long>& c) {
  return [c](acb_t out, const acb_t z, bool, long prec) {
    acb_zero(out);
    for (auto it = c.rbegin(); it != c.rend(); ++it) {
      acb_mul(out, out, z, prec);
      acb_add_si(out, out, *it, prec);
    }
  };
}

inline Rational power(const Rational& x, long e) {
  Rational r(1);
  for (long i = 0; i < e; ++i) r = r * x;
  return r;
}

inline Rational exact_poly_integral(const std::vector<long>& c, const Rational& a, const Rational& b) {
  Rational s(0);
  for (std::size_t k = 0; k < c.size(); ++k) {
    const long e = static_cast<long>(k) + 1;
    s = s + Rational(c[k]) * (power(b, e) - power(a, e)) / Rational(e);
  }
  return s;
}

/// 1/(1+t^2): a rational function; inversion of a ball containing 0 gives a
/// non-finite result, so poles are detected by the evaluation itself.
inline void one_over_one_plus_square(acb_t out, const acb_t z, bool, long prec) {
  acb_mul(out, z, z, prec);
  acb_add_ui(out, out, 1, prec);
  acb_inv(out, out, prec);
}

inline std::string str(const std::vector<long>& c) {
  std::string s = "[";
  for (long x : c) s += std::to_string(x) + " ";
  return s + "]";
}

/// 1 / ((t - 1/2)^2 + a^2): poles at 1/2 +- a i; counts the error bounds
/// (analytic calls) and those that were not finite.
struct PolePair {
  Rational a2;  // a^2
  long ellipses = 0, failed = 0, points = 0;  // points: the calls off the ellipses
  Integrand f() {
    return [this](acb_t out, const acb_t z, bool analytic, long prec) {
      acb_t h;
      acb_init(h);
      acb_set_d(h, 0.5);
      acb_sub(out, z, h, prec);
      acb_mul(out, out, out, prec);
      arb_set_fmpq(acb_realref(h), a2.get(), prec);
      arb_zero(acb_imagref(h));
      acb_add(out, out, h, prec);
      acb_inv(out, out, prec);
      acb_clear(h);
      if (analytic) {
        ++ellipses;
        if (!acb_is_finite(out)) ++failed;
      } else {
        ++points;
      }
    };
  }
};

inline void pole_pair_reference(arb_t ref, const Rational& a2) {  // (2 / a) atan(1 / (2 a)) on [0, 1]
  arb_t a;
  arb_init(a);
  arb_set_fmpq(a, a2.get(), 256);
  arb_sqrt(a, a, 256);
  arb_mul_2exp_si(ref, a, 1);
  arb_inv(ref, ref, 256);
  arb_atan(ref, ref, 256);
  arb_mul_2exp_si(ref, ref, 1);
  arb_div(ref, ref, a, 256);
  arb_clear(a);
}

/// 10^6 / (10^6 z^2 + 1), an integrand with poles at +-i/1000 (its integral
/// over [0, 1] is 1000 atan(1000)).
inline void near_pole_integrand(acb_t out, const acb_t z, bool, long prec) {
  acb_mul(out, z, z, prec);
  acb_mul_ui(out, out, 1000000, prec);
  acb_add_ui(out, out, 1, prec);
  acb_inv(out, out, prec);
  acb_mul_ui(out, out, 1000000, prec);
}

}  // namespace uniparam::test_support
