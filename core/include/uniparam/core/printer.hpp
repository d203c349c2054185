// uniparam/core/printer.hpp -- printers for exact values and balls: plain
// text, LaTeX, Maple, and a small JSON document builder.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"
#include "uniparam/core/ratfunc.hpp"

namespace uniparam {

enum class Format { Text, Latex, Maple };

/// A rational number: "-3/4" (text, Maple), "-\frac{3}{4}" (LaTeX).
std::string format_rational(const Rational& q, Format f);
/// A polynomial in `var`: "3*t^2 - t + 1" (text, Maple), "3 t^{2} - t + 1" (LaTeX).
std::string format_poly(const Poly& p, Format f, const char* var = "t");
/// A rational function: "(n)/(d)" (text, Maple), "\frac{n}{d}" (LaTeX);
/// just the numerator when the denominator is 1.
std::string format_ratfunc(const RatFunc& r, Format f, const char* var = "t");
/// A ball as a decimal enclosure: "1.2490457723982544 +/- 3.1e-17" (text),
/// "1.2490457723982544 \pm 3.1 \cdot 10^{-17}" (LaTeX); Maple gets the midpoint
/// only with a comment-free float literal. Exact balls print without radius.
std::string format_ball(const Ball& b, long sig_digits, Format f);

/// A JSON value: null, bool, number (kept as its exact decimal text), string,
/// array, object (keys keep insertion order). Strings are escaped per RFC 8259.
class Json {
 public:
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Json() = default;  ///< null
  /// true/false; a number; a string (any bytes; escaped when dumped); an
  /// empty array; an empty object.
  static Json boolean(bool b);
  static Json number(const std::string& decimal_text);  ///< \pre valid JSON number text (not checked)
  static Json number(long v);
  static Json string(const std::string& s);
  static Json array();
  static Json object();

  /// Appends to an array. \pre kind() == Array (checked: InvalidArgument).
  Json& push(Json v);
  /// Sets a key of an object, replacing an existing one.
  /// \pre kind() == Object (checked: InvalidArgument).
  Json& set(const std::string& key, Json v);
  /// Which of the six kinds this value is.
  Kind kind() const { return kind_; }
  /// Serialises; indent < 0 gives one line, otherwise pretty-printed.
  std::string dump(int indent = 2) const;

 private:
  Kind kind_ = Kind::Null;
  std::string scalar_;  // number text, string contents, or "true"/"false"
  std::vector<Json> items_;
  std::vector<std::pair<std::string, Json>> members_;
  void dump_to(std::string& out, int indent, int level) const;
};

/// The JSON contract of every certified real:
/// {"mid": "<decimal>", "rad": "<decimal>"}: the true value is in
/// [mid - rad, mid + rad]. `sig_digits` significant digits for mid; the
/// printing error is included in rad (see decimal.hpp).
Json json_ball(const Ball& b, long sig_digits);
/// A JSON array of json_ball(b, sig_digits) for each b, in order.
Json json_balls(const std::vector<Ball>& bs, long sig_digits);
/// An exact rational: {"mid": "<decimal>", "rad": "0", "exact": "p/q"} when
/// the decimal is exact, otherwise rad bounds the decimal's error and
/// "exact" still gives p/q.
Json json_rational(const Rational& q, long sig_digits);

}  // namespace uniparam
