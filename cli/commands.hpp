// cli/commands.hpp -- the table of subcommands.
#pragma once

#include <vector>

#include "args.hpp"
#include "uniparam/reparam/all.hpp"

namespace uniparam::cli {

struct Command {
  CommandSpec spec;
  int (*run)(int argc, char** argv);  ///< argv[1] is the command name
};

const std::vector<Command>& commands();

/// Options shared by the certified commands: --speed, --digits, --json,
/// --control, --weights and the budgets --max-prec, --max-degree, --max-bits,
/// --max-length, --max-depth, --timeout (docs/robustness.md).
std::vector<OptionSpec> common_options();
/// Reads --digits, --max-prec, --max-degree (validated ranges).
Options read_options(const Args& a);
/// Reads the limits of the curve parser: --max-degree (degree and exponent),
/// --max-bits, --max-length, --max-depth (validated ranges; InvalidArgument).
ParseLimits read_parse_limits(const Args& a);
/// The exact rational `text` given to option --`option` ("1/3", "0.25",
/// "1e-3"). \throws InvalidArgument naming the option for anything else
/// (malformed, division by zero, more than 100000 characters).
Rational read_rational(const std::string& option, const std::string& text);
/// Reads --timeout SECONDS (default 600): a positive number up to 1e9.
/// \throws InvalidArgument otherwise.
double read_timeout(const Args& a);
/// The curve a command works on: its CURVE argument read with
/// read_parse_limits, or the Bezier curve of --control (and --weights) in the
/// power basis (every command reads its curve through here, so new ways of
/// giving one apply to all commands).
/// \throws ParseError, DomainError, BudgetExceeded as Curve::parse;
///         InvalidArgument for --weights without --control and as read_bezier.
Curve read_curve(const Args& a);
/// The Bezier curve of --control and --weights (at most --max-degree + 1
/// points). \throws ParseError, InvalidArgument as BezierCurve::parse;
/// InvalidArgument when --control is missing.
BezierCurve read_bezier(const Args& a);

/// Runs a command under a TimeBudget of --timeout seconds (so every command
/// of the table gets the time limit): argv[1] is the command name. The
/// worker count is --threads N, else a non-empty UNIPARAM_THREADS, both
/// integers from 1 to 64 (InvalidArgument naming the one at fault). With
/// `watchdog`, a backstop thread ends the process with exit code 4 and the
/// budget message if the command overruns its deadline by max(0.4 s, 8%)
/// inside a call that cannot notice the TimeBudget (the fuzz driver runs
/// without it).
/// \throws whatever the command throws; InvalidArgument for bad arguments.
int run_command(const Command& c, int argc, char** argv, bool watchdog = true);

// One pair per command, defined in cmd_<name>.cpp.
CommandSpec uniformity_spec();
int run_uniformity(int argc, char** argv);
CommandSpec radical_spec();
int run_radical(int argc, char** argv);
/// The JSON document `radical --json` prints for r (without "at").
Json radical_json(const Curve& c, const RadicalResult& r, long digits, Format fmt);
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
CommandSpec sample_spec();
int run_sample(int argc, char** argv);
CommandSpec plot_spec();
int run_plot(int argc, char** argv);
/// `uniparam batch COMMAND ...` (cmd_batch.cpp): argv[2] is COMMAND.
int run_batch(int argc, char** argv);
CommandSpec locate_spec();
int run_locate(int argc, char** argv);
/// Row k of K of the exactly uniform samples as a SamplePoint: s = k/(K-1),
/// the located t and point, and mu as the speed (cmd_sample.cpp).
SamplePoint exact_sample_row(long k, long K, const LocatedPoint& p, const Ball& mu);
/// A sample's deviation from the exactly uniform parameterization,
/// |G(t)/mu - s| (frac gives G/mu), as a ball; `worst` becomes the largest so
/// far (cmd_sample.cpp).
Ball row_deviation(ArcFraction& frac, const SamplePoint& p, long digits, Ball& worst);
/// --method, --pieces, --target (cmd_sample.cpp); `with_none` adds
/// --method none (the original curve).
std::vector<OptionSpec> method_options(bool with_none);
/// Checks a map's method name m ("radical", "c0", "c1", or "none" when
/// `with_none`) and that the options pieces, target and max-pieces (given or
/// not) come only with the method they belong to; `flag` prefixes the option
/// names in messages ("--" for the CLI; "" and underscores for Python).
/// \throws InvalidArgument for an unknown method or a misplaced option.
void check_method_name(const std::string& m, bool pieces, bool target, bool max_pieces, bool with_none,
                       const std::string& flag);
/// The name given by --method (default "radical"), checked by
/// check_method_name with the CLI's option names.
std::string read_method_name(const Args& a, bool with_none);
/// The reparameterization of c selected by --method, computed with `opt`.
Reparameterization read_method(const Args& a, const Curve& c, SpeedKind kind, const Options& opt, bool with_none);
/// Exit status after using r: 4, with a message on stderr, when r is a C1
/// map whose target uniformity was not reached (the best map was used:
/// target_missed_message with --max-pieces from a); 0 otherwise.
int target_status(const Reparameterization& r, const std::string& command, const Args& a, long digits);
/// "x", "y", "z" for n <= 3 components, else "x1", ..., "xn" (0-based i).
std::string coordinate_name(std::size_t i, std::size_t n);
/// True for --json or --format json.
bool wants_json(const Args& a);
/// The formula format of --format text|latex|maple|json (json -> Text: the
/// JSON output carries text formulas).
Format read_format(const Args& a);
/// Parses --format text|latex|maple.
Format parse_format(const std::string& s);

}  // namespace uniparam::cli
