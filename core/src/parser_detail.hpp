// Internal to the parser (not installed): what parser.cpp (the
// operator-precedence parser and the tuple) and parser_arith.cpp (exact
// number values and the checked arithmetic) share: the tokens and the lexer
// (inline: every character goes through it), the error texts, and the
// Parser class.
#pragma once

#include <flint/fmpz_poly.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/error.hpp"
#include "uniparam/core/parser.hpp"

namespace uniparam::parser_detail {

/// log2(10): bits per decimal digit.
constexpr double kBitsPerDigit = 3.3219280948873623;

constexpr const char* kExpectOperand = "a number, 't' or '('";

inline bool is_digit(char c) { return c >= '0' && c <= '9'; }
inline bool is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// Quotes a piece of the user's text, shortened when long.
inline std::string quote(const std::string& s) {
  if (s.size() <= 24) return "'" + s + "'";
  return "'" + s.substr(0, 20) + "...'";
}

inline std::string column_text(std::size_t pos) { return "column " + std::to_string(pos + 1); }

enum class Tok { Number, T, Ident, LParen, RParen, LBracket, RBracket, Plus, Minus, Star, Slash, Caret, Comma, Invalid, End };

struct Token {
  Tok kind = Tok::End;
  std::size_t pos = 0;  // 0-based byte offset; the column is pos + 1
  std::size_t len = 0;
};

/// Splits the text into tokens. Only malformed numbers ("1.", ".") throw
/// here; every other bad character becomes an Invalid or Ident token that
/// the parser reports with what it expected at that point.
class Lexer {
 public:
  explicit Lexer(const std::string& s) : s_(s) {}

  const Token& peek() {
    if (!has_) { cur_ = scan(); has_ = true; }
    return cur_;
  }
  Token next() {
    Token t = peek();
    has_ = false;
    return t;
  }
  std::string text(const Token& t) const { return s_.substr(t.pos, t.len); }
  const std::string& source() const { return s_; }

 private:
  Token scan() {
    const std::size_t n = s_.size();
    while (i_ < n && is_space(s_[i_])) ++i_;
    Token t;
    t.pos = i_;
    if (i_ >= n) return t;  // End
    const char c = s_[i_];
    if (is_digit(c) || c == '.') {
      scan_number();
      t.kind = Tok::Number;
    } else if (is_alpha(c)) {
      while (i_ < n && (is_alpha(s_[i_]) || is_digit(s_[i_]))) ++i_;
      t.kind = (i_ - t.pos == 1 && c == 't') ? Tok::T : Tok::Ident;
    } else {
      ++i_;
      switch (c) {
        case '(': t.kind = Tok::LParen; break;
        case ')': t.kind = Tok::RParen; break;
        case '[': t.kind = Tok::LBracket; break;
        case ']': t.kind = Tok::RBracket; break;
        case '+': t.kind = Tok::Plus; break;
        case '-': t.kind = Tok::Minus; break;
        case '*': t.kind = Tok::Star; break;
        case '/': t.kind = Tok::Slash; break;
        case '^': t.kind = Tok::Caret; break;
        case ',': t.kind = Tok::Comma; break;
        default: t.kind = Tok::Invalid; break;
      }
    }
    t.len = i_ - t.pos;
    return t;
  }

  // number := digits ['.' digits] [('e'|'E') ['+'|'-'] digits] | '.' digits.
  // An 'e' not followed by an exponent is left for the next token, where it
  // is reported as an unknown symbol.
  void scan_number() {
    const std::size_t n = s_.size(), start = i_;
    while (i_ < n && is_digit(s_[i_])) ++i_;
    if (i_ < n && s_[i_] == '.') {
      ++i_;
      if (i_ >= n || !is_digit(s_[i_]))
        throw ParseError(i_ + 1, "a digit after the decimal point",
                         "incomplete number " + quote(s_.substr(start, i_ - start)));
      while (i_ < n && is_digit(s_[i_])) ++i_;
    }
    if (i_ < n && (s_[i_] == 'e' || s_[i_] == 'E')) {
      std::size_t j = i_ + 1;
      if (j < n && (s_[j] == '+' || s_[j] == '-')) ++j;
      if (j < n && is_digit(s_[j])) {
        i_ = j;
        while (i_ < n && is_digit(s_[i_])) ++i_;
      }
    }
  }

  const std::string& s_;
  std::size_t i_ = 0;
  Token cur_;
  bool has_ = false;
};

/// "the size limit of 268435456 bits (raise it with --max-bits)".
std::string size_limit_text(long max_bits);

/// The exact value of a number token at byte pos (same values as
/// Rational::parse). \throws BudgetExceeded when its numerator or
/// denominator would need more than max_bits bits.
Rational number_value(const std::string& s, std::size_t pos, long max_bits);

struct Op {
  char kind;         // '(' open parenthesis, 'n' unary minus, 'p' unary plus, or + - * /
  std::size_t pos;   // where it appeared
};

inline int precedence(char k) {
  switch (k) {
    case '+': case '-': return 1;
    case '*': case '/': return 2;
    case 'n': case 'p': return 3;
    default: return 0;  // '(' is a barrier
  }
}

class Parser {
 public:
  Parser(const std::string& text, const ParseLimits& limits) : lex_(text), lim_(limits) {
    if (text.size() > lim_.max_length)
      throw BudgetExceeded("the input has " + std::to_string(text.size()) +
                           " characters, more than the length limit of " + std::to_string(lim_.max_length) +
                           " (raise it with --max-length)");
  }

  Lexer& lexer() { return lex_; }

  /// Parses one expression. With closer == 0 it must extend to the end of
  /// the input; otherwise it is a tuple component ending at ',' or `closer`
  /// at parenthesis level 0, and that token is stored in *terminator.
  /// `base_depth` counts enclosing brackets; `open_pos` is the tuple's bracket.
  RatFunc expression(char closer, int base_depth, std::size_t open_pos, Token* terminator);

  [[noreturn]] void fail(const Token& tk, const std::string& expected, const std::string& context = "") const;

 private:
  void push_nesting(char kind, const Token& tk);
  void reduce(int min_prec);
  void apply(const Op& op);
  void after_operand();
  std::pair<long, std::size_t> read_exponent();
  long fold_exponents(const std::vector<std::pair<long, std::size_t>>& exps) const;
  std::string operator_expected(char closer) const;

  void check(long num_deg, long den_deg, double num_size, double den_size, std::size_t pos, const char* what) const;
  RatFunc add(const RatFunc& a, const RatFunc& b, bool subtract, std::size_t pos) const;
  RatFunc mul(const RatFunc& a, const RatFunc& b, std::size_t pos) const;
  RatFunc div(const RatFunc& a, const RatFunc& b, std::size_t pos) const;
  RatFunc pow(const RatFunc& a, long e, std::size_t pos) const;
  void pow_poly(fmpz_poly_t out, const fmpz_poly_struct* base, unsigned long e, std::size_t pos) const;

  Lexer lex_;
  const ParseLimits& lim_;
  std::vector<RatFunc> vals_;
  std::vector<Op> ops_;
  int depth_ = 0;  // base depth + parentheses and unary signs on ops_
  int open_parens_ = 0;
};

}  // namespace uniparam::parser_detail
