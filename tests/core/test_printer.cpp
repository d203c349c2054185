// Tests of printer.hpp: LaTeX/Maple/text strings of simple values, the JSON
// builder (structure, RFC 8259 escaping checked by decoding the output
// again), and the json_ball / json_rational enclosure contract.
#include <gtest/gtest.h>

#include <arf.h>
#include <mag.h>

#include <cstdlib>
#include <random>
#include <string>

#include "support/iterations.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/json.hpp"
#include "uniparam/core/parser.hpp"
#include "uniparam/core/printer.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

const RatFunc T = RatFunc::t();
RatFunc q(long a, long b = 1) { return RatFunc(Rational(a, b)); }
Rational abs(const Rational& x) { return x.sign() < 0 ? -x : x; }

// ---- the output read back by the JSON reader (json.hpp: RFC 8259, it refuses raw
// control characters, lone surrogates and invalid escapes) ---------------------------

std::string roundtrip_string(const std::string& s) {
  const std::string dumped = Json::string(s).dump(-1);
  const JsonValue v = parse_json(dumped);
  EXPECT_TRUE(v.is_string()) << dumped;
  return v.text;
}

// The value of the string member "key" of a one-line dump of an object.
std::string field(const std::string& dumped, const std::string& key) {
  const JsonValue v = parse_json(dumped);
  const JsonValue* m = v.is_object() ? v.find(key) : nullptr;
  if (!m || !m->is_string()) {
    ADD_FAILURE() << "no string member " << key << " in " << dumped;
    return "";
  }
  return m->text;
}

// ---- formats ------------------------------------------------------------------------

TEST(Printer, Rationals) {
  EXPECT_EQ(format_rational(Rational(-3, 4), Format::Text), "-3/4");
  EXPECT_EQ(format_rational(Rational(-3, 4), Format::Maple), "-3/4");
  EXPECT_EQ(format_rational(Rational(-3, 4), Format::Latex), "-\\frac{3}{4}");
  EXPECT_EQ(format_rational(Rational(5, 7), Format::Latex), "\\frac{5}{7}");
  EXPECT_EQ(format_rational(Rational(12), Format::Latex), "12");
  EXPECT_EQ(format_rational(Rational(-12), Format::Text), "-12");
  EXPECT_EQ(format_rational(Rational(0), Format::Latex), "0");
}

TEST(Printer, Polynomials) {
  const Poly p(std::vector<long>{1, -1, 3});  // 3t^2 - t + 1
  EXPECT_EQ(format_poly(p, Format::Text), "3*t^2 - t + 1");
  EXPECT_EQ(format_poly(p, Format::Maple), "3*t^2 - t + 1");
  EXPECT_EQ(format_poly(p, Format::Latex), "3 t^{2} - t + 1");
  EXPECT_EQ(format_poly(Poly(0), Format::Latex), "0");
  EXPECT_EQ(format_poly(Poly(-5), Format::Text), "-5");
  EXPECT_EQ(format_poly(-Poly::t(), Format::Latex), "-t");
  EXPECT_EQ(format_poly(Poly(std::vector<long>{0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, -2}), Format::Latex), "-2 t^{11}");
  EXPECT_EQ(format_poly(Poly(std::vector<long>{-1, 0, 1}), Format::Text, "s"), "s^2 - 1");
  EXPECT_EQ(format_poly(Poly(std::vector<long>{0, 2}), Format::Latex, "u"), "2 u");
}

TEST(Printer, TextPolynomialsAgreeWithPolyStrAndParseBack) {
  std::mt19937_64 rng(5);
  const long iters = iterations(200);
  std::uniform_int_distribution<long> coef(-1000000, 1000000), deg(0, 7);
  for (long it = 0; it < iters; ++it) {
    std::vector<long> c;
    for (long i = deg(rng); i >= 0; --i) c.push_back(rng() % 3 ? coef(rng) : (rng() % 2 ? 1 : -1));
    const Poly p(c);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": " + p.str());
    EXPECT_EQ(format_poly(p, Format::Text), p.str());
    EXPECT_EQ(parse_expression(format_poly(p, Format::Maple)), RatFunc(p));
    const std::string latex = format_poly(p, Format::Latex);
    EXPECT_EQ(latex.find('*'), std::string::npos) << latex;
  }
}

