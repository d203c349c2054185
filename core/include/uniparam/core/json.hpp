// uniparam/core/json.hpp -- a small, strict JSON reader (RFC 8259) for user
// input: NURBS descriptions, batch lines.
//
// Numbers are kept as their text, so that a caller reads them exactly
// (JsonValue::as_rational: "0.1" is 1/10, never the double nearest to it).
// Objects keep their keys in input order; a key given twice is an error.
#pragma once

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/number.hpp"

namespace uniparam {

/// Bounds of parse_json: nesting depth of arrays and objects, and the length
/// of the text in bytes.
struct JsonLimits {
  int max_depth = 64;
  std::size_t max_length = std::size_t(1) << 26;
};

/// One JSON value read by parse_json (the writer of results is printer.hpp's Json).
struct JsonValue {
  enum class Kind { Null, Bool, Number, String, Array, Object };
  Kind kind = Kind::Null;
  bool boolean = false;   ///< Kind::Bool
  std::string text;       ///< Kind::Number: the number's text as written; Kind::String: the value (UTF-8)
  std::vector<JsonValue> items;                              ///< Kind::Array
  std::vector<std::pair<std::string, JsonValue>> members;    ///< Kind::Object, in input order, keys distinct
  std::size_t line = 1, column = 1;  ///< where the value starts in the parsed text (1-based)

  /// Whether the value is of that kind.
  bool is_null() const { return kind == Kind::Null; }
  bool is_bool() const { return kind == Kind::Bool; }
  bool is_number() const { return kind == Kind::Number; }
  bool is_string() const { return kind == Kind::String; }
  bool is_array() const { return kind == Kind::Array; }
  bool is_object() const { return kind == Kind::Object; }
  /// "null", "a boolean", "a number", "a string", "an array", "an object".
  const char* kind_name() const;

  /// The member named `key`, or nullptr when absent.
  /// \throws InvalidArgument when this value is not an object.
  const JsonValue* find(const std::string& key) const;

  /// Typed access. `what` names the value in the message ("\"degree\"",
  /// "knot 3"). \throws InvalidArgument "<what> must be <kind>, got <kind>"
  /// when the value has another kind.
  bool as_bool(const std::string& what) const;
  const std::string& as_string(const std::string& what) const;
  const std::vector<JsonValue>& as_array(const std::string& what) const;
  const std::vector<std::pair<std::string, JsonValue>>& as_object(const std::string& what) const;
  /// The exact rational of a number ("0.25", "-1e-3", read as decimals) or
  /// of a string holding one ("1/3", "0.25", "-2").
  /// \throws InvalidArgument naming `what` for any other kind, malformed
  ///         text, a zero denominator, or a decimal exponent of 1000 or more
  ///         in absolute value (10^(10^6)-sized numbers).
  Rational as_rational(const std::string& what) const;
  /// An integer number (JSON text without fraction or exponent, or one whose
  /// exact value is an integer) in [lo, hi].
  /// \throws InvalidArgument naming `what` otherwise.
  long as_long(const std::string& what, long lo, long hi) const;

  /// Compact JSON text of this value (numbers as their text, keys in order);
  /// parse_json(v.dump()) reproduces v (positions aside).
  std::string dump() const;
};

/// Parses `text` as exactly one JSON value (RFC 8259), surrounded by optional
/// whitespace (space, tab, LF, CR). Strings must be valid UTF-8 without raw
/// control characters; escapes \" \\ \/ \b \f \n \r \t \uXXXX (surrogate
/// pairs combined; a lone surrogate is an error). Numbers follow the JSON
/// grammar ("-0.5e3"; no "+1", ".5", "01", NaN).
/// \pre 1 <= limits.max_depth <= 10000 (checked: InvalidArgument).
/// \post the returned tree has depth <= limits.max_depth; recursion depth is
///       bounded by it.
/// \throws ParseError whose column() is the 1-based column within its line,
///         its message naming the line when the text has several, for
///         malformed text, a duplicate key, nesting deeper than
///         limits.max_depth, or text longer than limits.max_length.
JsonValue parse_json(const std::string& text, const JsonLimits& limits = {});

/// `s` as a JSON string literal with quotes, as printer.hpp's Json writes it:
/// ", \ and control characters escaped (\n, \t, ... or \u00XX), valid UTF-8
/// copied, each byte of invalid UTF-8 as \ufffd (so the literal is always
/// valid JSON).
std::string json_quote(const std::string& s);

/// Appends the code point cp (\pre cp <= 0x10FFFF, not checked) to out as
/// 1 to 4 bytes of UTF-8. Never throws beyond allocation.
void append_utf8(std::string& out, unsigned long cp);

}  // namespace uniparam
