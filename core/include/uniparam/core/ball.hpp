// uniparam/core/ball.hpp -- real balls [mid +- rad] (RAII over Arb's arb_t).
//
// The ball rule (Arb's): every operation's output contains the exact result
// for every choice of inputs inside the input balls. A Ball never pretends
// to be a number: comparisons are "certainly" predicates (false means
// "not proven", not "false").
#pragma once

#include <arb.h>

#include <string>
#include <vector>

#include "uniparam/core/number.hpp"

namespace uniparam {

class Ball {
 public:
  /// The exact 0.
  Ball() noexcept { arb_init(v_); }
  /// The exact integer x.
  explicit Ball(long x) noexcept { arb_init(v_); arb_set_si(v_, x); }
  explicit Ball(int x) noexcept : Ball(static_cast<long>(x)) {}  // beats the arb_t overload for 0
  Ball(double) = delete;  // a double is not an enclosure of the number it was meant to be
  /// An enclosure of x rounded to prec bits (exact when representable).
  Ball(const Rational& x, long prec) noexcept { arb_init(v_); arb_set_fmpq(v_, x.get(), prec); }
  /// The exact integer x.
  explicit Ball(const Integer& x) noexcept { arb_init(v_); arb_set_fmpz(v_, x.get()); }
  /// A copy of Arb's ball x (the same midpoint and radius).
  explicit Ball(const arb_t x) noexcept { arb_init(v_); arb_set(v_, x); }
  /// Copies are exact; a moved-from Ball holds some valid ball (0 after a
  /// move construction).
  Ball(const Ball& o) noexcept { arb_init(v_); arb_set(v_, o.v_); }
  Ball(Ball&& o) noexcept { arb_init(v_); arb_swap(v_, o.v_); }
  Ball& operator=(const Ball& o) noexcept { arb_set(v_, o.v_); return *this; }
  Ball& operator=(Ball&& o) noexcept { arb_swap(v_, o.v_); return *this; }
  ~Ball() { arb_clear(v_); }

  /// The arb_t itself, for Arb's functions (which keep the ball rule).
  arb_struct* get() noexcept { return v_; }
  const arb_struct* get() const noexcept { return v_; }

  /// Certain predicates (Arb's arb_is_*, arb_contains*): true only when
  /// proven for every point of the ball, false for "not proven". is_finite:
  /// mid and rad finite; is_exact: rad = 0; certainly_positive/negative/zero:
  /// every point is > 0, < 0, = 0; contains(x): x (a rational, or every
  /// point of the ball x) lies in this ball.
  bool is_finite() const noexcept { return arb_is_finite(v_); }
  bool is_exact() const noexcept { return arb_is_exact(v_); }
  bool certainly_positive() const noexcept { return arb_is_positive(v_); }
  bool certainly_negative() const noexcept { return arb_is_negative(v_); }
  bool certainly_zero() const noexcept { return arb_is_zero(v_); }
  bool contains(const Rational& x) const noexcept { return arb_contains_fmpq(v_, x.get()); }
  bool contains(const Ball& x) const noexcept { return arb_contains(v_, x.v_); }
  /// True when rad <= 10^-digits * max(1, |mid|): the accuracy contract of
  /// every reported number.
  bool meets_digits(long digits) const;

  /// The midpoint, in decimal with up to `digits` significant digits and
  /// rounded to nearest, e.g. "1.24904577239825"; "0" for zero.
  std::string mid_decimal(long digits) const;
  /// An upper bound of the radius, in decimal (3 significant digits,
  /// rounded up), e.g. "3.12e-17"; "0" for an exact ball.
  std::string rad_decimal() const;
  /// Arb's own notation "[mid +/- rad]" at `digits` digits.
  std::string str(long digits = 20) const;

 private:
  arb_t v_;
};

/// Replaces the real ball x by a ball enclosing its intersection with [0, 1]
/// (by the nearest end when they do not meet). For enclosing a monotone map's
/// argument that is known to lie in [0, 1].
void clamp_unit(arb_t x, long prec);

/// The midpoint of b as an exact rational. \pre the midpoint finite
/// (checked: DomainError).
Rational mid_rational(const Ball& b);
/// The radius of b as an exact rational (Arb's radius is a dyadic number,
/// so nothing is rounded). \pre the radius finite (checked: DomainError).
Rational rad_rational(const Ball& b);

/// A ball containing the closed interval between lo and hi (either order):
/// the union of their enclosures at prec bits.
Ball interval_ball(const Rational& lo, const Rational& hi, long prec);

/// Whether every ball of v meets_digits(digits) (true for an empty v).
bool all_meet_digits(const std::vector<Ball>& v, long digits);

/// The normalised cumulative sums of w (N = w.size() >= 1): out[0] = 0 and
/// out[N] = 1 exactly, out[i] a ball containing (w_0 + ... + w_{i-1}) / total
/// for 0 < i < N, at `prec` bits. Precondition: total encloses the sum of w
/// (a ball containing 0 gives indeterminate quotients, never wrong ones).
std::vector<Ball> cumulative_normalised(const std::vector<Ball>& w, const Ball& total, long prec);

/// The same for exact rationals or doubles: out[0] = 0 and out[N] = 1
/// exactly, out[i] = (w_0 + ... + w_{i-1}) / total for 0 < i < N, the sums
/// taken left to right (T = Rational: exact; T = double: each sum and
/// quotient rounded to nearest). Precondition: total != 0 (for Rational,
/// Rational's division by zero reports it).
template <class T>
std::vector<T> cumulative_normalised(const std::vector<T>& w, const T& total) {
  std::vector<T> out{T(0)};
  T acc(0);
  for (std::size_t k = 0; k + 1 < w.size(); ++k) {
    acc = acc + w[k];
    out.push_back(acc / total);
  }
  out.push_back(T(1));
  return out;
}

}  // namespace uniparam
