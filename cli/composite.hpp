// cli/composite.hpp -- the commands on composite curves (--svg, --nurbs):
// reading them, and the reports of uniformity, the maps and locate.
#pragma once

#include <optional>
#include <string>

#include "args.hpp"
#include "uniparam/uniparam.hpp"

namespace uniparam::cli {

/// The composite curve of --svg PATH or --nurbs JSON (each also "-" for
/// standard input or "@FILE"), or nullopt when neither is given. An SVG path
/// must have one subpath unless --subpath K (0-based) picks one.
/// \throws ParseError, InvalidArgument as parse_svg_path / parse_nurbs
///         (bad data, an arc that is not exactly rational); DomainError for a
///         segment that is not a curve; BudgetExceeded above --max-degree.
std::optional<CompositeCurve> read_composite(const Args& a);

/// A one-line description: "SVG path of 12 segments", "NURBS of 4 segments".
std::string composite_description(const Args& a, const CompositeCurve& c);

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
