// cli/commands.cpp -- the table of subcommands and their shared options.
#include "commands.hpp"

namespace uniparam::cli {

std::vector<OptionSpec> common_options() {
  return {
      {"speed", "KIND", "speed to make uniform: angular or parametric", "angular"},
      {"digits", "D", "correct decimal digits: every ball has radius <= 10^-D * max(1, |mid|)", "15"},
      {"json", "", "print JSON: certified reals as {\"mid\", \"rad\"}", ""},
      {"max-prec", "BITS", "largest working precision before giving up", "16384"},
      {"max-degree", "N", "largest curve degree accepted", "2000"},
  };
}

Options read_options(const Args& a) {
  Options o;
  o.digits = a.get_long("digits", o.digits, 1, 10000);
  o.max_prec = a.get_long("max-prec", o.max_prec, 64, 1L << 24);
  o.max_degree = a.get_long("max-degree", o.max_degree, 1, 20000);  // the parser refuses degrees above 20000
  return o;
}

Curve read_curve(const Args& a) { return parse_curve(a.positional.at(0)); }

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {uniformity_spec(), &run_uniformity},
      {radical_spec(), &run_radical},
      {moebius_spec(), &run_moebius},
      {sample_spec(), &run_sample},
      {plot_spec(), &run_plot},
  };
  return table;
}

}  // namespace uniparam::cli
