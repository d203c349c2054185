// uniparam/core/number.hpp -- exact integers and rationals (RAII over FLINT's
// fmpz and fmpq).
//
// Values are always exact. There is deliberately no constructor from double:
// 0.1 is 1/10 only when the text "0.1" is parsed (see parser.hpp).
#pragma once

#include <flint/fmpq.h>
#include <flint/fmpz.h>

#include <string>

namespace uniparam {

/// An exact integer.
class Integer {
 public:
  /// 0, and the exact value of a machine integer.
  Integer() noexcept { fmpz_init(v_); }
  Integer(long x) noexcept { fmpz_init_set_si(v_, x); }  // NOLINT: exact
  Integer(int x) noexcept : Integer(static_cast<long>(x)) {}  // NOLINT: beats the fmpz_t overload for 0
  Integer(double) = delete;  // no silent rounding: parse the decimal text instead
  /// Parses a decimal integer (optional leading '-'); throws InvalidArgument.
  explicit Integer(const std::string& decimal);
  /// A copy of FLINT's x.
  explicit Integer(const fmpz_t x) noexcept { fmpz_init_set(v_, x); }
  /// Copies are exact; a moved-from Integer holds some valid integer.
  Integer(const Integer& o) noexcept { fmpz_init_set(v_, o.v_); }
  Integer(Integer&& o) noexcept { fmpz_init(v_); fmpz_swap(v_, o.v_); }
  Integer& operator=(const Integer& o) noexcept { fmpz_set(v_, o.v_); return *this; }
  Integer& operator=(Integer&& o) noexcept { fmpz_swap(v_, o.v_); return *this; }
  ~Integer() { fmpz_clear(v_); }

  /// The fmpz itself, for FLINT's functions.
  fmpz* get() noexcept { return v_; }
  const fmpz* get() const noexcept { return v_; }

  /// -1, 0 or 1.
  int sign() const noexcept { return fmpz_sgn(v_); }
  /// Number of bits of |x| (0 for x = 0).
  long bits() const noexcept { return static_cast<long>(fmpz_bits(v_)); }
  /// The decimal digits, with a leading '-' when negative.
  std::string str() const;

  /// Exact comparisons and ring operations (never overflow, never throw but
  /// for memory).
  friend bool operator==(const Integer& a, const Integer& b) noexcept { return fmpz_equal(a.v_, b.v_); }
  friend bool operator!=(const Integer& a, const Integer& b) noexcept { return !(a == b); }
  friend bool operator<(const Integer& a, const Integer& b) noexcept { return fmpz_cmp(a.v_, b.v_) < 0; }
  friend Integer operator+(const Integer& a, const Integer& b);
  friend Integer operator-(const Integer& a, const Integer& b);
  friend Integer operator*(const Integer& a, const Integer& b);

 private:
  fmpz_t v_;
};

/// An exact rational number, always in canonical form (gcd 1, positive
/// denominator).
class Rational {
 public:
  /// 0, and the exact value of a machine integer.
  Rational() noexcept { fmpq_init(v_); }
  Rational(long x) noexcept { fmpq_init(v_); fmpq_set_si(v_, x, 1); }  // NOLINT: exact
  Rational(int x) noexcept : Rational(static_cast<long>(x)) {}  // NOLINT: beats the fmpq_t overload for 0
  Rational(double) = delete;  // 0.1 is 1/10 only via Rational::parse("0.1")
  /// num/den; throws DomainError when den == 0.
  Rational(const Integer& num, const Integer& den);
  Rational(long num, long den);
  /// The integer x.
  explicit Rational(const Integer& x) noexcept { fmpq_init(v_); fmpz_set(fmpq_numref(v_), x.get()); }
  /// A copy of FLINT's x. \pre x canonical (as every fmpq FLINT returns).
  explicit Rational(const fmpq_t x) noexcept { fmpq_init(v_); fmpq_set(v_, x); }
  /// Parses "a", "-a", "a/b" or a decimal "1.25", "-0.1", "1e-3" exactly.
  /// Throws ParseError (column within the string) on anything else.
  static Rational parse(const std::string& text);
  /// The simplest rational (smallest denominator, then smallest numerator in
  /// absolute value) in the closed interval [lo, hi]. \pre lo <= hi
  /// (checked: InvalidArgument).
  static Rational simplest_between(const Rational& lo, const Rational& hi);
  /// Copies are exact; a moved-from Rational holds some valid rational.
  Rational(const Rational& o) noexcept { fmpq_init(v_); fmpq_set(v_, o.v_); }
  Rational(Rational&& o) noexcept { fmpq_init(v_); fmpq_swap(v_, o.v_); }
  Rational& operator=(const Rational& o) noexcept { fmpq_set(v_, o.v_); return *this; }
  Rational& operator=(Rational&& o) noexcept { fmpq_swap(v_, o.v_); return *this; }
  ~Rational() { fmpq_clear(v_); }

  /// The fmpq itself, for FLINT's functions. \post a caller writing
  /// through it leaves it canonical (FLINT's fmpq functions do).
  fmpq* get() noexcept { return v_; }
  const fmpq* get() const noexcept { return v_; }

  /// Numerator and (positive) denominator of the canonical form; the sign
  /// (-1, 0, 1); whether it is 0 or an integer.
  Integer num() const { return Integer(fmpq_numref(v_)); }
  Integer den() const { return Integer(fmpq_denref(v_)); }
  int sign() const noexcept { return fmpq_sgn(v_); }
  bool is_zero() const noexcept { return fmpq_is_zero(v_); }
  bool is_integer() const noexcept { return fmpz_is_one(fmpq_denref(v_)); }
  /// "a" or "a/b".
  std::string str() const;

  /// Exact comparisons and field operations (never rounded).
  friend bool operator==(const Rational& a, const Rational& b) noexcept { return fmpq_equal(a.v_, b.v_); }
  friend bool operator!=(const Rational& a, const Rational& b) noexcept { return !(a == b); }
  friend bool operator<(const Rational& a, const Rational& b) noexcept { return fmpq_cmp(a.v_, b.v_) < 0; }
  friend bool operator<=(const Rational& a, const Rational& b) noexcept { return fmpq_cmp(a.v_, b.v_) <= 0; }
  friend bool operator>(const Rational& a, const Rational& b) noexcept { return fmpq_cmp(a.v_, b.v_) > 0; }
  friend bool operator>=(const Rational& a, const Rational& b) noexcept { return fmpq_cmp(a.v_, b.v_) >= 0; }
  friend Rational operator+(const Rational& a, const Rational& b);
  friend Rational operator-(const Rational& a, const Rational& b);
  friend Rational operator*(const Rational& a, const Rational& b);
  /// Throws DomainError on division by zero.
  friend Rational operator/(const Rational& a, const Rational& b);
  Rational operator-() const;

 private:
  fmpq_t v_;
};

/// 2^e as an exact rational, for any e (e < 0 gives 1 / 2^-e).
Rational pow2(long e);

/// The largest multiple of 2^s that is <= x, i.e. floor(x / 2^s) 2^s,
/// exact; s may be negative (a grid of step 2^s finer than the integers).
/// The ceiling on the same grid is -grid_floor(-x, s).
Rational grid_floor(const Rational& x, long s);

}  // namespace uniparam
