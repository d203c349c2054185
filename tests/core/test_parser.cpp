// Tests of the exact parser (core/parser.hpp): round trips of random rational
// functions through the printers, random expression trees printed with
// minimal parentheses and compared with an exact evaluation done here,
// precedence, implicit multiplication, every error kind with its column, the
// ParseLimits budgets, hostile inputs and a fuzz test.
#include <gtest/gtest.h>

#include <climits>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/parser.hpp"
#include "uniparam/core/printer.hpp"

namespace uniparam {
namespace {

using test_support::iterations;
using test_support::random_integer;

const RatFunc T = RatFunc::t();
RatFunc q(long a, long b = 1) { return RatFunc(Rational(a, b)); }

Poly random_poly(std::mt19937_64& rng, int max_degree, int max_digits) {
  const int d = std::uniform_int_distribution<int>(0, max_degree)(rng);
  std::vector<Integer> c;
  for (int i = 0; i <= d; ++i) c.push_back(rng() % 3 == 0 ? Integer(0) : random_integer(rng, max_digits));
  return Poly(c);
}

// ---- round trips through the printers -------------------------------------------

TEST(Parser, RoundTripsRandomRationalFunctionsProperty) {
  std::mt19937_64 rng(2024);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Poly n = random_poly(rng, 8, 30);
    Poly d = random_poly(rng, 6, 30);
    if (d.is_zero()) d = Poly(1);
    const RatFunc r(n, d);
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 2024): " + r.str());
    for (const std::string& text : {r.str(), format_ratfunc(r, Format::Text), format_ratfunc(r, Format::Maple),
                                    "(" + n.str() + ")/(" + d.str() + ")"}) {
      EXPECT_EQ(parse_expression(text), r) << text;
    }
    // The same curve component inside a tuple.
    const std::vector<RatFunc> tup = parse_tuple("(" + r.str() + ", " + format_ratfunc(r, Format::Maple) + ")");
    ASSERT_EQ(tup.size(), 2u);
    EXPECT_EQ(tup[0], r);
    EXPECT_EQ(tup[1], r);
  }
}

// A random expression printed with as few parentheses as the grammar allows,
// with its value computed here by exact arithmetic.
struct Expr {
  std::string text;
  RatFunc value;
  int prec;  // 1 sum, 2 product, 3 unary sign, 4 power, 5 atom or parenthesised
};

class ExprGen {
 public:
  explicit ExprGen(std::mt19937_64& rng) : rng_(rng) {}

  Expr gen(int depth) {
    if (depth == 0 || pick(4) == 0) return leaf();
    switch (pick(6)) {
      case 0: return sum(gen(depth - 1), gen(depth - 1), pick(2) == 0 ? '+' : '-');
      case 1: return product(gen(depth - 1), gen(depth - 1));
      case 2: return quotient(gen(depth - 1), gen(depth - 1));
      case 3: return negate(gen(depth - 1));
      case 4: return power(gen(depth - 1));
      default: return wrap(gen(depth - 1));
    }
  }

