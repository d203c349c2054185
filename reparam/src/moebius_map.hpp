// moebius_map.hpp -- the local Moebius map of a piece, written once (internal
// to uniparam_reparam), over three number types: real balls (BallMapArith),
// complex balls (AcbMapArith) and exact rationals (RationalMapArith).
//
// On the local coordinate u in [0, 1] of a piece, with weights p, q > 0,
//     x(u) = p u / (p u + q (1 - u)),    dx/du = p q / den^2,
// den = p u + q (1 - u). x fixes 0 and 1, and increases from 0 to 1. The
// Moebius parameter alpha of a piece (docs/math.md (2.1)) is p = 1 - alpha,
// q = alpha; the balancing map m of scaling.hpp on a piece is p = k, q = 1.
#pragma once

#include <acb.h>
#include <arb.h>

#include "speed_enclosure.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam::detail {

/// Real balls at precision prec; values are arb_ptr, temporaries Ball.
struct BallMapArith {
  using ptr = arb_ptr;
  using srcptr = arb_srcptr;
  using Box = Ball;
  long prec;
  static ptr at(Box& b) { return b.get(); }
  void one_minus(ptr r, srcptr a) const {
    arb_sub_ui(r, a, 1, prec);
    arb_neg(r, r);
  }
  void mul(ptr r, srcptr a, srcptr b) const { arb_mul(r, a, b, prec); }
  void add(ptr r, srcptr a, srcptr b) const { arb_add(r, a, b, prec); }
  void div(ptr r, srcptr a, srcptr b) const { arb_div(r, a, b, prec); }
  static void set(ptr r, srcptr a) { arb_set(r, a); }
  static bool is_zero(srcptr a) { return arb_is_zero(a); }
  static bool is_one(srcptr a) { return arb_is_one(a); }
};

/// Complex balls at precision prec; values are acb_ptr, temporaries AcbBox.
struct AcbMapArith {
  using ptr = acb_ptr;
  using srcptr = acb_srcptr;
  using Box = AcbBox;
  long prec;
  static ptr at(Box& b) { return b.get(); }
  void one_minus(ptr r, srcptr a) const {
    acb_sub_ui(r, a, 1, prec);
    acb_neg(r, r);
  }
  void mul(ptr r, srcptr a, srcptr b) const { acb_mul(r, a, b, prec); }
  void add(ptr r, srcptr a, srcptr b) const { acb_add(r, a, b, prec); }
  void div(ptr r, srcptr a, srcptr b) const { acb_div(r, a, b, prec); }
  static void set(ptr r, srcptr a) { acb_set(r, a); }
  static bool is_zero(srcptr a) { return acb_is_zero(a); }
  static bool is_one(srcptr a) { return acb_is_one(a); }
};

/// Exact rationals; values are Rational*.
struct RationalMapArith {
  using ptr = Rational*;
  using srcptr = const Rational*;
  using Box = Rational;
  static ptr at(Box& b) { return &b; }
  static void one_minus(ptr r, srcptr a) { *r = Rational(1) - *a; }
  static void mul(ptr r, srcptr a, srcptr b) { *r = *a * *b; }
  static void add(ptr r, srcptr a, srcptr b) { *r = *a + *b; }
  static void div(ptr r, srcptr a, srcptr b) { *r = *a / *b; }
  static void set(ptr r, srcptr a) { *r = *a; }
  static bool is_zero(srcptr a) { return a->sign() == 0; }
  static bool is_one(srcptr a) { return *a == Rational(1); }
};

/// The local Moebius map x(u) = p u / (p u + q (1 - u)) with weight q (q ==
/// nullptr stands for q = 1, with no multiplication by it) in the arithmetic A.
/// Writes x (if non-null), dx/du = p q / den^2 (if non-null) and den = p u +
/// q (1 - u) (if non-null); outputs may not alias u, p or q.
/// \pre p, q enclose positive numbers and u a part of [0, 1] (then den holds
///      no zero); not checked.
/// \post every output contains the exact value for every u, p, q inside the
///       inputs; an exact u = 0 or u = 1 gives x = u exactly (the map's
///       fixed points: the ball quotient p / p would not be exact).
template <class A>
void moebius_map(const A& o, typename A::ptr x, typename A::ptr dx, typename A::ptr den, typename A::srcptr u,
                 typename A::srcptr p, typename A::srcptr q) {
  typename A::Box num_box, den_box;
  const typename A::ptr num = A::at(num_box), d = A::at(den_box);
  o.mul(num, p, u);  // p u
  o.one_minus(d, u);
  if (q) o.mul(d, d, q);  // q (1 - u)
  o.add(d, d, num);
  if (dx) {
    if (q) o.mul(dx, q, p);
    else A::set(dx, p);
    o.div(dx, dx, d);
    o.div(dx, dx, d);
  }
  if (x) {
    if (A::is_zero(u) || A::is_one(u)) A::set(x, u);
    else o.div(x, num, d);
  }
  if (den) A::set(den, d);
}

/// The local Moebius map of a piece with Moebius parameter alpha
/// (docs/math.md (2.1)): x(u) = (1 - alpha) u / ((1 - alpha) u + alpha (1 - u)),
/// dx/du = alpha (1 - alpha) / den^2. moebius_map with p = 1 - alpha,
/// q = alpha: the same contract, for 0 < alpha < 1.
template <class A>
void moebius_alpha_map(const A& o, typename A::ptr x, typename A::ptr dx, typename A::srcptr u,
                       typename A::srcptr alpha) {
  typename A::Box p_box;
  const typename A::ptr p = A::at(p_box);
  o.one_minus(p, alpha);
  moebius_map(o, x, dx, nullptr, u, p, alpha);
}

/// The local coordinate of an exact end: when z is exact and equals the exact
/// ball lo (hi), sets u to exactly 0 (1). (z - lo) / (hi - lo) of correlated
/// balls would keep the radius of the other end, and an exact end must map
/// exactly onto the piece's breakpoint.
inline void pin_exact_end(arb_t u, const Ball& z, const Ball& lo, const Ball& hi) {
  if (!z.is_exact()) return;
  if (lo.is_exact() && arb_equal(z.get(), lo.get())) arb_zero(u);
  else if (hi.is_exact() && arb_equal(z.get(), hi.get())) arb_one(u);
}

}  // namespace uniparam::detail