TEST(Printer, RationalFunctions) {
  const RatFunc r = (T + q(1)) / (T * T + q(1));
  EXPECT_EQ(format_ratfunc(r, Format::Text), "(t + 1)/(t^2 + 1)");
  EXPECT_EQ(format_ratfunc(r, Format::Maple), "(t + 1)/(t^2 + 1)");
  EXPECT_EQ(format_ratfunc(r, Format::Latex), "\\frac{t + 1}{t^{2} + 1}");
  EXPECT_EQ(format_ratfunc(r, Format::Latex, "s"), "\\frac{s + 1}{s^{2} + 1}");
  EXPECT_EQ(format_ratfunc(q(1) - T * T, Format::Latex), "-t^{2} + 1");  // denominator 1: numerator only
  EXPECT_EQ(format_ratfunc(q(3, 2), Format::Text), "(3)/(2)");
  EXPECT_EQ(format_ratfunc(q(0), Format::Text), "0");
  EXPECT_EQ(format_ratfunc(r, Format::Text), r.str());
}

TEST(Printer, Balls) {
  EXPECT_EQ(format_ball(Ball(3), 10, Format::Text), "3");
  EXPECT_EQ(format_ball(Ball(3), 10, Format::Latex), "3");
  EXPECT_EQ(format_ball(Ball(3), 10, Format::Maple), "3.0");  // a float literal
  EXPECT_EQ(format_ball(Ball(Rational(-1, 4), 64), 10, Format::Maple), "-0.25");

  const Ball third(Rational(1, 3), 128);
  const std::string text = format_ball(third, 10, Format::Text);
  const std::size_t pm = text.find(" +/- ");
  ASSERT_NE(pm, std::string::npos) << text;
  EXPECT_EQ(text.substr(0, pm), "0.3333333333");
  const Rational rad = Rational::parse(text.substr(pm + 5));
  EXPECT_LE(abs(Rational(1, 3) - Rational::parse("0.3333333333")), rad) << text;
  EXPECT_LT(rad, Rational::parse("1e-10")) << text;

  const std::string latex = format_ball(third, 10, Format::Latex);
  EXPECT_EQ(latex.substr(0, 12), "0.3333333333") << latex;
  EXPECT_NE(latex.find(" \\pm "), std::string::npos) << latex;
  EXPECT_NE(latex.find(" \\cdot 10^{-"), std::string::npos) << latex;
  EXPECT_EQ(latex.find('e'), std::string::npos) << latex;
  EXPECT_EQ(format_ball(third, 10, Format::Maple), "0.3333333333");

  // Scientific midpoints in LaTeX.
  const Ball tiny(Rational::parse("1.5e-30"), 200);
  const std::string tl = format_ball(tiny, 5, Format::Latex);
  EXPECT_EQ(tl.substr(0, 20), "1.5 \\cdot 10^{-30} \\") << tl;
  EXPECT_NE(format_ball(tiny, 5, Format::Maple).find("e-30"), std::string::npos);
}

TEST(Printer, NonFiniteBallIsRefused) {
  Ball b;
  arb_indeterminate(b.get());
  EXPECT_THROW(format_ball(b, 5, Format::Text), DomainError);
  EXPECT_THROW(json_ball(b, 5), DomainError);
}

// ---- Json ---------------------------------------------------------------------------

