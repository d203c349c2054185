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
// then '^' (whose exponent is an integer literal, evaluated at once).//
// The lexer and the Parser class are in parser_detail.hpp, the values of
// numbers and the checked arithmetic in parser_arith.cpp.

#include "uniparam/core/parser.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "parser_detail.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {

using namespace parser_detail;

namespace parser_detail {

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

}  // namespace parser_detail

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
