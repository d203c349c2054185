// uniparam/core/ball_poly.hpp -- polynomials with real ball coefficients
// (RAII over Arb's arb_poly_t). Each coefficient encloses the exact one; by
// the ball rule, evaluation encloses the value of every polynomial whose
// coefficients lie in the balls.
#pragma once

#include <acb.h>
#include <arb_poly.h>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// A polynomial with real ball coefficients (see above).
class BallPoly {
 public:
  /// The zero polynomial.
  BallPoly() noexcept { arb_poly_init(v_); }
  /// The exact integer polynomial p (exact balls; no rounding).
  explicit BallPoly(const Poly& p) noexcept { arb_poly_init(v_); arb_poly_set_fmpz_poly(v_, p.get(), ARF_PREC_EXACT); }
  /// Copies are exact; a moved-from BallPoly holds some valid polynomial.
  BallPoly(const BallPoly& o) noexcept { arb_poly_init(v_); arb_poly_set(v_, o.v_); }
  BallPoly(BallPoly&& o) noexcept { arb_poly_init(v_); arb_poly_swap(v_, o.v_); }
  BallPoly& operator=(const BallPoly& o) noexcept { arb_poly_set(v_, o.v_); return *this; }
  BallPoly& operator=(BallPoly&& o) noexcept { arb_poly_swap(v_, o.v_); return *this; }
  ~BallPoly() { arb_poly_clear(v_); }

  /// The arb_poly_t itself, for Arb's functions.
  arb_poly_struct* get() noexcept { return v_; }
  const arb_poly_struct* get() const noexcept { return v_; }

  /// The number of stored coefficients (degree() + 1; 0 for the zero
  /// polynomial) and the degree (-1 for the zero polynomial).
  long length() const noexcept { return arb_poly_length(v_); }
  long degree() const noexcept { return arb_poly_degree(v_); }
  /// The ball coefficient of t^i: exactly 0 for i > degree(). \pre i >= 0.
  Ball coeff(long i) const { Ball c; arb_poly_get_coeff_arb(c.get(), v_, i); return c; }

  /// Enclosure of p(x) for real x.
  Ball operator()(const Ball& x, long prec) const { Ball r; arb_poly_evaluate(r.get(), v_, x.get(), prec); return r; }
  /// Enclosure of p(z) for complex z (Horner in ball arithmetic).
  void evaluate(acb_t out, const acb_t z, long prec) const { arb_poly_evaluate_acb(out, v_, z, prec); }

 private:
  arb_poly_t v_;
};

/// out(w) = in(w + s 2^e), s = +1 or -1 (InvalidArgument otherwise): a
/// Taylor shift by a signed power of two, as the local expansions of
/// algebra/ need (a child cell's centre is its parent's plus or minus half
/// its width). The coefficients are scaled by 2^(e k) (exact), shifted by
/// +-1, and scaled back by 2^(-e k) (exact). The shift by +-1 takes the
/// midpoints as exact integers on the grid of their lowest bit, shifts them
/// exactly (FLINT, additions only) and rounds each result once to prec; the
/// radii are shifted with upper-bound arithmetic. Several times cheaper
/// than Arb's arb_poly_taylor_shift (ball multiply-adds). Non-finite balls,
/// and midpoints spanning more than 2^16 + 16 prec bits, fall back to a
/// ball Horner scheme (additions). out may alias in.
/// \post each coefficient of out encloses the corresponding coefficient of
///       q(w + s 2^e) for every polynomial q whose coefficients lie in in's
///       balls.
void taylor_shift_pow2(arb_poly_t out, const arb_poly_t in, long e, int s, long prec);

}  // namespace uniparam
