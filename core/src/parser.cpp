// parser.cpp -- exact parser of expressions and tuples in t (see parser.hpp).
//
// Design: an operator-precedence parser with explicit stacks (operands and
// pending operators). Nothing recurses, so no input can overflow the C++
// stack whatever ParseLimits say; the nesting budget max_depth is enforced
// on the explicit operator stack (parentheses and unary signs) and on chains
// of '^'. Every arithmetic step first predicts an upper bound for the degree
// and the coefficient size of its result and throws BudgetExceeded before
// computing anything too large.
//
// Precedences (low to high): binary + -, then * / and implicit
// multiplication (left associative, so "1/2t" is (1/2)*t), then unary + -,
// then '^' (whose exponent is an integer literal, evaluated at once).

#include "uniparam/core/parser.hpp"

#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_q.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

/// log2(10): bits per decimal digit.
constexpr double kBitsPerDigit = 3.3219280948873623;

const char* const kExpectOperand = "a number, 't' or '('";

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_alpha(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_'; }
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f'; }

/// Quotes a piece of the user's text, shortened when long.
std::string quote(const std::string& s) {
  if (s.size() <= 24) return "'" + s + "'";
  return "'" + s.substr(0, 20) + "...'";
}

std::string column_text(std::size_t pos) { return "column " + std::to_string(pos + 1); }

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

Rational power_of_ten(long k) {
  Integer p;
  fmpz_set_ui(p.get(), 10);
  fmpz_pow_ui(p.get(), p.get(), static_cast<ulong>(k < 0 ? -k : k));
  return k >= 0 ? Rational(p) : Rational(Integer(1), p);
}

/// "the size limit of 268435456 bits (raise it with --max-bits)".
std::string size_limit_text(long max_bits) {
  return "the size limit of " + std::to_string(max_bits) + " bits (raise it with --max-bits)";
}

/// The exact value of a number token (same values as Rational::parse).
/// \throws BudgetExceeded when its numerator or denominator would need more
///         than max_bits bits.
Rational number_value(const std::string& s, std::size_t pos, long max_bits) {
  std::string mantissa;
  long frac_digits = 0;
  std::size_t i = 0;
  while (i < s.size() && is_digit(s[i])) mantissa += s[i++];
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) { mantissa += s[i++]; ++frac_digits; }
  }
  long exponent = 0;
  bool too_long = false;
  if (i < s.size()) {  // 'e' or 'E'
    ++i;
    bool neg = false;
    if (s[i] == '+' || s[i] == '-') { neg = s[i] == '-'; ++i; }
    while (i < s.size() && s[i] == '0') ++i;
    too_long = s.size() - i > 15;  // |exponent| < 10^15: no overflow below
    for (; !too_long && i < s.size(); ++i) exponent = 10 * exponent + (s[i] - '0');
    if (neg) exponent = -exponent;
  }
  // mantissa * 10^(exponent - frac_digits): predict its size before computing it.
  const double bits = kBitsPerDigit * (static_cast<double>(mantissa.size()) +
                                       std::fabs(static_cast<double>(exponent - frac_digits)));
  if (too_long || bits > static_cast<double>(max_bits))
    throw BudgetExceeded("the number " + quote(s) + " at " + column_text(pos) +
                         " is too large: its exact value exceeds " + size_limit_text(max_bits));
  Rational value(Integer(mantissa.empty() ? std::string("0") : mantissa));
  if (value.is_zero()) return value;
  return value * power_of_ten(exponent - frac_digits);
}

// ---- size predictions -------------------------------------------------------

long poly_bits(const fmpz_poly_struct* p) {
  slong b = fmpz_poly_max_bits(p);
  return b < 0 ? -b : b;
}

/// Upper bound of (length) * (max coefficient bits) of the product p*q.
double product_size(const fmpz_poly_struct* p, const fmpz_poly_struct* q) {
  if (p->length == 0 || q->length == 0) return 0.0;
  const double len = static_cast<double>(p->length + q->length - 1);
  const double shortest = static_cast<double>(std::min(p->length, q->length));
  const double bits = static_cast<double>(poly_bits(p) + poly_bits(q)) + std::ceil(std::log2(shortest)) + 1.0;
  return len * bits;
}

const fmpz_poly_struct* num_of(const RatFunc& r) { return fmpz_poly_q_numref(r.get()); }
const fmpz_poly_struct* den_of(const RatFunc& r) { return fmpz_poly_q_denref(r.get()); }
long deg(const fmpz_poly_struct* p) { return fmpz_poly_degree(p); }

