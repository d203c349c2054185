// printer.cpp -- text, LaTeX and Maple printers and the JSON builder (see
// printer.hpp). Every decimal printed for a ball or a rational goes through
// decimal.hpp, so a printed enclosure [mid - rad, mid + rad] always contains
// the exact value.

#include "uniparam/core/printer.hpp"

#include <cstdio>

#include "uniparam/core/decimal.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

/// "3.1e-17" -> "3.1 \cdot 10^{-17}"; plain decimals unchanged.
std::string latex_decimal(const std::string& d) {
  const std::size_t e = d.find('e');
  if (e == std::string::npos) return d;
  return d.substr(0, e) + " \\cdot 10^{" + d.substr(e + 1) + "}";
}

/// A decimal that Maple reads as a float: "10" -> "10.0"; "1.5", "1e-30" unchanged.
std::string maple_float(const std::string& d) {
  if (d.find_first_of(".e") != std::string::npos) return d;
  return d + ".0";
}

/// True when `s` is a JSON number per RFC 8259:
/// -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?
bool is_json_number(const std::string& s) {
  std::size_t i = 0;
  const std::size_t n = s.size();
  auto digit = [&](std::size_t k) { return k < n && s[k] >= '0' && s[k] <= '9'; };
  if (i < n && s[i] == '-') ++i;
  if (!digit(i)) return false;
  if (s[i] == '0') ++i;
  else while (digit(i)) ++i;
  if (i < n && s[i] == '.') {
    ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  if (i < n && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < n && (s[i] == '+' || s[i] == '-')) ++i;
    if (!digit(i)) return false;
    while (digit(i)) ++i;
  }
  return i == n;
}

/// Length of the well-formed UTF-8 sequence starting at s[i] (RFC 3629:
/// no overlong forms, no surrogates, at most U+10FFFF), or 0 if ill-formed.
std::size_t utf8_length(const std::string& s, std::size_t i) {
  auto byte = [&](std::size_t k) -> int { return k < s.size() ? static_cast<unsigned char>(s[k]) : -1; };
  auto cont = [&](std::size_t k, int lo, int hi) { int b = byte(k); return b >= lo && b <= hi; };
  const int c = byte(i);
  if (c >= 0xC2 && c <= 0xDF) return cont(i + 1, 0x80, 0xBF) ? 2 : 0;
  if (c >= 0xE0 && c <= 0xEF) {
    const int lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2, 0x80, 0xBF) ? 3 : 0;
  }
  if (c >= 0xF0 && c <= 0xF4) {
    const int lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    return cont(i + 1, lo, hi) && cont(i + 2, 0x80, 0xBF) && cont(i + 3, 0x80, 0xBF) ? 4 : 0;
  }
  return 0;
}

/// Appends s as a JSON string literal. Control characters are escaped;
/// bytes that are not well-formed UTF-8 become U+FFFD, so the output is
/// always valid JSON text.
void append_json_string(std::string& out, const std::string& s) {
  out += '"';
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\b': out += "\\b"; break;
        case '\f': out += "\\f"; break;
        case '\n': out += "\\n"; break;
        case '\r': out += "\\r"; break;
        case '\t': out += "\\t"; break;
        default:
          if (c < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", c);
            out += buf;
          } else {
            out += static_cast<char>(c);
          }
      }
      ++i;
      continue;
    }
    const std::size_t n = utf8_length(s, i);
    if (n == 0) {
      out += "\\ufffd";
      ++i;
    } else {
      out.append(s, i, n);
      i += n;
    }
  }
  out += '"';
}

void newline(std::string& out, int indent, int level) {
  if (indent < 0) return;
  out += '\n';
  out.append(static_cast<std::size_t>(indent) * static_cast<std::size_t>(level), ' ');
}

}  // namespace

std::string format_rational(const Rational& q, Format f) {
  if (f != Format::Latex || q.is_integer()) return q.str();
  const Integer num = q.num();
  const bool neg = num.sign() < 0;
  const std::string mag = neg ? (-q).num().str() : num.str();
  return std::string(neg ? "-" : "") + "\\frac{" + mag + "}{" + q.den().str() + "}";
}

std::string format_poly(const Poly& p, Format f, const char* var) {
  if (p.is_zero()) return "0";
  const bool latex = f == Format::Latex;
  std::string out;
  for (long i = p.degree(); i >= 0; --i) {
    const Integer c = p.coeff(i);
    if (c.sign() == 0) continue;
    const bool neg = c.sign() < 0;
    if (out.empty()) out += neg ? "-" : "";
    else out += neg ? " - " : " + ";
    const std::string mag = neg ? (Integer(0) - c).str() : c.str();
    const bool unit = i > 0 && mag == "1";
    if (!unit) out += mag;
    if (i == 0) continue;
    if (!unit) out += latex ? " " : "*";
    out += var;
    if (i > 1) out += latex ? "^{" + std::to_string(i) + "}" : "^" + std::to_string(i);
  }
  return out;
}

