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

/// Limits that keep hostile input from exhausting memory or the stack.
struct ParseLimits {
  std::size_t max_length = 1u << 20;  ///< characters
  long max_exponent = 10000;          ///< |exponent| allowed after '^'
  long max_degree = 20000;            ///< of any intermediate numerator/denominator
  int max_depth = 500;                ///< parenthesis nesting
};

/// Parses one expression in t into an exact, canonical rational function.
/// \throws ParseError with the 1-based column and what was expected
///         (unbalanced parentheses, dangling operators, unknown symbols such
///         as 'x' or 'sin', non-integer exponents, empty input, non-ASCII bytes);
///         DomainError on division by zero (the message gives the column);
///         BudgetExceeded when a ParseLimits bound is exceeded (the message
///         names the limit).
RatFunc parse_expression(const std::string& text, const ParseLimits& limits = {});

/// Parses a parenthesised or bracketed tuple "(x(t), y(t), ...)" of >= 1
/// expressions. Same errors as parse_expression, plus ParseError for empty
/// components "(t, )" and trailing text after the closing bracket.
std::vector<RatFunc> parse_tuple(const std::string& text, const ParseLimits& limits = {});

}  // namespace uniparam
