// cli/json_reports.hpp -- the JSON documents of the commands, built from the
// library's results (with radical_json, commands.hpp, and moebius_json,
// moebius_report.hpp). The CLI prints them for --json; the Python module
// (python/) returns the same documents, so both give identical strings.
//
// `digits` is the precision the result was computed for (Options::digits):
// balls print printed_digits(digits) significant digits (report.hpp).
#pragma once

#include <optional>
#include <string>

#include "uniparam/reparam/all.hpp"

namespace uniparam::cli {

/// `uniparam uniformity --json`: curve, speed, digits, speed_squared, zeros,
/// identically_zero, mu, mean_square, u.
Json uniformity_json(const Curve& c, SpeedKind kind, long digits, const UniformityResult& r);

/// The "at" object of `uniparam radical --at Z --json`: z, r, p_r, speed,
/// at_joint of the values v of p o r at z (radical_json, commands.hpp, gives
/// the rest of the document).
Json radical_at_json(const Rational& z, const SamplePoint& v, long digits);

/// The values of p o r at z for `uniparam radical --at Z` (the Python
/// module's at=), certified to opt.digits + 1: r's data are refined as far
/// as the evaluation needs (an ill-conditioned map needs them to more
/// digits than the report), within opt.max_prec.
/// \pre r = radical(c, kind, opt); z in [0, 1] (unit_at).
/// \throws as Sampler::at (BudgetExceeded, time budget).
SamplePoint radical_at(const Curve& c, SpeedKind kind, const RadicalResult& r, const Rational& z, const Options& opt);

/// z, checked to lie in [0, 1] before anything is computed.
/// \throws InvalidArgument "<name> must lie in [0, 1], got <z>" otherwise.
Rational unit_at(const std::string& name, const Rational& z);

/// Whether the exact weights of a Bezier result of degree n are printed
/// expanded, for --exact-weights `form` ("expanded", "formula" or "auto":
/// expanded while the largest has at most 4096 characters).
/// \throws InvalidArgument for another form.
bool expand_weights(const std::string& form, const BezierResult& r, long n);

/// `uniparam bezier --json` for bz and its result r; `expanded` as
/// expand_weights.
Json bezier_json(const BezierCurve& bz, const BezierResult& r, long digits, bool expanded);

/// `uniparam locate --json`: `option` is "length", "angle" or "fraction",
/// `value` the number given to it.
Json locate_json(const Curve& c, SpeedKind kind, long digits, const std::string& option, const Rational& value,
                 const LocateResult& r);

/// `uniparam sample --json` without its "samples": curve, speed, method,
/// digits, points (K), mu, u_before, u_after, joints.
Json sample_header_json(const Curve& c, SpeedKind kind, const Reparameterization& r, long digits, long K);
/// One row of "samples": s, t, point, speed, at_joint.
Json sample_row_json(const SamplePoint& p, long digits);
/// `uniparam sample --method exact --json` without "mu" (set once known)
/// and "samples"; its rows are sample_row_json of points whose speed is mu.
Json sample_exact_header_json(const Curve& c, SpeedKind kind, long digits, long K);

/// The SVG document of `uniparam plot` for c reparameterized by r (K sample
/// points; `projection` as --projection, empty for the default; `target` the
/// text of --target named in the title of a C1 map).
/// \throws InvalidArgument for a bad projection; as sample().
std::string plot_svg(const Curve& c, SpeedKind kind, const Reparameterization& r, long K,
                     const std::string& projection, const std::string& target, const Options& opt);

}  // namespace uniparam::cli
