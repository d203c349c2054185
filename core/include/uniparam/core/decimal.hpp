// uniparam/core/decimal.hpp -- exact decimal formatting of rationals and
// rigorous decimal enclosures of balls.
#pragma once

#include <string>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {

/// x rounded to nearest with `sig_digits` (>= 1) significant digits, in plain
/// decimal notation ("0.000123", "1249.05") when the decimal exponent lies in
/// [-7, 21), scientific ("1.25e-30") otherwise. "0" for zero.
std::string decimal_string(const Rational& x, long sig_digits);

/// Rounds a nonnegative rational *up* to 2 significant digits, as a decimal
/// string ("3.2e-17", "0.0015", "0" for zero).
std::string decimal_upper(const Rational& x);

/// A decimal enclosure of a ball: the true value lies in [mid - rad, mid + rad]
/// where mid and rad are read as exact decimals. The printed midpoint has
/// `sig_digits` significant digits; its rounding error is added to rad, so
/// the enclosure is at least as wide as the ball (never narrower).
struct DecimalEnclosure {
  std::string mid;
  std::string rad;
};
/// Throws DomainError if the ball is not finite.
DecimalEnclosure decimal_enclosure(const Ball& x, long sig_digits);

}  // namespace uniparam