// ---- the parser ---------------------------------------------------------------

struct Op {
  char kind;         // '(' open parenthesis, 'n' unary minus, 'p' unary plus, or + - * /
  std::size_t pos;   // where it appeared
};

int precedence(char k) {
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

[[noreturn]] void Parser::fail(const Token& tk, const std::string& expected, const std::string& context) const {
  const std::string text = lex_.text(tk);
  std::string detail;
  switch (tk.kind) {
    case Tok::End: {
      const std::string& s = lex_.source();
      const bool blank = std::all_of(s.begin(), s.begin() + static_cast<std::ptrdiff_t>(tk.pos), is_space);
      detail = blank ? "empty input" : "unexpected end of input";
      break;
    }
    case Tok::Ident: {
      std::size_t j = tk.pos + tk.len;
      const std::string& s = lex_.source();
      while (j < s.size() && is_space(s[j])) ++j;
      const bool call = j < s.size() && s[j] == '(';
      detail = std::string(call ? "unknown function " : "unknown symbol ") + quote(text) +
               (call ? "; only rational functions of t are supported" : "");
      break;
    }
    case Tok::Number:
      detail = "unexpected number " + quote(text);
      break;
    case Tok::Invalid: {
      const auto c = static_cast<unsigned char>(text[0]);
      char buf[8];
      std::snprintf(buf, sizeof buf, "0x%02X", c);
      if (c >= 0x80) detail = std::string("non-ASCII byte ") + buf + "; only ASCII text is accepted";
      else if (c < 0x20 || c == 0x7F) detail = std::string("invalid control character ") + buf;
      else detail = "unexpected character " + quote(text);
      break;
    }
    default:
      detail = "unexpected " + quote(text);
      break;
  }
  throw ParseError(tk.pos + 1, expected, detail + context);
}

void Parser::push_nesting(char kind, const Token& tk) {
  ops_.push_back({kind, tk.pos});
  if (kind == '(') ++open_parens_;
  if (++depth_ > lim_.max_depth)
    throw BudgetExceeded("nesting too deep at " + column_text(tk.pos) + ": more than " +
                         std::to_string(lim_.max_depth) +
                         " nested parentheses, signs or powers exceed the depth limit of " +
                         std::to_string(lim_.max_depth) + " (raise it with --max-depth)");
}

void Parser::reduce(int min_prec) {
  while (!ops_.empty() && ops_.back().kind != '(' && precedence(ops_.back().kind) >= min_prec) {
    Op op = ops_.back();
    ops_.pop_back();
    apply(op);
  }
}

void Parser::apply(const Op& op) {
  if (op.kind == 'n' || op.kind == 'p') {
    --depth_;
    if (op.kind == 'n') vals_.back() = -vals_.back();
    return;
  }
  RatFunc b = std::move(vals_.back());
  vals_.pop_back();
  RatFunc& a = vals_.back();
  switch (op.kind) {
    case '+': a = add(a, b, false, op.pos); break;
    case '-': a = add(a, b, true, op.pos); break;
    case '*': a = mul(a, b, op.pos); break;
    default: a = div(a, b, op.pos); break;
  }
}

std::string Parser::operator_expected(char closer) const {
  if (open_parens_ > 0) return "an operator or ')'";
  if (closer != 0) return std::string("an operator, ',' or '") + closer + "'";
  return "an operator or end of input";
}

RatFunc Parser::expression(char closer, int base_depth, std::size_t open_pos, Token* terminator) {
  vals_.clear();
  ops_.clear();
  depth_ = base_depth;
  open_parens_ = 0;
  bool want_operand = true;
  for (;;) {
    const Token tk = lex_.next();
    if (want_operand) {
      switch (tk.kind) {
        case Tok::Number:
          vals_.emplace_back(number_value(lex_.text(tk), tk.pos, lim_.max_bits));
          after_operand();
          want_operand = false;
          break;
        case Tok::T:
          vals_.push_back(RatFunc::t());
          after_operand();
          want_operand = false;
          break;
        case Tok::LParen: push_nesting('(', tk); break;
        case Tok::Plus: push_nesting('p', tk); break;
        case Tok::Minus: push_nesting('n', tk); break;
        default: {
          const bool nothing_yet = vals_.empty() && ops_.empty();
          if (nothing_yet && closer == 0 && tk.kind == Tok::End)
            throw ParseError(tk.pos + 1, kExpectOperand, "empty expression");
          const bool ends_component = tk.kind == Tok::Comma || (tk.kind == Tok::RParen && closer == ')') ||
                                      (tk.kind == Tok::RBracket && closer == ']');
          if (nothing_yet && closer != 0 && ends_component)
            throw ParseError(tk.pos + 1, "an expression", "empty component");
          std::string context;
          if (tk.kind == Tok::Star && tk.pos > 0 && lex_.source()[tk.pos - 1] == '*')
            context = "; write powers with '^', as in t^2";
          else if (tk.kind == Tok::LBracket)
            context = "; use '(' for grouping";
          else if (tk.kind == Tok::End && !ops_.empty() && ops_.back().kind != '(')
            context = " after '" + lex_.source().substr(ops_.back().pos, 1) + "' at " + column_text(ops_.back().pos);
          fail(tk, kExpectOperand, context);
        }
      }
      continue;
    }
    switch (tk.kind) {
      case Tok::Plus:
      case Tok::Minus:
        reduce(1);
        ops_.push_back({tk.kind == Tok::Plus ? '+' : '-', tk.pos});
        want_operand = true;
        break;
      case Tok::Star:
      case Tok::Slash:
        reduce(2);
        ops_.push_back({tk.kind == Tok::Star ? '*' : '/', tk.pos});
        want_operand = true;
        break;
      case Tok::T:  // implicit multiplication: "2t", "(t+1)t"
        reduce(2);
        ops_.push_back({'*', tk.pos});
        vals_.push_back(RatFunc::t());
        after_operand();
        break;
      case Tok::LParen:  // implicit multiplication: "3(t+1)", "(t+1)(t-1)"
        reduce(2);
        ops_.push_back({'*', tk.pos});
        push_nesting('(', tk);
        want_operand = true;
        break;
      case Tok::RParen:
        reduce(1);
        if (open_parens_ == 0) {
          if (closer == ')') { *terminator = tk; return std::move(vals_.back()); }
          fail(tk, operator_expected(closer), "; no '(' is open");
        }
        ops_.pop_back();  // the '('
        --open_parens_;
        --depth_;
        after_operand();
        break;
      case Tok::Comma:
      case Tok::RBracket:
        if (open_parens_ == 0 && closer != 0 && (tk.kind == Tok::Comma || closer == ']')) {
          reduce(1);
          *terminator = tk;
          return std::move(vals_.back());
        }
        fail(tk, operator_expected(closer));
      case Tok::End:
        if (open_parens_ > 0) {
          std::size_t open = 0;
          for (auto it = ops_.rbegin(); it != ops_.rend(); ++it)
            if (it->kind == '(') { open = it->pos; break; }
          throw ParseError(tk.pos + 1, "')'", "missing ')' to close the '(' at " + column_text(open));
        }
        if (closer != 0)
          throw ParseError(tk.pos + 1, std::string("',' or '") + closer + "'",
                           std::string("missing '") + closer + "' to close the '" + lex_.source()[open_pos] +
                               "' at " + column_text(open_pos));
        reduce(1);
        return std::move(vals_.back());
      case Tok::Number:
        fail(tk, operator_expected(closer), lex_.text(tk)[0] == '.' ? "" : "; write products with '*'");
      case Tok::Ident:
        fail(tk, "an operator, 't' or '('");
      default:
        fail(tk, operator_expected(closer));
    }
  }
}

// After an operand (number, t or a closed group): an optional chain of
// '^' exponent, applied at once to vals_.back(). The chain is right
// associative: t^2^3 = t^(2^3).
void Parser::after_operand() {
  if (lex_.peek().kind != Tok::Caret) return;
  const std::size_t caret_pos = lex_.peek().pos;
  std::vector<std::pair<long, std::size_t>> exps;
  while (lex_.peek().kind == Tok::Caret) {
    const Token caret = lex_.next();
    if (depth_ + static_cast<long>(exps.size()) + 1 > lim_.max_depth)
      throw BudgetExceeded("nesting too deep at " + column_text(caret.pos) + ": a chain of more than " +
                           std::to_string(lim_.max_depth) + " nested powers exceeds the depth limit of " +
                           std::to_string(lim_.max_depth) + " (raise it with --max-depth)");
    exps.push_back(read_exponent());
  }
  vals_.back() = pow(vals_.back(), fold_exponents(exps), caret_pos);
}

// exponent := ['+'|'-'] integer | '(' ['+'|'-'] integer ')'
std::pair<long, std::size_t> Parser::read_exponent() {
  const char* expected = "an integer exponent";
  Token tk = lex_.next();
  const bool paren = tk.kind == Tok::LParen;
  if (paren) tk = lex_.next();
  const std::size_t start = tk.pos;
  bool neg = false;
  if (tk.kind == Tok::Plus || tk.kind == Tok::Minus) {
    neg = tk.kind == Tok::Minus;
    tk = lex_.next();
  }
  if (tk.kind != Tok::Number) fail(tk, expected, tk.kind == Tok::T ? "; exponents must be integer constants" : "");
  const std::string text = lex_.text(tk);
  if (!std::all_of(text.begin(), text.end(), is_digit))
    throw ParseError(tk.pos + 1, expected, "the exponent must be an integer written with digits, not " + quote(text));
  std::size_t i = 0;
  while (i + 1 < text.size() && text[i] == '0') ++i;
  long value = 0;
  bool too_big = text.size() - i > 18;
  for (; !too_big && i < text.size(); ++i) value = 10 * value + (text[i] - '0');
  if (too_big || value > lim_.max_exponent)
    throw BudgetExceeded("the exponent " + quote((neg ? "-" : "") + text) + " at " + column_text(tk.pos) +
                         " exceeds the exponent limit of " + std::to_string(lim_.max_exponent) +
                         " (raise it with --max-degree)");
  if (paren) {
    const Token close = lex_.next();
    if (close.kind != Tok::RParen) fail(close, "')' after the exponent");
  }
  return {neg ? -value : value, start};
}

long Parser::fold_exponents(const std::vector<std::pair<long, std::size_t>>& exps) const {
  long acc = exps.back().first;
  for (std::size_t k = exps.size() - 1; k-- > 0;) {
    const long b = exps[k].first;
    const std::size_t pos = exps[k].second;
    if (acc < 0) {
      if (b == 0) throw DomainError("division by zero at " + column_text(pos) + ": 0 raised to a negative power");
      if (b != 1 && b != -1)
        throw ParseError(pos + 1, "an integer exponent",
                         "the exponent " + std::to_string(b) + "^" + std::to_string(acc) + " is not an integer");
      acc = (b == -1 && (-acc) % 2 == 1) ? -1 : 1;
      continue;
    }
    long r = 1;
    if (b == 0) r = acc == 0 ? 1 : 0;
    else if (b == 1) r = 1;
    else if (b == -1) r = acc % 2 ? -1 : 1;
    else
      for (long i = 0; i < acc; ++i) {
        r *= b;  // |r| <= max_exponent * |b| before the check: no overflow
        if (r > lim_.max_exponent || -r > lim_.max_exponent)
          throw BudgetExceeded("the exponent " + std::to_string(b) + "^" + std::to_string(acc) + " at " +
                               column_text(pos) + " exceeds the exponent limit of " +
                               std::to_string(lim_.max_exponent) + " (raise it with --max-degree)");
      }
    acc = r;
  }
  return acc;
}

// ---- checked arithmetic ---------------------------------------------------------

void Parser::check(long num_deg, long den_deg, double num_size, double den_size, std::size_t pos,
                   const char* what) const {
  const long d = std::max(num_deg, den_deg);
  if (d > lim_.max_degree)
    throw BudgetExceeded("degree limit exceeded at " + column_text(pos) + ": the " + what +
                         " would have degree up to " + std::to_string(d) + ", above the degree limit of " +
                         std::to_string(lim_.max_degree) + " (raise it with --max-degree)");
  const double size = std::max(num_size, den_size);
  if (size > static_cast<double>(lim_.max_bits)) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", size);
    throw BudgetExceeded("size limit exceeded at " + column_text(pos) + ": the " + what + " would need about " +
                         buf + " bits, above " + size_limit_text(lim_.max_bits));
  }
}