TEST(Json, Scalars) {
  EXPECT_EQ(Json().dump(), "null");
  EXPECT_EQ(Json::boolean(true).dump(), "true");
  EXPECT_EQ(Json::boolean(false).dump(-1), "false");
  EXPECT_EQ(Json::number(-42).dump(), "-42");
  EXPECT_EQ(Json::number("1.25e-30").dump(), "1.25e-30");
  EXPECT_EQ(Json::number("0").dump(), "0");
  EXPECT_EQ(Json::string("abc").dump(), "\"abc\"");
  EXPECT_EQ(Json().kind(), Json::Kind::Null);
  EXPECT_EQ(Json::number(1).kind(), Json::Kind::Number);
  for (const char* bad : {"", "abc", "01", "1.", ".5", "1e", "+1", "NaN", "inf", "1 ", "0x10", "--1"}) {
    SCOPED_TRACE(bad);
    EXPECT_THROW(Json::number(std::string(bad)), InvalidArgument);
  }
}

TEST(Json, Escaping) {
  EXPECT_EQ(Json::string("a\"b\\c").dump(), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(Json::string("\n\r\t\b\f").dump(), "\"\\n\\r\\t\\b\\f\"");
  EXPECT_EQ(Json::string(std::string("\x01\x1f\0", 3)).dump(), "\"\\u0001\\u001f\\u0000\"");
  EXPECT_EQ(Json::string("/\x7f").dump(), "\"/\x7f\"");
  EXPECT_EQ(Json::string("\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80").dump(), "\"\xc3\xa9\xe2\x82\xac\xf0\x9f\x98\x80\"");
  // Ill-formed UTF-8 never reaches the output: each bad byte becomes U+FFFD.
  EXPECT_EQ(Json::string("a\xff" "b").dump(), "\"a\\ufffdb\"");
  EXPECT_EQ(Json::string("\xc0\xaf").dump(), "\"\\ufffd\\ufffd\"");         // overlong '/'
  EXPECT_EQ(Json::string("\xed\xa0\x80").dump(), "\"\\ufffd\\ufffd\\ufffd\"");  // surrogate
  EXPECT_EQ(Json::string("\xe2\x82").dump(), "\"\\ufffd\\ufffd\"");           // truncated
  EXPECT_EQ(Json::string("\xf4\x90\x80\x80").dump(), "\"\\ufffd\\ufffd\\ufffd\\ufffd\"");  // > U+10FFFF
  // Keys are escaped too.
  Json o = Json::object();
  o.set("k\"\n", Json());
  EXPECT_EQ(o.dump(-1), "{\"k\\\"\\n\":null}");
}

TEST(Json, EscapingRoundTripsProperty) {
  std::mt19937_64 rng(8259);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    std::string s;
    for (int i = static_cast<int>(rng() % 40); i > 0; --i) {
      unsigned long cp;
      switch (rng() % 4) {
        case 0: cp = rng() % 0x20; break;    // control characters
        case 1: cp = 0x20 + rng() % 0x60; break;  // printable ASCII incl. '"' and '\\'
        case 2: cp = 0x80 + rng() % 0xD780; break;  // BMP below the surrogates
        default: cp = 0x10000 + rng() % 0x100000; break;
      }
      append_utf8(s, cp);
    }
    SCOPED_TRACE("iteration " + std::to_string(it));
    EXPECT_EQ(roundtrip_string(s), s);
  }
}

TEST(Json, Structure) {
  Json doc = Json::object();
  doc.set("name", Json::string("circle"));
  doc.set("digits", Json::number(15));
  Json arr = Json::array();
  arr.push(Json::number(1)).push(Json::boolean(false)).push(Json());
  doc.set("list", arr);
  doc.set("empty_a", Json::array());
  doc.set("empty_o", Json::object());
  EXPECT_EQ(doc.dump(-1),
            "{\"name\":\"circle\",\"digits\":15,\"list\":[1,false,null],\"empty_a\":[],\"empty_o\":{}}");
  EXPECT_EQ(doc.dump(2),
            "{\n"
            "  \"name\": \"circle\",\n"
            "  \"digits\": 15,\n"
            "  \"list\": [\n"
            "    1,\n"
            "    false,\n"
            "    null\n"
            "  ],\n"
            "  \"empty_a\": [],\n"
            "  \"empty_o\": {}\n"
            "}");
  EXPECT_EQ(doc.dump(), doc.dump(2));
  // Replacing a key keeps its position.
  doc.set("digits", Json::string("x"));
  EXPECT_EQ(doc.dump(-1).find("\"name\":\"circle\",\"digits\":\"x\",\"list\""), 1u);
  EXPECT_EQ(doc.kind(), Json::Kind::Object);
}