std::string format_ratfunc(const RatFunc& r, Format f, const char* var) {
  const Poly num = r.num(), den = r.den();
  if (den == Poly(1)) return format_poly(num, f, var);
  if (f == Format::Latex) return "\\frac{" + format_poly(num, f, var) + "}{" + format_poly(den, f, var) + "}";
  return "(" + format_poly(num, f, var) + ")/(" + format_poly(den, f, var) + ")";
}

// Throws DomainError for a non-finite ball (via decimal_enclosure).
std::string format_ball(const Ball& b, long sig_digits, Format f) {
  const DecimalEnclosure e = decimal_enclosure(b, sig_digits);
  const bool exact = e.rad == "0";  // the printed midpoint is the ball's exact value
  switch (f) {
    case Format::Latex:
      return latex_decimal(e.mid) + (exact ? "" : " \\pm " + latex_decimal(e.rad));
    case Format::Maple:
      return maple_float(e.mid);
    case Format::Text:
    default:
      return exact ? e.mid : e.mid + " +/- " + e.rad;
  }
}

// ---- Json ------------------------------------------------------------------------

Json Json::boolean(bool b) {
  Json j;
  j.kind_ = Kind::Bool;
  j.scalar_ = b ? "true" : "false";
  return j;
}

Json Json::number(const std::string& decimal_text) {
  if (!is_json_number(decimal_text))
    throw InvalidArgument("not a JSON number: '" + decimal_text + "'");
  Json j;
  j.kind_ = Kind::Number;
  j.scalar_ = decimal_text;
  return j;
}

Json Json::number(long v) { return number(std::to_string(v)); }

Json Json::string(const std::string& s) {
  Json j;
  j.kind_ = Kind::String;
  j.scalar_ = s;
  return j;
}

Json Json::array() {
  Json j;
  j.kind_ = Kind::Array;
  return j;
}

Json Json::object() {
  Json j;
  j.kind_ = Kind::Object;
  return j;
}

Json& Json::push(Json v) {
  if (kind_ != Kind::Array) throw InvalidArgument("Json::push needs an array");
  items_.push_back(std::move(v));
  return *this;
}

Json& Json::set(const std::string& key, Json v) {
  if (kind_ != Kind::Object) throw InvalidArgument("Json::set needs an object");
  for (auto& m : members_)
    if (m.first == key) {
      m.second = std::move(v);
      return *this;
    }
  members_.emplace_back(key, std::move(v));
  return *this;
}

std::string Json::dump(int indent) const {
  std::string out;
  dump_to(out, indent, 0);
  return out;
}

void Json::dump_to(std::string& out, int indent, int level) const {
  switch (kind_) {
    case Kind::Null: out += "null"; return;
    case Kind::Bool:
    case Kind::Number: out += scalar_; return;
    case Kind::String: append_json_string(out, scalar_); return;
    case Kind::Array:
      if (items_.empty()) { out += "[]"; return; }
      out += '[';
      for (std::size_t i = 0; i < items_.size(); ++i) {
        if (i > 0) out += ',';
        newline(out, indent, level + 1);
        items_[i].dump_to(out, indent, level + 1);
      }
      newline(out, indent, level);
      out += ']';
      return;
    case Kind::Object:
      if (members_.empty()) { out += "{}"; return; }
      out += '{';
      for (std::size_t i = 0; i < members_.size(); ++i) {
        if (i > 0) out += ',';
        newline(out, indent, level + 1);
        append_json_string(out, members_[i].first);
        out += indent < 0 ? ":" : ": ";
        members_[i].second.dump_to(out, indent, level + 1);
      }
      newline(out, indent, level);
      out += '}';
      return;
  }
}

Json json_ball(const Ball& b, long sig_digits) {
  const DecimalEnclosure e = decimal_enclosure(b, sig_digits);
  Json j = Json::object();
  j.set("mid", Json::string(e.mid));
  j.set("rad", Json::string(e.rad));
  return j;
}

Json json_balls(const std::vector<Ball>& bs, long sig_digits) {
  Json a = Json::array();
  for (const Ball& b : bs) a.push(json_ball(b, sig_digits));
  return a;
}

Json json_rational(const Rational& q, long sig_digits) {
  const std::string mid = decimal_string(q, sig_digits);
  Rational err = q - Rational::parse(mid);
  if (err.sign() < 0) err = -err;
  Json j = Json::object();
  j.set("mid", Json::string(mid));
  j.set("rad", Json::string(err.is_zero() ? std::string("0") : decimal_upper(err)));
  j.set("exact", Json::string(q.str()));
  return j;
}

}  // namespace uniparam