RatFunc Parser::add(const RatFunc& a, const RatFunc& b, bool subtract, std::size_t pos) const {
  if (!a.is_zero() && !b.is_zero()) {
    const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
    const long num_deg = std::max(deg(na) + deg(db), deg(nb) + deg(da));
    const double num_size = std::max(product_size(na, db), product_size(nb, da)) + static_cast<double>(num_deg + 1);
    check(num_deg, deg(da) + deg(db), num_size, product_size(da, db), pos, subtract ? "difference" : "sum");
  }
  return subtract ? a - b : a + b;
}

RatFunc Parser::mul(const RatFunc& a, const RatFunc& b, std::size_t pos) const {
  if (a.is_zero() || b.is_zero()) return RatFunc(0);
  const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
  check(deg(na) + deg(nb), deg(da) + deg(db), product_size(na, nb), product_size(da, db), pos, "product");
  return a * b;
}

RatFunc Parser::div(const RatFunc& a, const RatFunc& b, std::size_t pos) const {
  if (b.is_zero())
    throw DomainError("division by zero at " + column_text(pos) + ": the divisor is identically zero");
  if (a.is_zero()) return RatFunc(0);
  const auto *na = num_of(a), *da = den_of(a), *nb = num_of(b), *db = den_of(b);
  check(deg(na) + deg(db), deg(da) + deg(nb), product_size(na, db), product_size(da, nb), pos, "quotient");
  return a / b;
}

