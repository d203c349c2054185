// The strict JSON reader of json.hpp: a recursive-descent parser whose
// recursion depth is bounded by JsonLimits::max_depth.
#include "uniparam/core/json.hpp"

#include "uniparam/core/printer.hpp"

#include <cstdint>

#include "uniparam/core/error.hpp"

namespace uniparam {

namespace {

class Parser {
 public:
  Parser(const std::string& s, const JsonLimits& lim) : s_(s), lim_(lim) {
    multiline_ = s.find('\n') != std::string::npos;
  }

  JsonValue parse_document() {
    if (lim_.max_depth < 1 || lim_.max_depth > 10000)
      throw InvalidArgument("parse_json: max_depth must be from 1 to 10000, got " + std::to_string(lim_.max_depth));
    if (s_.size() > lim_.max_length)
      fail(0, "", "the JSON text has " + std::to_string(s_.size()) + " bytes, more than the limit of " +
                      std::to_string(lim_.max_length));
    skip_ws();
    if (i_ >= s_.size()) fail(i_, "a JSON value", "empty input");
    JsonValue v = value(0);
    skip_ws();
    if (i_ < s_.size()) fail(i_, "end of input", "unexpected text after the JSON value");
    return v;
  }

 private:
  const std::string& s_;
  const JsonLimits& lim_;
  bool multiline_ = false;
  std::size_t i_ = 0;
  std::size_t line_ = 1, line_start_ = 0;

  // Line and column (1-based, column in bytes) of byte offset `at`.
  std::pair<std::size_t, std::size_t> position(std::size_t at) const {
    std::size_t line = 1, start = 0;
    for (std::size_t k = 0; k < at && k < s_.size(); ++k)
      if (s_[k] == '\n') { ++line; start = k + 1; }
    return {line, at - start + 1};
  }

  [[noreturn]] void fail(std::size_t at, const std::string& expected, const std::string& detail) const {
    auto [line, col] = position(at);
    throw ParseError(col, expected, multiline_ ? "line " + std::to_string(line) + ": " + detail : detail);
  }


  // Newlines occur only in whitespace (a raw one in a string is an error),
  // so the line is tracked here.
  void skip_ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t' || s_[i_] == '\n' || s_[i_] == '\r')) {
      if (s_[i_] == '\n') { ++line_; line_start_ = i_ + 1; }
      ++i_;
    }
  }

  bool literal(const char* word) {
    std::size_t k = 0;
    while (word[k] && i_ + k < s_.size() && s_[i_ + k] == word[k]) ++k;
    if (word[k]) return false;
    i_ += k;
    return true;
  }

  JsonValue value(int depth) {
    JsonValue v;
    v.line = line_;
    v.column = i_ - line_start_ + 1;
    const char c = s_[i_];
    if (c == '{' || c == '[') {
      if (depth >= lim_.max_depth)
        fail(i_, "", "nesting deeper than " + std::to_string(lim_.max_depth) + " levels");
      if (c == '{') object(v, depth + 1); else array(v, depth + 1);
    } else if (c == '"') {
      v.kind = JsonValue::Kind::String;
      v.text = string_literal();
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      v.kind = JsonValue::Kind::Number;
      v.text = number();
    } else if (literal("true")) {
      v.kind = JsonValue::Kind::Bool;
      v.boolean = true;
    } else if (literal("false")) {
      v.kind = JsonValue::Kind::Bool;
    } else if (literal("null")) {
      v.kind = JsonValue::Kind::Null;
    } else {
      fail(i_, "a JSON value", "unexpected " + shown_char(c));
    }
    return v;
  }

  void array(JsonValue& v, int depth) {
    v.kind = JsonValue::Kind::Array;
    ++i_;  // '['
    skip_ws();
    if (i_ < s_.size() && s_[i_] == ']') { ++i_; return; }
    for (;;) {
      skip_ws();
      if (i_ >= s_.size()) fail(i_, "a JSON value", "unterminated array");
      v.items.push_back(value(depth));
      skip_ws();
      if (i_ >= s_.size()) fail(i_, "',' or ']'", "unterminated array");
      if (s_[i_] == ',') { ++i_; continue; }
      if (s_[i_] == ']') { ++i_; return; }
      fail(i_, "',' or ']'", "unexpected " + shown_char(s_[i_]) + " in an array");
    }
  }

  void object(JsonValue& v, int depth) {
    v.kind = JsonValue::Kind::Object;
    ++i_;  // '{'
    skip_ws();
    if (i_ < s_.size() && s_[i_] == '}') { ++i_; return; }
    for (;;) {
      skip_ws();
      if (i_ >= s_.size()) fail(i_, "a key", "unterminated object");
      if (s_[i_] != '"') fail(i_, "a key in double quotes", "unexpected " + shown_char(s_[i_]) + " in an object");
      const std::size_t key_at = i_;
      std::string key = string_literal();
      for (const auto& m : v.members)
        if (m.first == key) fail(key_at, "", "duplicate key " + json_quote(key));
      skip_ws();
      if (i_ >= s_.size() || s_[i_] != ':')
        fail(i_, "':'", i_ >= s_.size() ? "unterminated object" : "unexpected " + shown_char(s_[i_]) + " after a key");
      ++i_;
      skip_ws();
      if (i_ >= s_.size()) fail(i_, "a JSON value", "unterminated object");
      JsonValue member = value(depth);
      v.members.emplace_back(std::move(key), std::move(member));
      skip_ws();
      if (i_ >= s_.size()) fail(i_, "',' or '}'", "unterminated object");
      if (s_[i_] == ',') { ++i_; continue; }
      if (s_[i_] == '}') { ++i_; return; }
      fail(i_, "',' or '}'", "unexpected " + shown_char(s_[i_]) + " in an object");
    }
  }

