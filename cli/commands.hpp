// cli/commands.hpp -- the table of subcommands.
#pragma once

#include <vector>

#include "args.hpp"
#include "uniparam/uniparam.hpp"

namespace uniparam::cli {

struct Command {
  CommandSpec spec;
  int (*run)(int argc, char** argv);  ///< argv[1] is the command name
};

const std::vector<Command>& commands();

/// Options shared by the certified commands: --speed, --digits, --json,
/// --max-prec, --max-degree, --control, --weights.
std::vector<OptionSpec> common_options();
/// Reads --digits, --max-prec, --max-degree (validated ranges).
Options read_options(const Args& a);
/// The curve a command works on: its CURVE argument, or the Bezier curve of
/// --control (and --weights) in the power basis (every command reads its
/// curve through here, so new ways of giving one apply to all commands).
/// \throws ParseError, DomainError as Curve::parse; InvalidArgument for
///         --weights without --control and as read_bezier.
Curve read_curve(const Args& a);
/// The Bezier curve of --control and --weights (at most --max-degree + 1
/// points). \throws ParseError, InvalidArgument as BezierCurve::parse;
/// InvalidArgument when --control is missing.
BezierCurve read_bezier(const Args& a);

// One pair per command, defined in cmd_<name>.cpp.
CommandSpec uniformity_spec();
int run_uniformity(int argc, char** argv);
CommandSpec radical_spec();
int run_radical(int argc, char** argv);
CommandSpec moebius_spec();
int run_moebius(int argc, char** argv);
CommandSpec reparam_spec();
int run_reparam(int argc, char** argv);
/// --format, --rational, --rational-digits of the Moebius commands.
std::vector<OptionSpec> moebius_output_options();
/// "0,1/3,2/3,1" -> breakpoints (exact rationals; checked later by the method).
std::vector<RealAlgebraic> parse_breakpoints(const std::string& list);
/// Applies --rational / --rational-digits to a result.
MoebiusResult finish_moebius(const Curve& c, const MoebiusResult& r, const Args& a, const Options& opt);
CommandSpec bezier_spec();
int run_bezier(int argc, char** argv);
/// Parses --format text|latex|maple.
Format parse_format(const std::string& s);

}  // namespace uniparam::cli