 private:
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }
  std::string sp() { return pick(3) == 0 ? " " : ""; }

  Expr wrap(const Expr& e) { return {"(" + sp() + e.text + sp() + ")", e.value, 5}; }
  Expr wrap_if(const Expr& e, bool cond) { return cond ? wrap(e) : e; }

  Expr leaf() {
    switch (pick(3)) {
      case 0: return {"t", T, 5};
      case 1: {
        const long v = std::uniform_int_distribution<long>(0, 1000)(rng_);
        return {std::to_string(v), q(v), 5};
      }
      default: {  // a decimal I.F or I.Fe±k, valued without the parser
        const long ip = pick(100), fp = 1 + pick(999);
        std::string f = std::to_string(fp);
        f = std::string(static_cast<std::size_t>(pick(3)), '0') + f;  // leading zeros in the fraction
        Integer den;
        fmpz_set_ui(den.get(), 10);
        fmpz_pow_ui(den.get(), den.get(), f.size());
        Rational v(Integer(std::to_string(ip) + f), den);
        std::string text = std::to_string(ip) + "." + f;
        if (pick(2) == 0) {
          const long k = pick(7) - 3;
          text += (pick(2) ? "e" : "E") + std::to_string(k);
          for (long i = 0; i < (k < 0 ? -k : k); ++i) v = k > 0 ? v * Rational(10) : v / Rational(10);
        }
        return {text, RatFunc(v), 5};
      }
    }
  }

  Expr sum(const Expr& a, const Expr& b, char op) {
    const Expr r = wrap_if(b, op == '-' ? b.prec <= 1 : b.prec < 1);
    return {a.text + sp() + op + sp() + r.text, op == '+' ? a.value + b.value : a.value - b.value, 1};
  }

  Expr product(const Expr& a, const Expr& b) {
    const Expr l = wrap_if(a, a.prec < 2);
    const Expr r = wrap_if(b, b.prec < 2);
    const bool implicit_ok = (r.text[0] == 't' || r.text[0] == '(') && pick(2) == 0;
    if (implicit_ok) {
      // "tt" would be one identifier: separate it.
      const std::string gap = (l.text.back() == 't' && r.text[0] == 't') ? " " : sp();
      return {l.text + gap + r.text, a.value * b.value, 2};
    }
    return {l.text + sp() + "*" + sp() + r.text, a.value * b.value, 2};
  }

  Expr quotient(const Expr& a, Expr b) {
    if (b.value.is_zero()) b = {"(t+1)", T + q(1), 5};
    const Expr l = wrap_if(a, a.prec < 2);
    const Expr r = wrap_if(b, b.prec <= 2);
    return {l.text + sp() + "/" + sp() + r.text, a.value / b.value, 2};
  }

  Expr negate(const Expr& a) {
    const Expr c = wrap_if(a, a.prec < 3);
    return {"-" + sp() + c.text, -a.value, 3};
  }

  Expr power(const Expr& a) {
    long e = pick(6) - 2;  // -2 .. 3
    if (a.value.is_zero() && e < 0) e = 2;
    const Expr b = wrap_if(a, a.prec < 5);
    std::string et = std::to_string(e);
    if (pick(3) == 0) et = "(" + sp() + et + sp() + ")";
    else if (e >= 0 && pick(4) == 0) et = "+" + et;
    return {b.text + sp() + "^" + sp() + et, a.value.pow(e), 4};
  }

  std::mt19937_64& rng_;
};

TEST(Parser, RandomExpressionsMatchExactEvaluationProperty) {
  std::mt19937_64 rng(7);
  ExprGen gen(rng);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Expr e = gen.gen(5);
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 7): " + e.text);
    EXPECT_EQ(parse_expression(e.text), e.value) << "expected " << e.value.str();
  }
}

// ---- precedence, implicit multiplication, numbers ---------------------------------

TEST(Parser, Precedence) {
  EXPECT_EQ(parse_expression("1+2*3"), q(7));
  EXPECT_EQ(parse_expression("(1+2)*3"), q(9));
  EXPECT_EQ(parse_expression("2^3^2"), q(512));  // right associative
  EXPECT_EQ(parse_expression("t^2^3"), T.pow(8));
  EXPECT_EQ(parse_expression("(t^2)^3"), T.pow(6));
  EXPECT_EQ(parse_expression("-2^2"), q(-4));    // -(2^2)
  EXPECT_EQ(parse_expression("(-2)^2"), q(4));
  EXPECT_EQ(parse_expression("-t^2"), -T.pow(2));
  EXPECT_EQ(parse_expression("2*-3"), q(-6));
  EXPECT_EQ(parse_expression("2--3"), q(5));
  EXPECT_EQ(parse_expression("--t"), T);
  EXPECT_EQ(parse_expression("+t"), T);
  EXPECT_EQ(parse_expression("1-2-3"), q(-4));   // left associative
  EXPECT_EQ(parse_expression("1/2/3"), q(1, 6));
  EXPECT_EQ(parse_expression("12/3*2"), q(8));
  EXPECT_EQ(parse_expression("1-t^2/2"), q(1) - T * T / q(2));
  EXPECT_EQ(parse_expression("t^-1"), q(1) / T);
  EXPECT_EQ(parse_expression("t^(-2)"), q(1) / (T * T));
  EXPECT_EQ(parse_expression("t^+2"), T * T);
  EXPECT_EQ(parse_expression("2^-1"), q(1, 2));
  EXPECT_EQ(parse_expression("(t+1)^-2^2"), (T + q(1)).pow(4));  // exponent (-2)^2
  EXPECT_EQ(parse_expression("t^0"), q(1));
  EXPECT_EQ(parse_expression("0^0"), q(1));
}