  static bool digit(char c) { return c >= '0' && c <= '9'; }

  std::string number() {
    const std::size_t start = i_;
    if (s_[i_] == '-') ++i_;
    if (i_ >= s_.size() || !digit(s_[i_])) fail(i_, "a digit", "malformed number");
    if (s_[i_] == '0') {
      ++i_;
      if (i_ < s_.size() && digit(s_[i_])) fail(i_, "'.', 'e' or the end of the number", "leading zero in a number");
    } else {
      while (i_ < s_.size() && digit(s_[i_])) ++i_;
    }
    if (i_ < s_.size() && s_[i_] == '.') {
      ++i_;
      if (i_ >= s_.size() || !digit(s_[i_])) fail(i_, "a digit", "malformed number: no digit after '.'");
      while (i_ < s_.size() && digit(s_[i_])) ++i_;
    }
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
      if (i_ >= s_.size() || !digit(s_[i_])) fail(i_, "a digit", "malformed number: no digit in the exponent");
      while (i_ < s_.size() && digit(s_[i_])) ++i_;
    }
    return s_.substr(start, i_ - start);
  }

  unsigned hex4() {
    unsigned v = 0;
    for (int k = 0; k < 4; ++k, ++i_) {
      if (i_ >= s_.size()) fail(i_, "four hexadecimal digits", "unterminated \\u escape");
      const char c = s_[i_];
      unsigned d;
      if (c >= '0' && c <= '9') d = c - '0';
      else if (c >= 'a' && c <= 'f') d = c - 'a' + 10;
      else if (c >= 'A' && c <= 'F') d = c - 'A' + 10;
      else fail(i_, "a hexadecimal digit", "malformed \\u escape");
      v = v * 16 + d;
    }
    return v;
  }


  // A raw multi-byte UTF-8 sequence starting at i_ (lead byte >= 0x80):
  // checked (no overlong forms, no surrogates, at most U+10FFFF) and copied.
  void utf8_sequence(std::string& out) {
    const std::size_t at = i_;
    const auto b0 = static_cast<unsigned char>(s_[i_]);
    int len;
    std::uint32_t cp;
    if (b0 >= 0xC2 && b0 <= 0xDF) { len = 2; cp = b0 & 0x1F; }
    else if (b0 >= 0xE0 && b0 <= 0xEF) { len = 3; cp = b0 & 0x0F; }
    else if (b0 >= 0xF0 && b0 <= 0xF4) { len = 4; cp = b0 & 0x07; }
    else fail(at, "UTF-8 text", "invalid UTF-8 " + shown_char(s_[at]) + " in a string");
    for (int k = 1; k < len; ++k) {
      if (at + k >= s_.size()) fail(at, "UTF-8 text", "truncated UTF-8 sequence in a string");
      const auto b = static_cast<unsigned char>(s_[at + k]);
      if ((b & 0xC0) != 0x80) fail(at, "UTF-8 text", "invalid UTF-8 sequence in a string");
      cp = (cp << 6) | (b & 0x3F);
    }
    if ((len == 3 && cp < 0x800) || (len == 4 && cp < 0x10000) || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF))
      fail(at, "UTF-8 text", "invalid UTF-8 sequence in a string");
    out.append(s_, at, len);
    i_ = at + len;
  }

  std::string string_literal() {
    const std::size_t open = i_;
    ++i_;  // '"'
    std::string out;
    for (;;) {
      if (i_ >= s_.size()) fail(open, "a closing '\"'", "unterminated string");
      const char c = s_[i_];
      const auto u = static_cast<unsigned char>(c);
      if (c == '"') { ++i_; return out; }
      if (u < 0x20) fail(i_, "'\\n' style escapes", "raw control character " + shown_char(c) + " in a string");
      if (u >= 0x80) { utf8_sequence(out); continue; }
      if (c != '\\') { out += c; ++i_; continue; }
      const std::size_t esc = i_;
      ++i_;
      if (i_ >= s_.size()) fail(open, "a closing '\"'", "unterminated string");
      const char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xDC00 && cp <= 0xDFFF) fail(esc, "", "lone low surrogate \\u escape");
          if (cp >= 0xD800 && cp <= 0xDBFF) {
            if (i_ + 1 >= s_.size() || s_[i_] != '\\' || s_[i_ + 1] != 'u')
              fail(esc, "a low surrogate \\uDC00-\\uDFFF", "lone high surrogate \\u escape");
            i_ += 2;
            const std::uint32_t lo = hex4();
            if (lo < 0xDC00 || lo > 0xDFFF) fail(esc, "a low surrogate \\uDC00-\\uDFFF", "invalid surrogate pair");
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          append_utf8(out, cp);
          break;
        }
        default:
          fail(esc, "one of \\\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX", "invalid escape '\\" + std::string(1, e) + "'");
      }
    }
  }
};

