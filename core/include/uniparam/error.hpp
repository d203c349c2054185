// uniparam/error.hpp -- the exception hierarchy of the whole library, public
// (the facade uniparam/uniparam.hpp and the engine throw the same types).
//
// The library never calls exit() or abort(); every failure is one of these
// types, so callers can tell "your input is wrong" from "the mathematics is
// undefined" from "the budget was too small to certify".
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace uniparam {

/// Base of every uniparam exception.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Text that is not a valid expression, curve or number.
/// `column()` is the 1-based column where the problem was detected,
/// `expected()` a short description of what would have been valid there.
class ParseError : public Error {
 public:
  ParseError(std::size_t column, std::string expected, const std::string& detail)
      : Error("parse error at column " + std::to_string(column) + ": " + detail +
              (expected.empty() ? std::string() : " (expected " + expected + ")")),
        column_(column), expected_(std::move(expected)) {}
  /// The 1-based column, and what would have been valid there ("" when
  /// nothing short says it).
  std::size_t column() const noexcept { return column_; }
  const std::string& expected() const noexcept { return expected_; }

 private:
  std::size_t column_;
  std::string expected_;
};

/// A well-formed request whose mathematics is undefined: division by zero,
/// a pole of the curve in [0, 1], a constant curve, a non-regular point.
class DomainError : public Error {
 public:
  using Error::Error;
};

/// A well-formed request outside what an option allows (digits < 1, ...).
class InvalidArgument : public Error {
 public:
  using Error::Error;
};

/// A value that could not be certified within a budget (precision, degree,
/// evaluations, time). The message names the limit and the option that
/// raises it. Nothing uncertified is ever returned in its place.
class BudgetExceeded : public Error {
 public:
  using Error::Error;
};

/// The wall-clock time budget ran out (TimeBudget, --timeout; core/budget.hpp).
/// Its message always names the time limit and --timeout. It is its own type
/// so that code that reports its own failures (a precision loop giving up,
/// a fallback after a failed attempt) can tell it apart and let it through:
/// a timeout is never reported as a precision or other budget failure.
class TimeLimitExceeded : public BudgetExceeded {
 public:
  using BudgetExceeded::BudgetExceeded;
};

/// The computation was cancelled from outside (ScopedCancellation,
/// core/budget.hpp; the Python module's Ctrl-C). A TimeLimitExceeded, so
/// every place that lets a timeout through lets a cancellation through too.
class Interrupted : public TimeLimitExceeded {
 public:
  using TimeLimitExceeded::TimeLimitExceeded;
};

}  // namespace uniparam
