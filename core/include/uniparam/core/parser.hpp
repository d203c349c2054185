// uniparam/core/parser.hpp -- exact parser of expressions and curves in t.
//
// Grammar (whitespace ignored):
//   tuple   := '(' expr (',' expr)* ')'  |  '[' expr (',' expr)* ']'
//   expr    := term (('+' | '-') term)*
//   term    := factor (('*' | '/') factor | implicit-factor)*
//   factor  := ('+' | '-') factor | power
//   power   := primary ('^' exponent)?          (right associative: t^2^3 = t^8)
//   exponent:= ['+'|'-'] integer | '(' ['+'|'-'] integer ')'
//   primary := number | 't' | '(' expr ')'
//   number  := digits ['.' digits] [('e'|'E') ['+'|'-'] digits] | '.' digits
// Implicit multiplication is accepted where unambiguous: "2t", "3(t+1)",
// "(t+1)(t-1)", "2t^2". Decimals are read exactly (0.1 = 1/10). Exponents are
// integers; negative exponents invert. `-t^2` is -(t^2).
#pragma once

#include <string>
#include <vector>

#include "uniparam/core/ratfunc.hpp"

namespace uniparam {

/// Limits that keep hostile input from exhausting memory, time or the stack.
/// Each BudgetExceeded message names the limit and the uniparam option that
/// sets it on the command line (docs/robustness.md):
///   max_length   --max-length     max_exponent, max_degree   --max-degree
///   max_depth    --max-depth      max_bits                   --max-bits
/// (the CLI sets max_exponent = max_degree: a larger exponent of a
/// non-constant base exceeds the degree limit anyway).
struct ParseLimits {
  std::size_t max_length = 1u << 20;  ///< characters of input
  long max_exponent = 10000;          ///< |exponent| allowed after '^'
  long max_degree = 20000;            ///< of any intermediate numerator/denominator
  int max_depth = 500;                ///< nesting of parentheses, unary signs and '^' chains
  /// Size of any intermediate polynomial or number literal, in bits:
  /// (degree + 1) * bits of its largest coefficient, checked before it is
  /// computed. The default 2^28 bits is 32 MiB.
  long max_bits = 1L << 28;
};

/// Parses one expression in t into an exact, canonical rational function.
/// \throws ParseError with the 1-based column and what was expected
///         (unbalanced parentheses, dangling operators, unknown symbols such
///         as 'x' or 'sin', non-integer exponents, empty input, non-ASCII bytes);
///         DomainError on division by zero (the message gives the column);
///         BudgetExceeded when a ParseLimits bound is exceeded (the message
///         names the limit, its value and the option that raises it).
RatFunc parse_expression(const std::string& text, const ParseLimits& limits = {});

/// Parses a parenthesised or bracketed tuple "(x(t), y(t), ...)" of >= 1
/// expressions. Same errors as parse_expression, plus ParseError for empty
/// components "(t, )" and trailing text after the closing bracket.
std::vector<RatFunc> parse_tuple(const std::string& text, const ParseLimits& limits = {});

}  // namespace uniparam
