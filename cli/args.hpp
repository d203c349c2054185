// cli/args.hpp -- command-line parsing for the uniparam command.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace uniparam::cli {

/// One option of a command: "--name VALUE" (or "--name=VALUE"), or a flag.
struct OptionSpec {
  std::string name;       ///< without the leading "--"
  std::string value;      ///< placeholder for the value ("D"), empty for a flag
  std::string help;
  std::string fallback;   ///< default shown in --help (empty: none)
};

struct CommandSpec {
  std::string name;
  std::string synopsis;   ///< one line
  std::string description;
  /// Names, all required; except that a first positional named "CURVE" is
  /// replaced by --control when the command has that option (exactly one of
  /// the two must be given).
  std::vector<std::string> positionals;
  std::vector<OptionSpec> options;
};

/// The result of parsing argv against a CommandSpec.
struct Args {
  std::string command;  ///< the command's name (CommandSpec::name)
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;  ///< options with values
  std::map<std::string, bool> flags;
  bool help = false;

  bool flag(const std::string& n) const { return flags.count(n) != 0; }
  bool has(const std::string& n) const { return values.count(n) != 0; }
  std::string get(const std::string& n, const std::string& dflt) const {
    auto it = values.find(n);
    return it == values.end() ? dflt : it->second;
  }
  /// Integer option in [lo, hi]; InvalidArgument naming the option otherwise.
  long get_long(const std::string& n, long dflt, long lo, long hi) const;
};

/// The integer `text` of the option or variable `name` ("--threads",
/// "UNIPARAM_THREADS"), read in full (no sign-only, trailing characters or
/// overflow). \pre lo <= hi.
/// \throws InvalidArgument naming `name` when `text` is not an integer in [lo, hi].
long parse_long(const std::string& name, const std::string& text, long lo, long hi);

/// True when the command's first positional CURVE may be given as --control instead.
bool curve_or_control(const CommandSpec& spec);

/// Parses argv[first..argc) for `spec` ("-o" means "--output" when spec
/// has that option); InvalidArgument for an unknown option,
/// a missing value or a wrong number of positional arguments (unless --help),
/// or both CURVE and --control given.
Args parse_args(const CommandSpec& spec, int argc, char** argv, int first);

/// Help text of one command.
std::string help_text(const CommandSpec& spec);

}  // namespace uniparam::cli
