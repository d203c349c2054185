// uniparam/core/ratfunc.hpp -- rational functions in Q(t) (RAII over
// fmpz_poly_q), always canonical: numerator and denominator in Z[t] coprime
// (content included) and the denominator's leading coefficient positive.
// Two equal rational functions therefore have equal representations.
#pragma once

#include <flint/fmpz_poly_q.h>

#include <string>

#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {

/// A rational function with rational coefficients, canonical (see above).
class RatFunc {
 public:
  /// 0, and the exact constant c.
  RatFunc() noexcept { fmpz_poly_q_init(v_); }
  RatFunc(long c) noexcept { fmpz_poly_q_init(v_); fmpz_poly_q_set_si(v_, c); }  // NOLINT: exact
  RatFunc(int c) noexcept : RatFunc(static_cast<long>(c)) {}  // NOLINT: beats the pointer overload for 0
  RatFunc(double) = delete;
  /// The constant c; the polynomial p (over the denominator 1).
  explicit RatFunc(const Rational& c);
  explicit RatFunc(const Poly& p);
  /// num/den canonicalised; throws DomainError when den is zero.
  RatFunc(const Poly& num, const Poly& den);
  /// The function t.
  static RatFunc t();
  /// Copies are exact; a moved-from RatFunc holds some valid function.
  RatFunc(const RatFunc& o) noexcept { fmpz_poly_q_init(v_); fmpz_poly_q_set(v_, o.v_); }
  RatFunc(RatFunc&& o) noexcept { fmpz_poly_q_init(v_); fmpz_poly_q_swap(v_, o.v_); }
  RatFunc& operator=(const RatFunc& o) noexcept { fmpz_poly_q_set(v_, o.v_); return *this; }
  RatFunc& operator=(RatFunc&& o) noexcept { fmpz_poly_q_swap(v_, o.v_); return *this; }
  ~RatFunc() { fmpz_poly_q_clear(v_); }

  /// The fmpz_poly_q itself, for FLINT's functions. \post a caller writing
  /// through it leaves it canonical (FLINT's fmpz_poly_q functions do).
  fmpz_poly_q_struct* get() noexcept { return v_; }
  const fmpz_poly_q_struct* get() const noexcept { return v_; }

  /// Numerator and denominator of the canonical form (coprime, the
  /// denominator's leading coefficient positive); whether it is 0.
  Poly num() const { return Poly(fmpz_poly_q_numref(v_)); }
  Poly den() const { return Poly(fmpz_poly_q_denref(v_)); }
  bool is_zero() const noexcept { return fmpz_poly_q_is_zero(v_); }
  /// True when the function is a constant (denominator and numerator of degree <= 0).
  bool is_constant() const noexcept;
  /// The exact derivative d/dt (canonical).
  RatFunc derivative() const;
  /// Exact value at x; throws DomainError when x is a pole.
  Rational operator()(const Rational& x) const;
  /// Plain text "(num)/(den)" or "num" when den = 1.
  std::string str(const char* var = "t") const;

  /// Exact comparisons and field operations, results canonical.
  friend bool operator==(const RatFunc& a, const RatFunc& b) noexcept { return fmpz_poly_q_equal(a.v_, b.v_); }
  friend bool operator!=(const RatFunc& a, const RatFunc& b) noexcept { return !(a == b); }
  friend RatFunc operator+(const RatFunc& a, const RatFunc& b);
  friend RatFunc operator-(const RatFunc& a, const RatFunc& b);
  friend RatFunc operator*(const RatFunc& a, const RatFunc& b);
  /// Throws DomainError when b is zero.
  friend RatFunc operator/(const RatFunc& a, const RatFunc& b);
  RatFunc operator-() const;
  /// Integer power; a negative exponent inverts (DomainError for 0^-k).
  RatFunc pow(long e) const;

 private:
  fmpz_poly_q_t v_;
};

/// f(g(x)), exact and canonical. \pre g's denominator does not vanish
/// identically after substitution (a constant g at a pole of f throws
/// DomainError).
RatFunc compose(const RatFunc& f, const RatFunc& g);

}  // namespace uniparam
