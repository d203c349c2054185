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
/// --max-prec, --max-degree.
std::vector<OptionSpec> common_options();
/// Reads --digits, --max-prec, --max-degree (validated ranges).
Options read_options(const Args& a);
/// The curve a command works on: its CURVE argument (every command reads its
/// curve through here, so new ways of giving one apply to all commands).
/// \throws ParseError, DomainError as Curve::parse.
Curve read_curve(const Args& a);

// One pair per command, defined in cmd_<name>.cpp.
CommandSpec uniformity_spec();
int run_uniformity(int argc, char** argv);
CommandSpec radical_spec();
int run_radical(int argc, char** argv);
CommandSpec moebius_spec();
int run_moebius(int argc, char** argv);
CommandSpec sample_spec();
int run_sample(int argc, char** argv);
CommandSpec plot_spec();
int run_plot(int argc, char** argv);
/// --method, --pieces, --target (cmd_sample.cpp); `with_none` adds
/// --method none (the original curve).
std::vector<OptionSpec> method_options(bool with_none);
/// The reparameterization of c selected by --method, computed with `opt`.
/// --method c1 throws InvalidArgument until the C1 method exists.
Reparameterization read_method(const Args& a, const Curve& c, SpeedKind kind, const Options& opt, bool with_none);
/// "x", "y", "z" for n <= 3 components, else "x1", ..., "xn" (0-based i).
std::string coordinate_name(std::size_t i, std::size_t n);
/// Parses --format text|latex|maple.
Format parse_format(const std::string& s);

}  // namespace uniparam::cli
