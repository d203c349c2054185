#include "args.hpp"

#include <algorithm>

#include <cerrno>
#include <cstdlib>

#include "uniparam/core/error.hpp"

namespace uniparam::cli {

long parse_long(const std::string& name, const std::string& s, long lo, long hi) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno == ERANGE)
    throw InvalidArgument(name + " expects an integer, got '" + s + "'");
  if (v < lo || v > hi)
    throw InvalidArgument(name + " must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
                          s);
  return v;
}

long Args::get_long(const std::string& n, long dflt, long lo, long hi) const {
  auto it = values.find(n);
  if (it == values.end()) return dflt;
  return parse_long("--" + n, it->second, lo, hi);
}

bool curve_or_control(const CommandSpec& spec) {
  if (spec.positionals.empty() || spec.positionals.front() != "CURVE") return false;
  for (const auto& o : spec.options)
    if (o.name == "control") return true;
  return false;
}

Args parse_args(const CommandSpec& spec, int argc, char** argv, int first) {
  Args a;
  a.command = spec.name;
  for (int i = first; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") { a.help = true; continue; }
    // "-o FILE" is "--output FILE" for the commands that write a file.
    if (arg == "-o" && std::any_of(spec.options.begin(), spec.options.end(),
                                   [](const OptionSpec& o) { return o.name == "output"; }))
      arg = "--output";
    if (arg.size() > 2 && arg.compare(0, 2, "--") == 0) {
      std::string name = arg.substr(2), value;
      bool inline_value = false;
      if (auto eq = name.find('='); eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inline_value = true;
      }
      const OptionSpec* o = nullptr;
      for (const auto& cand : spec.options)
        if (cand.name == name) o = &cand;
      if (!o) throw InvalidArgument("unknown option '--" + name + "' for 'uniparam " + spec.name +
                                    "' (see 'uniparam " + spec.name + " --help')");
      if (o->value.empty()) {
        if (inline_value) throw InvalidArgument("option '--" + name + "' takes no value");
        a.flags[name] = true;
      } else {
        if (!inline_value) {
          if (i + 1 >= argc) throw InvalidArgument("option '--" + name + "' needs a value " + o->value);
          value = argv[++i];
        }
        a.values[name] = value;
      }
      continue;
    }
    a.positional.push_back(arg);
  }
  if (a.help) return a;
  // CURVE may be replaced by --control POINTS (a Bezier curve), --svg PATH or
  // --nurbs JSON: exactly one of them.
  std::size_t want = spec.positionals.size();
  if (curve_or_control(spec)) {
    std::vector<std::string> given;
    for (const char* o : {"control", "svg", "nurbs"})
      if (a.has(o)) given.push_back(std::string("--") + o);
    if (given.size() > 1)
      throw InvalidArgument("'uniparam " + spec.name + "': give one curve: " + given[0] + " and " + given[1] +
                            " were both given");
    if (!given.empty()) {
      if (a.positional.size() == want)
        throw InvalidArgument("'uniparam " + spec.name + "': give the curve either as CURVE or with " + given[0] +
                              ", not both");
      --want;
    }
  }
  if (a.positional.size() != want) {
    std::string names;
    for (const auto& p : spec.positionals) names += " " + p;
    if (curve_or_control(spec)) names = " CURVE (or --control, --svg, --nurbs)";
    throw InvalidArgument("'uniparam " + spec.name + "' expects" + (names.empty() ? " no arguments" : names) +
                          ", got " + std::to_string(a.positional.size()) + " argument(s) (quote the curve: \"(t, t^3)\")");
  }
  return a;
}

std::string help_text(const CommandSpec& spec) {
  std::string s = "usage: uniparam " + spec.name;
  for (std::size_t i = 0; i < spec.positionals.size(); ++i)
    s += (i == 0 && curve_or_control(spec)) ? " (CURVE | --control POINTS | --svg PATH | --nurbs JSON)"
                                            : " " + spec.positionals[i];
  s += " [options]\n\n" + spec.synopsis + "\n";
  if (!spec.description.empty()) s += "\n" + spec.description + "\n";
  s += "\noptions:\n";
  for (const auto& o : spec.options) {
    std::string left = "  --" + o.name + (o.value.empty() ? "" : " " + o.value);
    if (left.size() < 26) left += std::string(26 - left.size(), ' ');
    else left += "\n" + std::string(26, ' ');
    s += left + o.help;
    if (!o.fallback.empty()) s += " (default: " + o.fallback + ")";
    s += "\n";
  }
  s += "  --help, -h              show this help\n";
  return s;
}

}  // namespace uniparam::cli