TEST(Parser, ImplicitMultiplication) {
  EXPECT_EQ(parse_expression("2t"), q(2) * T);
  EXPECT_EQ(parse_expression("3(t+1)"), q(3) * T + q(3));
  EXPECT_EQ(parse_expression("(t+1)(t-1)"), T * T - q(1));
  EXPECT_EQ(parse_expression("2t^2"), q(2) * T * T);
  EXPECT_EQ(parse_expression("t(t+1)"), T * T + T);
  EXPECT_EQ(parse_expression("t t"), T * T);
  EXPECT_EQ(parse_expression("t^2t"), T.pow(3));
  EXPECT_EQ(parse_expression("t^(2)(t+1)"), T * T * (T + q(1)));
  EXPECT_EQ(parse_expression("1/2t"), T / q(2));  // left to right, like '*'
  EXPECT_EQ(parse_expression("-2t+1"), q(1) - q(2) * T);
  EXPECT_EQ(parse_expression("0.5t"), T / q(2));
  EXPECT_EQ(parse_expression("1e3t"), q(1000) * T);
}

TEST(Parser, NumbersAreExact) {
  EXPECT_EQ(parse_expression("0.1"), RatFunc(Rational(1, 10)));
  EXPECT_EQ(parse_expression("0.1+0.2"), parse_expression("0.3"));
  EXPECT_EQ(parse_expression("1e-3"), q(1, 1000));
  EXPECT_EQ(parse_expression("2.5E+2"), q(250));
  EXPECT_EQ(parse_expression(".5"), q(1, 2));
  EXPECT_EQ(parse_expression("007"), q(7));
  EXPECT_EQ(parse_expression("123456789012345678901234567890"),
            RatFunc(Rational(Integer("123456789012345678901234567890"))));
  EXPECT_EQ(parse_expression("0.000000000000000000001"), RatFunc(Rational::parse("1e-21")));
  for (const char* s : {"3.25", "1e-3", "12.5e-1", "0.0001", "7e0"})
    EXPECT_EQ(parse_expression(s), RatFunc(Rational::parse(s))) << s;
}

TEST(Parser, WhitespaceIsIgnored) {
  EXPECT_EQ(parse_expression("  2 t ^ 2\t+\n1 "), q(2) * T * T + q(1));
  EXPECT_EQ(parse_expression("( t + 1 ) / ( t - 1 )"), (T + q(1)) / (T - q(1)));
}

TEST(Parser, ResultIsCanonical) {
  const RatFunc r = parse_expression("(2t^2 - 2)/(4t - 4)");
  EXPECT_EQ(r, (T + q(1)) / q(2));
  EXPECT_EQ(r.den(), Poly(2));
  EXPECT_EQ(parse_expression("(t-1)^-1 * (t-1)"), q(1));
  EXPECT_EQ(parse_expression("(-t)^-3").den(), Poly::t().pow(3));  // positive leading coefficient
  EXPECT_EQ(parse_expression("(-t)^-3").num(), Poly(-1));
}

