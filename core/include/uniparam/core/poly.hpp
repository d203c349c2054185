// uniparam/core/poly.hpp -- dense polynomials in Z[t] (RAII over fmpz_poly).
#pragma once

#include <flint/fmpz_poly.h>

#include <string>
#include <vector>

#include "uniparam/core/number.hpp"

namespace uniparam {

/// A polynomial with integer coefficients. Degree of 0 is -1.
class Poly {
 public:
  /// The zero polynomial.
  Poly() noexcept { fmpz_poly_init(v_); }
  /// The constant c.
  Poly(long c) noexcept { fmpz_poly_init(v_); fmpz_poly_set_si(v_, c); }  // NOLINT: exact
  Poly(int c) noexcept : Poly(static_cast<long>(c)) {}  // NOLINT: beats the fmpz_poly_t overload for 0
  Poly(double) = delete;
  /// Coefficients from low to high degree.
  explicit Poly(const std::vector<Integer>& coeffs_low_to_high);
  explicit Poly(const std::vector<long>& coeffs_low_to_high);
  /// A copy of FLINT's p.
  explicit Poly(const fmpz_poly_t p) noexcept { fmpz_poly_init(v_); fmpz_poly_set(v_, p); }
  /// The polynomial t.
  static Poly t();
  /// Copies are exact; a moved-from Poly holds some valid polynomial.
  Poly(const Poly& o) noexcept { fmpz_poly_init(v_); fmpz_poly_set(v_, o.v_); }
  Poly(Poly&& o) noexcept { fmpz_poly_init(v_); fmpz_poly_swap(v_, o.v_); }
  Poly& operator=(const Poly& o) noexcept { fmpz_poly_set(v_, o.v_); return *this; }
  Poly& operator=(Poly&& o) noexcept { fmpz_poly_swap(v_, o.v_); return *this; }
  ~Poly() { fmpz_poly_clear(v_); }

  /// The fmpz_poly itself, for FLINT's functions.
  fmpz_poly_struct* get() noexcept { return v_; }
  const fmpz_poly_struct* get() const noexcept { return v_; }

  /// The degree (-1 for the zero polynomial); whether it is zero.
  long degree() const noexcept { return fmpz_poly_degree(v_); }
  bool is_zero() const noexcept { return fmpz_poly_is_zero(v_); }
  /// The coefficient of t^i: 0 for i < 0 or i > degree().
  Integer coeff(long i) const;
  /// The coefficient of t^degree() (0 for the zero polynomial).
  Integer leading() const { return coeff(degree()); }
  /// Max bits of the coefficients' absolute values.
  long max_bits() const noexcept;
  /// The exact derivative d/dt.
  Poly derivative() const;
  /// Exact value at a rational point.
  Rational operator()(const Rational& x) const;
  /// Sign of the value at x (-1, 0, 1), exact: from a ball evaluation where
  /// that excludes 0 (128 then 512 bits), else from the exact value.
  int sign_at(const Rational& x) const;
  /// Divides by the content and makes the leading coefficient positive
  /// (the zero polynomial stays zero).
  Poly primitive() const;
  /// Plain text in t, e.g. "3*t^2 - t + 1".
  std::string str(const char* var = "t") const;

  /// Exact comparisons and ring operations; pow(e) is the e-th power
  /// (pow(0) = 1).
  friend bool operator==(const Poly& a, const Poly& b) noexcept { return fmpz_poly_equal(a.v_, b.v_); }
  friend bool operator!=(const Poly& a, const Poly& b) noexcept { return !(a == b); }
  friend Poly operator+(const Poly& a, const Poly& b);
  friend Poly operator-(const Poly& a, const Poly& b);
  friend Poly operator*(const Poly& a, const Poly& b);
  Poly operator-() const;
  Poly pow(unsigned long e) const;

 private:
  fmpz_poly_t v_;
};

/// gcd with positive leading coefficient (gcd(0, 0) = 0).
Poly gcd(const Poly& a, const Poly& b);
/// Exact quotient a / b; throws DomainError if b does not divide a.
Poly divexact(const Poly& a, const Poly& b);
/// q(s) = 2^n p((1 + s) / 2), n = deg p, exactly: p in the basis centred at
/// 1/2 and scaled to [-1, 1] (an exact Taylor shift of 2^n p(u / 2) by 1).
/// The zero polynomial gives itself.
Poly centred_at_half(const Poly& p);
/// G(x) = L^n f(a + (b - a) x) / content, n = deg f, L the least integer
/// making it integral: f on [a, b] mapped to [0, 1] (b < a runs backwards),
/// exactly, so the roots of G in [0, 1] are those of f in [a, b], and the
/// roots of G are those of f less a, divided by b - a.
/// \pre a != b; f != 0.
Poly mapped_to_unit_interval(const Poly& f, const Rational& a, const Rational& b);
/// The coefficients a[0 .. n] of p (n + 1 of them; none for 0) as IEEE
/// doubles, all scaled by one power of 2 (the largest into [1/2, 1)): each
/// within 2^-52 of itself, relatively, or below 2^-1073 (the ones below
/// 2^-2000 of the largest become 0).
std::vector<double> scaled_doubles(const Poly& p);

}  // namespace uniparam
