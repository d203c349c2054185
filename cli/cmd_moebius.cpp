// cli/cmd_moebius.cpp -- `uniparam moebius CURVE`: the optimal single Moebius
// reparameterization (docs/math.md section 2), or C0 piecewise Moebius with the
// breakpoints given by --breakpoints.
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "composite.hpp"
#include "moebius_report.hpp"
#include "nurbs_out.hpp"

namespace uniparam::cli {

std::vector<OptionSpec> moebius_output_options() {
  return {
      {"format", "F", "formulas of the pieces: text, latex, maple (or json, the same as --json)", "text"},
      {"rational", "", "round alpha, S and T to short rationals and certify that exact map", ""},
      {"rational-digits", "D", "with --rational: round to the simplest rationals within 10^-D", "8"},
      nurbs_output_option(),
  };
}

MoebiusPrint read_moebius_print(const Args& a) {
  MoebiusPrint how;
  how.json = wants_json(a);
  how.format = read_format(a);
  return how;
}

MoebiusResult finish_moebius(const Curve& c, const MoebiusResult& r, const Args& a, const Options& opt) {
  const long rd = a.get_long("rational-digits", 8, 1, 100);
  if (a.has("rational-digits") && !a.flag("rational"))
    throw InvalidArgument("--rational-digits needs --rational");
  return a.flag("rational") ? make_rational(c, r, rd, opt) : r;
}

std::vector<RealAlgebraic> parse_breakpoints(const std::string& list) {
  std::vector<RealAlgebraic> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    std::size_t comma = list.find(',', start);
    std::string item = list.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    if (item.empty()) throw InvalidArgument("--breakpoints: empty entry in '" + list + "'");
    out.emplace_back(read_rational("breakpoints", item));
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

CommandSpec moebius_spec() {
  auto opts = common_options();
  opts.push_back({"breakpoints", "LIST", "C0 piecewise Moebius with fixed breakpoints, e.g. 0,1/3,2/3,1", "0,1"});
  for (auto& o : moebius_output_options()) opts.push_back(o);
  return {"moebius",
          "Optimal Moebius reparameterization: alpha* = 1/(1+sqrt(C/A)) and u after.",
          "With --breakpoints T the pieces are C0 Moebius maps with the optimal alpha\n"
          "and S for that T (docs/math.md (3.1)). Rational maps cannot lift zeros of the\n"
          "speed: for such curves see 'uniparam radical'.",
          {"CURVE"},
          opts};
}

int run_moebius(int argc, char** argv) {
  const CommandSpec spec = moebius_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const MoebiusPrint how = read_moebius_print(a);
  const std::vector<RealAlgebraic> T = parse_breakpoints(a.get("breakpoints", "0,1"));
  if (auto cc = read_composite(a); cc && cc->size() > 1) {
    CompositeMethod m;
    m.kind = a.has("breakpoints") ? CompositeMethod::Kind::Breakpoints : CompositeMethod::Kind::Moebius;
    for (const RealAlgebraic& t : T) m.breakpoints.push_back(t.rational());
    return run_map_composite(a, *cc, kind, opt, with_rational(a, m), "moebius");
  }
  const NurbsOutput no = read_nurbs_output(a);
  const Curve c = read_curve(a);
  const MoebiusResult r = finish_moebius(c, moebius_c0(c, kind, T, opt), a, opt);
  if (!no.replaces_report()) print_moebius(c, r, opt.digits, how);
  write_moebius_nurbs(c, r, no, opt);
  return 0;
}

}  // namespace uniparam::cli
