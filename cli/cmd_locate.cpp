// cli/cmd_locate.cpp -- `uniparam locate CURVE (--length S | --fraction F |
// --angle A)`: the parameter t at a given arc length, turning angle or
// fraction of either, certified (reparam/locate.hpp).
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "composite.hpp"
#include "json_reports.hpp"
#include "report.hpp"
#include "uniparam/reparam/locate.hpp"

namespace uniparam::cli {

CommandSpec locate_spec() {
  std::vector<OptionSpec> opts = {
      {"length", "S", "arc length from t = 0 (parametric speed; exact rational, 0 <= S <= length of the curve)", ""},
      {"angle", "A", "turning angle from t = 0 in radians (angular speed; exact rational, 0 <= A <= mu)", ""},
      {"fraction", "F", "fraction of the whole length or turning angle (exact rational in [0, 1])", ""},
  };
  for (OptionSpec o : common_options()) {
    if (o.name == "speed") {
      o.help = "angular (turning angle) or parametric (arc length; also 'arclength'); default: parametric with "
               "--length, else angular";
      o.fallback = "";
    }
    opts.push_back(o);
  }
  return {"locate",
          "The parameter t at a given arc length or turning angle, certified.",
          "Finds the unique t in [0, 1] with int_0^t sigma = S, where sigma is the\n"
          "parametric speed |p'| (S an arc length, --length) or the angular speed\n"
          "(S a turning angle in radians, --angle), or S = F * mu with mu = int_0^1\n"
          "sigma (--fraction). Prints t and the point p(t) as certified balls, and mu.\n"
          "The zeros of sigma (cusps; inflections for the angular speed) are handled:\n"
          "t is unique because sigma >= 0 vanishes only at isolated points. A straight\n"
          "line has no turning angle: use --length there.\n"
          "\n"
          "examples:\n"
          "  uniparam locate \"(t, t^2)\" --length 1/2         # arc length 0.5 from p(0)\n"
          "  uniparam locate \"(t, t^2)\" --fraction 1/2 --speed arclength\n"
          "  uniparam locate \"(t, t^3)\" --angle 0.25         # tangent turned by 0.25 rad",
          {"CURVE"},
          opts};
}

Json locate_json(const Curve& c, SpeedKind kind, long digits, const std::string& option, const Rational& value,
                 const LocateResult& r) {
  return composite_locate_json(c.str(), kind, digits, option, value, r);
}

int run_locate(int argc, char** argv) {
  const CommandSpec spec = locate_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const int given = static_cast<int>(a.has("length")) + static_cast<int>(a.has("angle")) +
                    static_cast<int>(a.has("fraction"));
  if (given != 1) throw InvalidArgument("give exactly one of --length S, --angle A and --fraction F");
  const std::string option = a.has("length") ? "length" : a.has("angle") ? "angle" : "fraction";
  SpeedKind kind;
  if (a.has("speed")) kind = parse_speed_kind(a.get("speed", ""));
  else kind = option == "length" ? SpeedKind::Parametric : SpeedKind::Angular;
  if (option == "length" && kind == SpeedKind::Angular)
    throw InvalidArgument("--length is an arc length, measured by the parametric speed: drop --speed angular, "
                          "or give a turning angle with --angle");
  if (option == "angle" && kind == SpeedKind::Parametric)
    throw InvalidArgument("--angle is a turning angle, measured by the angular speed: drop --speed " +
                          a.get("speed", "") + ", or give an arc length with --length");
  const Rational value = read_rational(option, a.get(option, ""));
  if (auto cc = read_composite(a); cc && cc->size() > 1)
    return run_locate_composite(a, *cc, kind, opt, value,
                                option == "fraction" ? LocateTarget::Fraction : LocateTarget::Integral, option);
  const Curve c = read_curve(a);
  check_degree(c, opt);
  const Speed s(c, kind);
  const LocateTarget target = option == "fraction" ? LocateTarget::Fraction : LocateTarget::Integral;
  const LocateResult r = locate_for_option(option, c, s, value, target, opt);
  if (wants_json(a)) {
    answer() << locate_json(c, kind, opt.digits, option, value, r).dump(2) << "\n";
    return 0;
  }
  print_locate_text(c.str(), kind, kind == SpeedKind::Parametric ? "arc length" : "turning angle", value, target, r,
                    opt.digits);
  return 0;
}

}  // namespace uniparam::cli
