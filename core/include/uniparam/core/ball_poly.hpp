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

class BallPoly {
 public:
  BallPoly() noexcept { arb_poly_init(v_); }
  /// The exact integer polynomial p (exact balls; no rounding).
  explicit BallPoly(const Poly& p) noexcept { arb_poly_init(v_); arb_poly_set_fmpz_poly(v_, p.get(), ARF_PREC_EXACT); }
  BallPoly(const BallPoly& o) noexcept { arb_poly_init(v_); arb_poly_set(v_, o.v_); }
  BallPoly(BallPoly&& o) noexcept { arb_poly_init(v_); arb_poly_swap(v_, o.v_); }
  BallPoly& operator=(const BallPoly& o) noexcept { arb_poly_set(v_, o.v_); return *this; }
  BallPoly& operator=(BallPoly&& o) noexcept { arb_poly_swap(v_, o.v_); return *this; }
  ~BallPoly() { arb_poly_clear(v_); }

  arb_poly_struct* get() noexcept { return v_; }
  const arb_poly_struct* get() const noexcept { return v_; }

  long length() const noexcept { return arb_poly_length(v_); }
  long degree() const noexcept { return arb_poly_degree(v_); }
  Ball coeff(long i) const { Ball c; arb_poly_get_coeff_arb(c.get(), v_, i); return c; }

  /// Enclosure of p(x) for real x.
  Ball operator()(const Ball& x, long prec) const { Ball r; arb_poly_evaluate(r.get(), v_, x.get(), prec); return r; }
  /// Enclosure of p(z) for complex z (Horner in ball arithmetic).
  void evaluate(acb_t out, const acb_t z, long prec) const { arb_poly_evaluate_acb(out, v_, z, prec); }

 private:
  arb_poly_t v_;
};

}  // namespace uniparam
