// cli/composite.hpp -- the commands on composite curves (--svg, --nurbs):
// reading them, and the reports of uniformity, the maps, locate and sample.
// The readers and the JSON documents are also the Python module's
// (python/src/module.cpp), so both give identical strings.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "args.hpp"
#include "uniparam/reparam/all.hpp"

namespace uniparam::cli {

/// The composite curve of --svg PATH or --nurbs JSON (each also "-" for
/// standard input or "@FILE"), or nullopt when neither is given. An SVG path
/// must have one subpath unless --subpath K (0-based) picks one.
/// \throws ParseError, InvalidArgument as parse_svg_path / parse_nurbs
///         (bad data, an arc that is not exactly rational); DomainError for a
///         segment that is not a curve; BudgetExceeded above --max-degree.
std::optional<CompositeCurve> read_composite(const Args& a);

/// How the messages of the composite readers name their inputs: the CLI's
/// options by default; the Python module names its parameters.
struct CompositeNames {
  std::string svg = "--svg";
  std::string subpath = "--subpath K";
  std::string max_degree = "--max-degree";
  /// Added to the message of a path of several subpaths without a choice.
  std::string subpaths_hint = ", or give each to 'uniparam batch' as its own line";
};

/// The subpaths of SVG path data `text` (the text itself, not a file name)
/// read by parse_svg_path, `max_length` bounding the text.
/// \throws ParseError, InvalidArgument as parse_svg_path (an arc that is not
///         exactly rational among them); InvalidArgument for a path without
///         a segment.
std::vector<PathInput> read_svg_subpaths(const std::string& text, std::size_t max_length,
                                         const CompositeNames& names = {});

/// The composite curve of paths[subpath], or of the only path when subpath
/// is nullopt, its segments at most opt.max_degree.
/// \throws InvalidArgument for several paths and no subpath, or subpath out
///         of range (callers check the range first, naming their option);
///         DomainError for a segment that is not a curve; BudgetExceeded for
///         a segment above opt.max_degree.
CompositeCurve svg_composite(const std::vector<PathInput>& paths, std::optional<std::size_t> subpath,
                             const Options& opt, const CompositeNames& names = {});

/// The composite curve of the NURBS/B-spline JSON `text` (parse_nurbs, at
/// most opt.max_degree). \throws as parse_nurbs; DomainError, BudgetExceeded
/// as svg_composite.
CompositeCurve read_nurbs_composite(const std::string& text, const Options& opt, const CompositeNames& names = {});

/// Where a composite curve came from, for its description.
enum class CompositeSource { Svg, Nurbs, Other };

/// A one-line description: "SVG path of 12 segments", "NURBS curve of 4 segments".
std::string composite_description(CompositeSource source, const CompositeCurve& c);
/// The description of the composite curve of --svg or --nurbs in `a`.
std::string composite_description(const Args& a, const CompositeCurve& c);

/// `uniformity --json` on a composite curve described by `description`:
/// curve, speed, digits, segments, knots, identically_zero, mu, mean_square,
/// u, joints, corner_turning (angular speed), parts.
Json composite_uniformity_json(const std::string& description, const CompositeCurve& c, SpeedKind kind, long digits,
                               const CompositeUniformity& r);

/// `radical`, `moebius` and `reparam --json` on a composite curve: the map r
/// of method m (digits as computed), with c's joints; each part's map as
/// moebius_json / radical_json with formulas in `fmt`.
Json composite_map_json(const std::string& description, const CompositeCurve& c, SpeedKind kind, long digits,
                        const CompositeMethod& m, const CompositeMap& r, const std::vector<Joint>& joints, Format fmt);

/// What `radical`, `moebius` and `reparam` say when the C1 target of m was
/// missed on some segment (they print the best map).
std::string composite_target_missed_message(const CompositeMethod& m);

/// locate(args...), an InvalidArgument's message prefixed with "--<option>: "
/// (the value given to --option is out of range); other errors as locate().
template <class... A>
LocateResult locate_for_option(const std::string& option, const A&... args) {
  try {
    return locate(args...);
  } catch (const InvalidArgument& e) {
    throw InvalidArgument("--" + option + ": " + e.what());
  }
}

/// The text report of `locate` (curve, speed, mu, the value reached, t and
/// the point's coordinates) on the answer stream; `description` names the
/// curve, `whole` says what mu measures ("arc length", "turning angle").
void print_locate_text(const std::string& description, SpeedKind kind, const std::string& whole, const Rational& value,
                       LocateTarget target, const LocateResult& r, long digits);

/// `locate --json` on a composite curve (`option`: length, angle or
/// fraction; `value` the number given to it).
Json composite_locate_json(const std::string& description, SpeedKind kind, long digits, const std::string& option,
                           const Rational& value, const LocateResult& r);

/// `sample --json` on a composite curve, without "samples": for a map r
/// (method `method`: its name, or "none"), curve, speed, method, digits,
/// points, mu, u_before, u_after, segment_joints; for r null (method
/// exact), curve, speed, method, digits, points ("mu" is set once known).
/// Rows are sample_row_json.
Json composite_sample_header_json(const std::string& description, const CompositeCurve& c, SpeedKind kind,
                                  const std::string& method, const CompositeMap* r, long digits, long K);

/// The SVG document of `uniparam plot` for the composite curve c and the
/// map of method m (K sample points at 6 digits; `projection` as
/// --projection, empty for the default); `missed` is called when the C1
/// target was not reached on every segment (the best map is drawn).
/// \throws InvalidArgument for a bad projection or method; as composite_map
///         and CompositeSampler.
std::string composite_plot_svg(const std::string& description, const CompositeCurve& c, SpeedKind kind,
                               const CompositeMethod& m, long K, const std::string& projection, const Options& opt,
                               const std::function<void()>& missed);

/// `uniformity` on a composite curve (text or --json).
int run_uniformity_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt);

/// `radical`, `moebius` and `reparam` on a composite curve: the method of
/// `m`, printed as text or --json. Exit 4 when a C1 target was missed.
int run_map_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt,
                      const CompositeMethod& m, const std::string& command);

/// The map of --method radical | c0 | c1 (| none with `with_none`) for a
/// composite curve: --pieces (c0; default max(3, segments)), --target (c1;
/// default 0.99) and --max-pieces (c1, per segment).
/// \throws InvalidArgument for an unknown method, an option of another
///         method, a target outside (0, 1).
CompositeMethod read_composite_method(const Args& a, const CompositeCurve& c, bool with_none);

/// The method of --rational / --rational-digits added to `m` (Moebius kinds).
CompositeMethod with_rational(const Args& a, CompositeMethod m);

/// `locate` on a composite curve.
int run_locate_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt,
                         const Rational& value, LocateTarget target, const std::string& option);

/// The joints as JSON: index, t (the knot), continuous, smooth, angle (radians).
Json json_joints(const CompositeCurve& c, const std::vector<Joint>& joints, long pd);

}  // namespace uniparam::cli
