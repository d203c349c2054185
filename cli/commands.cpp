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
      {"control", "POINTS", "the curve as Bezier control points \"[[x0,y0],[x1,y1],...]\" (instead of CURVE)", ""},
      {"weights", "LIST", "weights \"[w0,w1,...]\" of a rational Bezier curve (with --control; positive)", ""},
  };
}

Options read_options(const Args& a) {
  Options o;
  o.digits = a.get_long("digits", o.digits, 1, 10000);
  o.max_prec = a.get_long("max-prec", o.max_prec, 64, 1L << 24);
  o.max_degree = a.get_long("max-degree", o.max_degree, 1, 20000);  // the parser refuses degrees above 20000
  return o;
}

BezierCurve read_bezier(const Args& a) {
  if (!a.has("control")) throw InvalidArgument("give the control points with --control \"[[x0,y0],[x1,y1],...]\"");
  const long max_degree = read_options(a).max_degree;
  BezierCurve b = BezierCurve::parse(a.get("control", ""), a.get("weights", ""),
                                     static_cast<std::size_t>(max_degree) + 1);
  if (a.has("weights") && !b.is_rational()) throw InvalidArgument("--weights: empty list");
  return b;
}

Curve read_curve(const Args& a) {
  if (a.has("control")) return read_bezier(a).to_curve();
  if (a.has("weights")) throw InvalidArgument("--weights needs --control (the weights of a rational Bezier curve)");
  return parse_curve(a.positional.at(0));
}

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {uniformity_spec(), &run_uniformity},
      {radical_spec(), &run_radical},
      {moebius_spec(), &run_moebius},
      {reparam_spec(), &run_reparam},
      {bezier_spec(), &run_bezier},
      {sample_spec(), &run_sample},
      {plot_spec(), &run_plot},
  };
  return table;
}

}  // namespace uniparam::cli