TEST(Parser, Tuples) {
  const auto a = parse_tuple("(t, t^2)");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0], T);
  EXPECT_EQ(a[1], T * T);
  const auto b = parse_tuple("  [ (1-t^2)/(1+t^2), 2t/(1+t^2), 3 ]  ");
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[1], q(2) * T / (q(1) + T * T));
  EXPECT_EQ(b[2], q(3));
  const auto c = parse_tuple("(t)");
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0], T);
  EXPECT_EQ(parse_tuple("((t+1)(t-1), (t))")[0], T * T - q(1));
}

// ---- errors -------------------------------------------------------------------------

struct BadInput {
  std::string text;
  std::size_t column;   // expected ParseError column
  std::string mention;  // must appear in the message
};

void expect_parse_error(const BadInput& c, bool tuple) {
  SCOPED_TRACE("input '" + c.text + "'");
  try {
    if (tuple) parse_tuple(c.text);
    else parse_expression(c.text);
    ADD_FAILURE() << "no exception";
  } catch (const ParseError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.column(), c.column) << msg;
    EXPECT_NE(msg.find("column " + std::to_string(c.column)), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.mention), std::string::npos) << msg;
    EXPECT_FALSE(e.expected().empty()) << msg;
    EXPECT_NE(msg.find("(expected "), std::string::npos) << msg;
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception: " << e.what();
  }
}

TEST(Parser, ParseErrorColumns) {
  const std::vector<BadInput> cases = {
      {"", 1, "empty"},
      {"   ", 4, "empty"},
      {"(t+1", 5, "missing ')'"},
      {"((t)", 5, "column 1"},  // names the unclosed '('
      {"t+1)", 4, "')'"},
      {"t+", 3, "end of input"},
      {"t+", 3, "after '+'"},
      {"t*", 3, "end of input"},
      {"-", 2, "end of input"},
      {"*t", 1, "'*'"},
      {"t+*2", 3, "'*'"},
      {"t/)", 3, "')'"},
      {"t^", 3, "integer exponent"},
      {"t^t", 3, "'t'"},
      {"(t, )", 3, "','"},
      {"()", 2, "')'"},
      {"x", 1, "unknown symbol 'x'"},
      {"(t+1)/(x-1)", 8, "unknown symbol 'x'"},
      {"t + s", 5, "'s'"},
      {"2x", 2, "'x'"},
      {"pi*t", 1, "'pi'"},
      {"sin(t)", 1, "'sin'"},
      {"t + exp(t)", 5, "'exp'"},
      {"tt", 1, "'tt'"},
      {"t2", 1, "'t2'"},
      {"2e", 2, "'e'"},
      {"t^0.5", 3, "'0.5'"},
      {"t^1.0", 3, "integer"},
      {"t^(1+1)", 5, "'+'"},
      {"t^(2", 5, "end of input"},
      {"1.", 3, "digit"},
      {"t+.", 4, "digit"},
      {"2 3", 3, "'3'"},
      {"t**2", 3, "'^'"},
      {"[t]", 1, "'['"},
      {"(t]", 3, "']'"},
      {"t,t", 2, "','"},
      {"t = 1", 3, "'='"},
      {"\xff", 1, "0xFF"},
      {"t+\xce\xb1", 3, "non-ASCII"},
      {std::string("t+\x01", 3), 3, "control"},
      {std::string("t\0", 2), 2, "0x00"},
  };
  for (const auto& c : cases) expect_parse_error(c, false);
}

TEST(Parser, ErrorMessageReadsWell) {
  try {
    parse_tuple("(t^2, x)");
    FAIL() << "no exception";
  } catch (const ParseError& e) {
    EXPECT_EQ(std::string(e.what()), "parse error at column 7: unknown symbol 'x' (expected a number, 't' or '(')");
    EXPECT_EQ(e.expected(), "a number, 't' or '('");
  }
}