[[noreturn]] void wrong_kind(const std::string& what, const char* want, const JsonValue& v) {
  throw InvalidArgument(what + " must be " + want + ", got " + v.kind_name() + " (line " + std::to_string(v.line) +
                        ", column " + std::to_string(v.column) + ")");
}

void dump_to(const JsonValue& v, std::string& out) {
  switch (v.kind) {
    case JsonValue::Kind::Null: out += "null"; break;
    case JsonValue::Kind::Bool: out += v.boolean ? "true" : "false"; break;
    case JsonValue::Kind::Number: out += v.text; break;
    case JsonValue::Kind::String: out += json_quote(v.text); break;
    case JsonValue::Kind::Array:
      out += '[';
      for (std::size_t k = 0; k < v.items.size(); ++k) {
        if (k) out += ',';
        dump_to(v.items[k], out);
      }
      out += ']';
      break;
    case JsonValue::Kind::Object:
      out += '{';
      for (std::size_t k = 0; k < v.members.size(); ++k) {
        if (k) out += ',';
        out += json_quote(v.members[k].first);
        out += ':';
        dump_to(v.members[k].second, out);
      }
      out += '}';
      break;
  }
}

}  // namespace

const char* JsonValue::kind_name() const {
  switch (kind) {
    case Kind::Null: return "null";
    case Kind::Bool: return "a boolean";
    case Kind::Number: return "a number";
    case Kind::String: return "a string";
    case Kind::Array: return "an array";
    case Kind::Object: return "an object";
  }
  return "?";
}

const JsonValue* JsonValue::find(const std::string& key) const {
  if (!is_object()) wrong_kind("a value looked up by key (\"" + key + "\")", "an object", *this);
  for (const auto& m : members)
    if (m.first == key) return &m.second;
  return nullptr;
}

bool JsonValue::as_bool(const std::string& what) const {
  if (!is_bool()) wrong_kind(what, "true or false", *this);
  return boolean;
}

const std::string& JsonValue::as_string(const std::string& what) const {
  if (!is_string()) wrong_kind(what, "a string", *this);
  return text;
}

const std::vector<JsonValue>& JsonValue::as_array(const std::string& what) const {
  if (!is_array()) wrong_kind(what, "an array", *this);
  return items;
}

const std::vector<std::pair<std::string, JsonValue>>& JsonValue::as_object(const std::string& what) const {
  if (!is_object()) wrong_kind(what, "an object", *this);
  return members;
}

Rational JsonValue::as_rational(const std::string& what) const {
  if (!is_number() && !is_string()) wrong_kind(what, "a number or a string such as \"1/3\"", *this);
  std::string s = text;
  const std::string where = " (line " + std::to_string(line) + ", column " + std::to_string(column) + ")";
  const auto e = s.find_first_of("eE");
  if (e != std::string::npos) {
    std::size_t k = e + 1;
    if (k < s.size() && (s[k] == '+' || s[k] == '-')) ++k;
    std::size_t z = k;
    while (z + 1 < s.size() && s[z] == '0') ++z;  // leading zeros of the exponent
    if (s.size() - z > 3)
      throw InvalidArgument(what + ": the number '" + s.substr(0, 40) + (s.size() > 40 ? "..." : "") +
                            "' has a decimal exponent of 1000 or more in absolute value" + where);
    s.erase(k, z - k);
  }
  try {
    return Rational::parse(s);
  } catch (const Error& err) {
    throw InvalidArgument(what + ": '" + s.substr(0, 40) + (s.size() > 40 ? "..." : "") +
                          "' is not an exact rational such as 1/3, 0.25 or 1e-3" + where + " (" + err.what() + ")");
  }
}

long JsonValue::as_long(const std::string& what, long lo, long hi) const {
  if (!is_number()) wrong_kind(what, "an integer", *this);
  const Rational r = as_rational(what);
  if (!r.is_integer() || r < Rational(lo) || r > Rational(hi))
    throw InvalidArgument(what + " must be an integer from " + std::to_string(lo) + " to " + std::to_string(hi) +
                          ", got " + text.substr(0, 40));
  return fmpz_get_si(fmpq_numref(r.get()));
}

std::string JsonValue::dump() const {
  std::string out;
  dump_to(*this, out);
  return out;
}

JsonValue parse_json(const std::string& text, const JsonLimits& limits) { return Parser(text, limits).parse_document(); }

std::string json_quote(const std::string& s) { return Json::string(s).dump(-1); }

void append_utf8(std::string& out, unsigned long cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xC0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xE0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  } else {
    out += static_cast<char>(0xF0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (cp & 0x3F));
  }
}

}  // namespace uniparam
