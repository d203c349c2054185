// tests/support/reference.hpp -- comparing certified balls with published
// decimal reference values.
#pragma once

#include <arb.h>

#include <cstring>

#include "uniparam/core/ball.hpp"

namespace uniparam::test_support {

/// True when the ball overlaps the reference value, read from its decimal
/// text and widened by one unit of its last printed decimal (the reference
/// itself is rounded).
inline bool contains_ref(const Ball& b, const char* decimal) {
  Ball r;
  arb_set_str(r.get(), decimal, 256);
  const char* dot = std::strchr(decimal, '.');
  const long decimals = dot ? static_cast<long>(std::strlen(dot + 1)) : 0;
  mag_t m;
  mag_init(m);
  mag_set_ui_2exp_si(m, 1, -static_cast<slong>(decimals * 3.3219280948873623) + 1);
  arb_add_error_mag(r.get(), m);
  mag_clear(m);
  return arb_overlaps(b.get(), r.get());
}

/// The closed forms of the angular speed K / (1 + K^2 t^2), K = 2C, of the
/// parabola (t, C t^2) on [0, 1], at precision prec: mu = atan K and
/// u = mu^2 / int sigma^2 with int sigma^2 = (K / 2)(atan K + K / (1 + K^2)).
struct ParabolaAngular {
  Ball mu, u;
};
inline ParabolaAngular parabola_angular(const Ball& c, long prec) {
  ParabolaAngular r;
  Ball k, t, sq;
  arb_mul_2exp_si(k.get(), c.get(), 1);
  arb_atan(r.mu.get(), k.get(), prec);
  arb_sqr(t.get(), k.get(), prec);
  arb_add_ui(t.get(), t.get(), 1, prec);
  arb_div(t.get(), k.get(), t.get(), prec);
  arb_add(sq.get(), r.mu.get(), t.get(), prec);
  arb_mul(sq.get(), sq.get(), k.get(), prec);
  arb_mul_2exp_si(sq.get(), sq.get(), -1);
  arb_sqr(r.u.get(), r.mu.get(), prec);
  arb_div(r.u.get(), r.u.get(), sq.get(), prec);
  return r;
}

/// The local Moebius map x = (1-a) u / ((1-a) u + a (1-u)) and dx/du =
/// a (1-a) / den^2, by the plain formulas (a test oracle).
inline void local_moebius(Ball& x, Ball& dx, const Ball& u, const Ball& a, long prec) {
  Ball one_a, den, w;
  arb_sub_si(one_a.get(), a.get(), 1, prec);
  arb_neg(one_a.get(), one_a.get());
  arb_mul(x.get(), one_a.get(), u.get(), prec);
  arb_sub_si(w.get(), u.get(), 1, prec);
  arb_neg(w.get(), w.get());
  arb_mul(w.get(), w.get(), a.get(), prec);
  arb_add(den.get(), x.get(), w.get(), prec);
  arb_div(x.get(), x.get(), den.get(), prec);
  arb_mul(dx.get(), a.get(), one_a.get(), prec);
  arb_div(dx.get(), dx.get(), den.get(), prec);
  arb_div(dx.get(), dx.get(), den.get(), prec);
}

}  // namespace uniparam::test_support