// base^e by left-to-right binary powering, checking the size of every step.
void Parser::pow_poly(fmpz_poly_t out, const fmpz_poly_struct* base, unsigned long e, std::size_t pos) const {
  if (e == 0) { fmpz_poly_one(out); return; }
  fmpz_poly_set(out, base);
  int top = 63;
  while (!((e >> top) & 1UL)) --top;
  fmpz_poly_t tmp;
  fmpz_poly_init(tmp);
  try {
    for (int bit = top - 1; bit >= 0; --bit) {
      check(0, 0, product_size(out, out), 0.0, pos, "power");
      fmpz_poly_sqr(tmp, out);
      fmpz_poly_swap(tmp, out);
      if ((e >> bit) & 1UL) {
        check(0, 0, product_size(out, base), 0.0, pos, "power");
        fmpz_poly_mul(tmp, out, base);
        fmpz_poly_swap(tmp, out);
      }
    }
  } catch (...) {
    fmpz_poly_clear(tmp);
    throw;
  }
  fmpz_poly_clear(tmp);
}

RatFunc Parser::pow(const RatFunc& a, long e, std::size_t pos) const {
  if (e == 0) return RatFunc(1);
  if (a.is_zero()) {
    if (e < 0) throw DomainError("division by zero at " + column_text(pos) + ": 0 raised to a negative power");
    return RatFunc(0);
  }
  const unsigned long m = static_cast<unsigned long>(e < 0 ? -e : e);
  const double d = static_cast<double>(std::max(deg(num_of(a)), deg(den_of(a)))) * static_cast<double>(m);
  if (d > static_cast<double>(lim_.max_degree))
    throw BudgetExceeded("degree limit exceeded at " + column_text(pos) + ": the power would have degree " +
                         std::to_string(static_cast<long>(d)) + ", above the degree limit of " +
                         std::to_string(lim_.max_degree) + " (raise it with --max-degree)");
  // num and den are coprime with den's leading coefficient positive, so
  // num^m / den^m is already canonical; an inverse only needs the sign fixed.
  RatFunc r;
  fmpz_poly_struct* rn = fmpz_poly_q_numref(r.get());
  fmpz_poly_struct* rd = fmpz_poly_q_denref(r.get());
  pow_poly(rn, num_of(a), m, pos);
  pow_poly(rd, den_of(a), m, pos);
  if (e < 0) {
    fmpz_poly_swap(rn, rd);
    if (fmpz_sgn(fmpz_poly_lead(rd)) < 0) {
      fmpz_poly_neg(rn, rn);
      fmpz_poly_neg(rd, rd);
    }
  }
  return r;
}

}  // namespace

