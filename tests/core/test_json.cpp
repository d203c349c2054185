// Tests of the strict JSON reader (core/json.hpp): round trips through
// dump(), exact numbers, unicode escapes, every error kind with its
// position, the depth and length limits (deep nesting refused without a
// crash) and the typed accessors' messages.
#include <gtest/gtest.h>

#include <functional>
#include <random>
#include <string>

#include "support/errors.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/json.hpp"

namespace uniparam {
namespace {

// The ParseError of parse_json(text), or fails the test.
ParseError parse_error(const std::string& text, const JsonLimits& lim = {}) {
  try {
    parse_json(text, lim);
  } catch (const ParseError& e) {
    return e;
  }
  ADD_FAILURE() << "no ParseError for: " << text.substr(0, 80);
  return ParseError(0, "", "none");
}


TEST(JsonReader, ParsesEveryKind) {
  const JsonValue v = parse_json(R"( {"a": null, "b": true, "c": false, "d": -0.5e3, "e": "x\ty", "f": [1, [2], {}], "g": {"h": []}} )");
  ASSERT_TRUE(v.is_object());
  ASSERT_EQ(v.members.size(), 7u);
  EXPECT_EQ(v.members[0].first, "a");  // insertion order
  EXPECT_EQ(v.members[6].first, "g");
  EXPECT_TRUE(v.find("a")->is_null());
  EXPECT_TRUE(v.find("b")->as_bool("b"));
  EXPECT_FALSE(v.find("c")->as_bool("c"));
  EXPECT_EQ(v.find("d")->text, "-0.5e3");  // kept as text
  EXPECT_EQ(v.find("d")->as_rational("d"), Rational(-500));
  EXPECT_EQ(v.find("e")->as_string("e"), "x\ty");
  EXPECT_EQ(v.find("f")->as_array("f").size(), 3u);
  EXPECT_TRUE(v.find("g")->find("h")->is_array());
  EXPECT_EQ(v.find("zz"), nullptr);
}

TEST(JsonReader, NumbersAreExactDecimals) {
  const JsonValue v = parse_json("[0.1, 1e-3, -0, 123456789012345678901234567890.5, \"1/3\", \"-7/21\", 2E+2]");
  const auto& a = v.as_array("list");
  EXPECT_EQ(a[0].as_rational("x"), Rational(1, 10));
  EXPECT_EQ(a[1].as_rational("x"), Rational(1, 1000));
  EXPECT_EQ(a[2].as_rational("x"), Rational(0));
  EXPECT_EQ(a[3].as_rational("x"), Rational::parse("246913578024691357802469135781/2"));
  EXPECT_EQ(a[4].as_rational("x"), Rational(1, 3));
  EXPECT_EQ(a[5].as_rational("x"), Rational(-1, 3));
  EXPECT_EQ(a[6].as_rational("x"), Rational(200));
  EXPECT_EQ(parse_json("1e-0000000000003").as_rational("x"), Rational(1, 1000));  // leading zeros of an exponent
  EXPECT_EQ(parse_json("\"5e00\"").as_rational("x"), Rational(5));
  EXPECT_EQ(parse_json("7").as_long("n", 1, 10), 7);
  EXPECT_EQ(parse_json("7.0").as_long("n", 1, 10), 7);
}

TEST(JsonReader, RoundTripThroughDump) {
  // Random trees: dump, parse, dump again gives the same text.
  std::mt19937_64 rng(36);
  std::function<std::string(int)> gen = [&](int depth) -> std::string {
    switch (depth > 4 ? rng() % 4 : rng() % 6) {
      case 0: return "null";
      case 1: return rng() % 2 ? "true" : "false";
      case 2: return std::to_string(static_cast<long>(rng() % 2000) - 1000) + (rng() % 2 ? ".25e-7" : "");
      case 3: {
        std::string s;
        for (int k = static_cast<int>(rng() % 6); k > 0; --k) s += static_cast<char>(1 + rng() % 126);
        return json_quote(s);
      }
      case 4: {
        std::string s = "[";
        for (int k = static_cast<int>(rng() % 4); k > 0; --k) s += gen(depth + 1) + (k > 1 ? "," : "");
        return s + "]";
      }
      default: {
        std::string s = "{";
        for (int k = static_cast<int>(rng() % 4); k > 0; --k)
          s += json_quote("k" + std::to_string(k)) + ":" + gen(depth + 1) + (k > 1 ? "," : "");
        return s + "}";
      }
    }
  };
  for (int it = 0; it < 300; ++it) {
    const std::string text = gen(0);
    const JsonValue v = parse_json(text);
    EXPECT_EQ(v.dump(), text);
    EXPECT_EQ(parse_json(v.dump()).dump(), text);
  }
}

TEST(JsonReader, QuoteRoundTripsEveryByteBelow128) {
  std::string s;
  for (int c = 1; c < 128; ++c) s += static_cast<char>(c);
  EXPECT_EQ(parse_json(json_quote(s)).as_string("s"), s);
}

TEST(JsonReader, UnicodeEscapes) {
  EXPECT_EQ(parse_json(R"("\u00e9")").text, "\xC3\xA9");
  EXPECT_EQ(parse_json(R"("\u20AC")").text, "\xE2\x82\xAC");
  EXPECT_EQ(parse_json(R"("\ud83d\ude00")").text, "\xF0\x9F\x98\x80");  // surrogate pair
  EXPECT_EQ(parse_json("\"\xF0\x9F\x98\x80\"").text, "\xF0\x9F\x98\x80");  // raw UTF-8 kept
  EXPECT_EQ(parse_json(R"("\/\\\"\b\f\n\r\t")").text, "/\\\"\b\f\n\r\t");
}

TEST(JsonReader, ErrorKindsWithColumns) {
  struct Case { const char* text; std::size_t column; const char* words; };
  const Case cases[] = {
      {"", 1, "empty input"},
      {"   ", 4, "empty input"},
      {"[1, 2", 6, "unterminated array"},
      {"[1 2]", 4, "in an array"},
      {"{\"a\" 1}", 6, "after a key"},
      {"{a: 1}", 2, "in an object"},
      {"{\"a\": 1, \"a\": 2}", 10, "duplicate key"},
      {"{\"a\": 1,}", 9, "in an object"},
      {"[1,]", 4, "unexpected ']'"},
      {"01", 2, "leading zero"},
      {"+1", 1, "unexpected '+'"},
      {".5", 1, "unexpected '.'"},
      {"1.", 3, "no digit after '.'"},
      {"1e", 3, "no digit in the exponent"},
      {"-", 2, "malformed number"},
      {"NaN", 1, "unexpected 'N'"},
      {"tru", 1, "unexpected 't'"},
      {"\"abc", 1, "unterminated string"},
      {"\"a\\x\"", 3, "invalid escape"},
      {"\"a\\u12G4\"", 7, "malformed \\u escape"},
      {"\"\\ud800\"", 2, "lone high surrogate"},
      {"\"\\udc00\"", 2, "lone low surrogate"},
      {"\"\\ud800\\u0041\"", 2, "invalid surrogate pair"},
      {"\"a\tb\"", 3, "raw control character"},
      {"\"\xC3", 2, "truncated UTF-8"},
      {"\"\xC0\xAF\"", 2, "invalid UTF-8"},
      {"\"\xED\xA0\x80\"", 2, "invalid UTF-8"},  // an encoded surrogate
      {"1 2", 3, "after the JSON value"},
  };
  for (const auto& c : cases) {
    const ParseError e = parse_error(c.text);
    EXPECT_EQ(e.column(), c.column) << c.text;
    EXPECT_NE(std::string(e.what()).find(c.words), std::string::npos) << c.text << " -> " << e.what();
  }
}

TEST(JsonReader, MultiLineErrorsNameTheLine) {
  const ParseError e = parse_error("{\n  \"a\": [1,\n   2 x]\n}");
  EXPECT_EQ(e.column(), 6u);
  EXPECT_NE(std::string(e.what()).find("line 3"), std::string::npos) << e.what();
  const JsonValue v = parse_json("{\n  \"a\":\n    7}");
  EXPECT_EQ(v.find("a")->line, 3u);
  EXPECT_EQ(v.find("a")->column, 5u);
}

TEST(JsonReader, DeepNestingRefusedWithoutCrash) {
  const std::string deep = std::string(1000000, '[') + std::string(1000000, ']');
  const ParseError e = parse_error(deep);
  EXPECT_EQ(e.column(), 65u);
  EXPECT_NE(std::string(e.what()).find("nesting deeper than 64"), std::string::npos) << e.what();
  const std::string ok = std::string(64, '[') + std::string(64, ']');
  EXPECT_NO_THROW(parse_json(ok));
  const std::string objs = [] {
    std::string s;
    for (int k = 0; k < 65; ++k) s += "{\"a\":";
    return s + "1" + std::string(65, '}');
  }();
  EXPECT_THROW(parse_json(objs), ParseError);
  JsonLimits lim;
  lim.max_depth = 3;
  EXPECT_THROW(parse_json("[[[[1]]]]", lim), ParseError);
  EXPECT_NO_THROW(parse_json("[[[1]]]", lim));
  lim.max_depth = 0;
  EXPECT_THROW(parse_json("1", lim), InvalidArgument);
}

TEST(JsonReader, LengthLimit) {
  JsonLimits lim;
  lim.max_length = 10;
  EXPECT_NO_THROW(parse_json("[1,2,3,45]", lim));
  const ParseError e = parse_error("[1,2,3,456]", lim);
  EXPECT_NE(std::string(e.what()).find("more than the limit of 10"), std::string::npos) << e.what();
}

TEST(JsonReader, TypedAccessorsNameTheValue) {
  const JsonValue v = parse_json(R"({"degree": "two", "knots": 3, "w": [1e999999], "x": "1/0", "n": 2.5})");
  std::string m = test_support::message_of<InvalidArgument>([&] { v.find("degree")->as_long("\"degree\"", 1, 10); });
  EXPECT_NE(m.find("\"degree\" must be an integer, got a string"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("knots")->as_array("\"knots\""); });
  EXPECT_NE(m.find("\"knots\" must be an array, got a number"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("w")->items[0].as_rational("weight 0"); });
  EXPECT_NE(m.find("weight 0"), std::string::npos) << m;
  EXPECT_NE(m.find("exponent"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("x")->as_rational("x"); });
  EXPECT_NE(m.find("x: '1/0'"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("n")->as_long("n", 1, 10); });
  EXPECT_NE(m.find("n must be an integer from 1 to 10"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("knots")->find("a"); });
  EXPECT_NE(m.find("must be an object"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.as_string("the line"); });
  EXPECT_NE(m.find("the line must be a string, got an object"), std::string::npos) << m;
  m = test_support::message_of<InvalidArgument>([&] { v.find("degree")->as_bool("flag"); });
  EXPECT_NE(m.find("flag must be true or false"), std::string::npos) << m;
}

}  // namespace
}  // namespace uniparam
