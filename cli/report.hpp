// cli/report.hpp -- turning results into JSON (the certified-real contract)
// and into text.
#pragma once

#include <string>
#include <utility>

#include "uniparam/reparam/all.hpp"

namespace uniparam::cli {

/// Significant digits printed for a result requested at `digits` digits.
inline long printed_digits(long digits) { return digits + 3; }

/// {"mid", "rad"} plus, for an exact rational, "exact": "p/q", and for an
/// irrational algebraic number "exact": {"poly": "...", "interval": ["lo", "hi"]}.
Json json_algebraic(const RealAlgebraic& x, long digits);
/// Text: "1/2", or "0.43869133765083082 (root of 27*t^4 - 1 in (43/100, 11/25))".
std::string text_algebraic(const RealAlgebraic& x, long digits);

/// A short isolating interval of an irrational algebraic number (decimal ends
/// with few digits, exactly one root inside): RealAlgebraic::short_interval.
std::pair<Rational, Rational> short_interval(const RealAlgebraic& x);

/// A quadratic surd q whose certified value is b: a rational as
/// json_rational, otherwise json_ball(b) plus "exact": {"text", "latex",
/// "maple"}. \pre b encloses q.
Json json_surd(const QuadraticSurd& q, const Ball& b, long pd);

/// {"text": ..., "latex": ..., "maple": ...} of a rational function.
Json json_ratfunc(const RatFunc& r);
/// [{"t": algebraic, "multiplicity": k}, ...] of the zeros of a speed.
Json json_zeros(const std::vector<SpeedZero>& zeros, long digits);

}  // namespace uniparam::cli