RatFunc parse_expression(const std::string& text, const ParseLimits& limits) {
  Parser p(text, limits);
  return p.expression(0, 0, 0, nullptr);
}

std::vector<RatFunc> parse_tuple(const std::string& text, const ParseLimits& limits) {
  Parser p(text, limits);
  const Token open = p.lexer().next();
  if (open.kind == Tok::End || open.kind == Tok::Invalid) p.fail(open, "'(' or '['");
  if (open.kind != Tok::LParen && open.kind != Tok::LBracket)
    throw ParseError(open.pos + 1, "'(' or '['", "a curve is written as a tuple such as (x(t), y(t))");
  const char closer = open.kind == Tok::LParen ? ')' : ']';
  if (limits.max_depth < 1)
    throw BudgetExceeded("nesting too deep at " + column_text(open.pos) +
                         ": the tuple's bracket exceeds the depth limit of " + std::to_string(limits.max_depth) +
                         " (raise it with --max-depth)");
  std::vector<RatFunc> out;
  Token terminator;
  do {
    out.push_back(p.expression(closer, 1, open.pos, &terminator));
  } while (terminator.kind == Tok::Comma);
  const Token rest = p.lexer().next();
  if (rest.kind != Tok::End)
    p.fail(rest, "end of input", std::string(" after the closing '") + closer + "'");
  return out;
}

}  // namespace uniparam
