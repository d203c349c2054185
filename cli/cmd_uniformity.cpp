// cli/cmd_uniformity.cpp -- `uniparam uniformity CURVE`.
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "composite.hpp"
#include "json_reports.hpp"
#include "report.hpp"

namespace uniparam::cli {

CommandSpec uniformity_spec() {
  return {"uniformity",
          "Certified mean speed mu = int_0^1 sigma and uniformity u = mu^2 / int_0^1 sigma^2.",
          "Prints the exact squared speed sigma^2 as a rational function, the zeros of\n"
          "sigma in [0, 1] with their multiplicities (exact algebraic numbers), and\n"
          "certified balls for mu, int sigma^2 and u. For the angular speed of a\n"
          "straight line mu = 0 and u = 1 exactly.",
          {"CURVE"},
          common_options()};
}

Json uniformity_json(const Curve& c, SpeedKind kind, long digits, const UniformityResult& r) {
  const long pd = printed_digits(digits);
  Json j = Json::object();
  j.set("curve", Json::string(c.str()));
  j.set("speed", Json::string(to_string(kind)));
  j.set("digits", Json::number(digits));
  j.set("speed_squared", json_ratfunc(r.speed_squared));
  j.set("zeros", json_zeros(r.zeros, digits));
  j.set("identically_zero", Json::boolean(r.identically_zero));
  j.set("mu", json_ball(r.mu, pd));
  j.set("mean_square", json_ball(r.mean_square, pd));
  j.set("u", json_ball(r.u, pd));
  return j;
}

int run_uniformity(int argc, char** argv) {
  const CommandSpec spec = uniformity_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  if (auto cc = read_composite(a); cc && cc->size() > 1) return run_uniformity_composite(a, *cc, kind, opt);
  const Curve c = read_curve(a);
  const UniformityResult r = uniformity(c, kind, opt);
  const long pd = printed_digits(opt.digits);
  const char* sq = kind == SpeedKind::Angular ? "omega^2" : "|p'|^2";

  if (a.flag("json")) {
    answer() << uniformity_json(c, kind, opt.digits, r).dump(2) << "\n";
    return 0;
  }
  answer() << "curve      " << c.str() << "\n"
            << "speed      " << to_string(kind) << "\n"
            << sq << std::string(11 - std::string(sq).size(), ' ') << format_ratfunc(r.speed_squared, Format::Text)
            << "\n";
  if (r.identically_zero) answer() << "zeros      the speed is identically zero (a straight line)\n";
  else if (r.zeros.empty()) answer() << "zeros      none in [0, 1]\n";
  else
    for (std::size_t i = 0; i < r.zeros.size(); ++i)
      answer() << (i ? "           " : "zeros      ") << "t = " << text_algebraic(r.zeros[i].t, opt.digits)
                << ", multiplicity " << r.zeros[i].multiplicity << "\n";
  answer() << "mu         " << format_ball(r.mu, pd, Format::Text) << "\n"
            << "int s^2    " << format_ball(r.mean_square, pd, Format::Text) << "\n"
            << "u          " << format_ball(r.u, pd, Format::Text) << "\n";
  return 0;
}

}  // namespace uniparam::cli