TEST(Json, PreconditionsAreChecked) {
  Json a = Json::array(), o = Json::object(), n;
  EXPECT_THROW(o.push(Json()), InvalidArgument);
  EXPECT_THROW(n.push(Json()), InvalidArgument);
  EXPECT_THROW(a.set("k", Json()), InvalidArgument);
  EXPECT_THROW(Json::string("s").set("k", Json()), InvalidArgument);
}

// ---- the enclosure contract ---------------------------------------------------------

TEST(Json, BallContractProperty) {
  std::mt19937_64 rng(1729);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    // A ball around a random rational, widened by a random radius.
    Integer num(static_cast<long>(rng() % 2000000001) - 1000000000), den(1 + static_cast<long>(rng() % 1000000));
    const Rational x(num, den);
    Ball b(x, 20 + static_cast<long>(rng() % 200));
    mag_t extra;
    mag_init(extra);
    mag_set_ui_2exp_si(extra, rng() % 1000, -static_cast<long>(rng() % 120));
    mag_add(arb_radref(b.get()), arb_radref(b.get()), extra);
    mag_clear(extra);
    const long sig = 1 + static_cast<long>(rng() % 25);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": " + b.str(30) + ", sig " + std::to_string(sig));

    const std::string dumped = json_ball(b, sig).dump(-1);
    const DecimalEnclosure e = decimal_enclosure(b, sig);
    EXPECT_EQ(dumped, "{\"mid\":\"" + e.mid + "\",\"rad\":\"" + e.rad + "\"}");
    const Rational mid = Rational::parse(field(dumped, "mid")), rad = Rational::parse(field(dumped, "rad"));
    // The whole ball, not just x, lies in [mid - rad, mid + rad].
    const Rational m = mid_rational(b), r = rad_rational(b);
    EXPECT_LE(mid - rad, m - r) << dumped;
    EXPECT_GE(mid + rad, m + r) << dumped;
    EXPECT_LE(abs(x - mid), rad) << dumped;
  }
}

TEST(Json, RationalContractProperty) {
  EXPECT_EQ(json_rational(Rational(3, 4), 5).dump(-1), "{\"mid\":\"0.75\",\"rad\":\"0\",\"exact\":\"3/4\"}");
  EXPECT_EQ(json_rational(Rational(-7), 5).dump(-1), "{\"mid\":\"-7\",\"rad\":\"0\",\"exact\":\"-7\"}");
  std::mt19937_64 rng(144);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    const Rational x(Integer(static_cast<long>(rng() % 2000001) - 1000000), Integer(1 + static_cast<long>(rng() % 100000)));
    const long sig = 1 + static_cast<long>(rng() % 20);
    SCOPED_TRACE("iteration " + std::to_string(it) + ": " + x.str() + ", sig " + std::to_string(sig));
    const std::string dumped = json_rational(x, sig).dump(-1);
    const Rational mid = Rational::parse(field(dumped, "mid"));
    const std::string rad_text = field(dumped, "rad");
    const Rational rad = Rational::parse(rad_text);
    EXPECT_EQ(Rational::parse(field(dumped, "exact")), x) << dumped;
    EXPECT_LE(abs(x - mid), rad) << dumped;
    EXPECT_EQ(rad_text == "0", mid == x) << dumped;  // rad is 0 exactly when the decimal is exact
  }
}

}  // namespace
}  // namespace uniparam