TEST(Parser, TupleErrorColumns) {
  const std::vector<BadInput> cases = {
      {"(t, )", 5, "empty component"},
      {"()", 2, "empty component"},
      {"(t,,t)", 4, "empty component"},
      {"(t, -)", 6, "')'"},
      {"(t, t", 6, "missing ')'"},
      {"[t, t", 6, "missing ']'"},
      {"(t, t]", 6, "']'"},
      {"[t, t)", 6, "')'"},
      {"(t, t) x", 8, "after the closing"},
      {"(t, t)(t)", 7, "after the closing"},
      {"t, t", 1, "tuple"},
      {"", 1, "empty"},
      {"(t, (t+1)", 10, "missing"},
      {"(t, y)", 5, "'y'"},
  };
  for (const auto& c : cases) expect_parse_error(c, true);
}

TEST(Parser, DivisionByZeroIsADomainErrorWithColumn) {
  struct Case { const char* text; const char* column; };
  for (const Case& c : {Case{"1/0", "column 2"}, Case{"1/(t-t)", "column 2"}, Case{"t + 3/(2t - t - t)", "column 6"},
                        Case{"(t-t)^-1", "column 6"}, Case{"0^-2", "column 2"}, Case{"t/0.0", "column 2"}}) {
    SCOPED_TRACE(c.text);
    try {
      parse_expression(c.text);
      ADD_FAILURE() << "no exception";
    } catch (const DomainError& e) {
      EXPECT_NE(std::string(e.what()).find(c.column), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("division by zero"), std::string::npos) << e.what();
    } catch (const std::exception& e) {
      ADD_FAILURE() << "wrong exception: " << e.what();
    }
  }
  EXPECT_THROW(parse_tuple("(t, 1/(t-t))"), DomainError);
}

void expect_budget(const std::string& text, const std::string& limit_name, const ParseLimits& lim = {},
                   bool tuple = false) {
  SCOPED_TRACE("input of " + std::to_string(text.size()) + " chars starting '" + text.substr(0, 30) + "'");
  try {
    if (tuple) parse_tuple(text, lim);
    else parse_expression(text, lim);
    ADD_FAILURE() << "no exception";
  } catch (const BudgetExceeded& e) {
    EXPECT_NE(std::string(e.what()).find(limit_name), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception: " << e.what();
  }
}

TEST(Parser, LimitsAreEnforcedAndNamed) {
  expect_budget("t^100000", "exponent limit of 10000 (raise it with --max-degree)");
  expect_budget("t^-100000", "exponent limit");
  expect_budget("t^99999999999999999999999", "exponent limit");
  expect_budget("t^2^2^2^2^2", "exponent limit");  // 2^16 > 10000
  expect_budget("t^10000*t^10000*t", "degree limit of 20000 (raise it with --max-degree)");
  expect_budget("(t+1)^10000 * (t-1)^10001", "exponent limit");
  expect_budget("(t^3+1)^7000", "degree limit");
  expect_budget("1/(t^10000 + 1) + t/(t^10000*t - 1)", "degree limit");
  expect_budget(std::string(100000, '('), "depth limit of 500 (raise it with --max-depth)");
  expect_budget(std::string(100000, '(') + "t" + std::string(100000, ')'), "depth limit");
  expect_budget(std::string((1u << 20) - 1, '-') + "t", "depth limit");
  std::string chain = "t";
  for (int i = 0; i < 600; ++i) chain += "^1";
  expect_budget(chain, "depth limit");
  expect_budget(std::string((1u << 20) + 1, ' '), "length limit of 1048576 (raise it with --max-length)");
  expect_budget("(" + std::string(1u << 20, 't') + ")", "length limit", {}, true);
  expect_budget("1e100000000", "size limit of 268435456 bits (raise it with --max-bits)");
  expect_budget("1e-1000000000000000000000", "--max-bits");
  expect_budget("(1e999999*t + 1)^10000", "size limit");

  ParseLimits small;
  small.max_degree = 5;
  small.max_exponent = 3;
  small.max_depth = 3;
  small.max_length = 20;
  EXPECT_EQ(parse_expression("t^3*t^2", small), T.pow(5));
  expect_budget("t^3*t^3", "degree limit of 5", small);
  expect_budget("t^4", "exponent limit of 3", small);
  EXPECT_EQ(parse_expression("((-t))", small), -T);
  expect_budget("(((t)))+(((((t)))))", "depth limit of 3", small);
  EXPECT_EQ(parse_expression("---t", small), -T);
  expect_budget("----t", "depth limit of 3", small);
  EXPECT_EQ(parse_tuple("(t, ((t)))", small)[1], T);
  expect_budget("(t, (((t))))", "depth limit of 3", small, true);  // the tuple bracket counts
  EXPECT_EQ(parse_tuple("(t, (t))", small).size(), 2u);
  expect_budget("t+t+t+t+t+t+t+t+t+t+t", "length limit of 20", small);
  small.max_bits = 64;
  expect_budget("12345678901234567890", "size limit of 64 bits", small);
  expect_budget("1e30", "size limit of 64 bits", small);
  expect_budget("(99t+99)^3", "size limit of 64 bits", small);
}

TEST(Parser, HostileInputsAreFastAndDoNotOverflowTheStack) {
  // A megabyte of '(' with an unlimited depth budget: the parser keeps its
  // own stack, so this parses instead of crashing.
  ParseLimits deep;
  deep.max_depth = INT_MAX;
  const std::size_t n = 500000;
  EXPECT_EQ(parse_expression(std::string(n, '(') + "t" + std::string(n, ')'), deep), T);
  EXPECT_EQ(parse_expression(std::string(2 * n, '-') + "t", deep), T);
  EXPECT_EQ(parse_expression(std::string(2 * n - 1, '-') + "t", deep), -T);
  // A megabyte of '(' with the default limits is refused.
  expect_budget(std::string(1u << 20, '('), "depth limit");
  expect_budget(std::string(1u << 20, '-'), "depth limit");
  // A long flat sum is fine: 2^19 terms.
  std::string sum = "t";
  while (sum.size() + 2 <= (1u << 20)) sum += "+t";
  EXPECT_EQ(parse_expression(sum), q(static_cast<long>((sum.size() + 1) / 2)) * T);
  // A long digit string is one exact number.
  const std::string digits(500000, '9');
  EXPECT_EQ(parse_expression(digits + "+1"), RatFunc(Rational(Integer("1" + std::string(500000, '0')))));
  // No wall-clock assertion (house rule: no timed tests; it failed under
  // ASan on a loaded machine): a hang is caught by CTest's timeout.
}

TEST(Parser, FuzzOnlyThrowsUniparamErrors) {
  std::mt19937_64 rng(99);
  const std::string alphabet = "tt0123456789..+-*/^^()()[],  exs\xff\t";
  ParseLimits lim;
  lim.max_degree = 60;
  lim.max_exponent = 12;
  const long iters = iterations(200) * 20;
  long ok = 0;
  for (long it = 0; it < iters; ++it) {
    std::string s;
    for (int i = std::uniform_int_distribution<int>(0, 24)(rng); i > 0; --i)
      s += alphabet[rng() % alphabet.size()];
    for (bool tuple : {false, true}) {
      SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 99): '" + s + "'");
      try {
        if (tuple) parse_tuple(s, lim);
        else parse_expression(s, lim);
        ++ok;
      } catch (const ParseError& e) {
        EXPECT_GE(e.column(), 1u) << e.what();
        EXPECT_LE(e.column(), s.size() + 1) << e.what();
        EXPECT_FALSE(e.expected().empty()) << e.what();
      } catch (const Error&) {
        // DomainError or BudgetExceeded: fine.
      } catch (const std::exception& e) {
        ADD_FAILURE() << "non-uniparam exception: " << e.what();
      }
    }
  }
  EXPECT_GT(ok, 0);  // the alphabet does produce valid inputs
}

}  // namespace
}  // namespace uniparam
