// cli/cmd_moebius.cpp -- `uniparam moebius CURVE`: the optimal single Moebius
// reparameterization (MATH.md section 2), or C0 piecewise Moebius with the
// breakpoints given by --breakpoints.
#include <iostream>

#include "commands.hpp"
#include "report.hpp"
#include "uniparam/reparam/moebius.hpp"

namespace uniparam::cli {

CommandSpec moebius_spec() {
  auto opts = common_options();
  opts.push_back({"breakpoints", "LIST", "C0 piecewise Moebius with fixed breakpoints, e.g. 0,1/3,2/3,1", "0,1"});
  return {"moebius",
          "Optimal Moebius reparameterization: alpha* = 1/(1+sqrt(C/A)) and u after.",
          "With --breakpoints T the pieces are C0 Moebius maps with the optimal alpha\n"
          "and S for that T (MATH.md 3.1). Rational maps cannot lift zeros of the\n"
          "speed: for such curves see 'uniparam radical'.",
          {"CURVE"},
          opts};
}

namespace {

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

}  // namespace

int run_moebius(int argc, char** argv) {
  const CommandSpec spec = moebius_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { std::cout << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const std::vector<RealAlgebraic> T = parse_breakpoints(a.get("breakpoints", "0,1"));
  const Curve c = read_curve(a);
  const MoebiusResult r = moebius_c0(c, kind, T, opt);
  const long pd = printed_digits(opt.digits);
  if (a.flag("json")) {
    Json j = Json::object();
    j.set("curve", Json::string(c.str()));
    j.set("speed", Json::string(to_string(kind)));
    j.set("digits", Json::number(opt.digits));
    Json t = Json::array(), s = Json::array(), al = Json::array();
    for (const auto& b : r.T) t.push(json_algebraic(b.t, opt.digits));
    for (const auto& b : r.S) s.push(json_ball(b, pd));
    for (const auto& p : r.integrals) al.push(json_ball(p.alpha, pd));
    j.set("t", t);
    j.set("s", s);
    j.set("alpha", al);
    j.set("mu", json_ball(r.mu, pd));
    j.set("u_before", json_ball(r.u_before, pd));
    j.set("u_after", json_ball(r.u_after, pd));
    j.set("continuity", Json::string("C0"));
    j.set("speed_vanishes", Json::boolean(r.speed_vanishes));
    std::cout << j.dump(2) << "\n";
    return 0;
  }
  std::cout << "curve      " << c.str() << "\nspeed      " << to_string(kind) << "\n";
  for (std::size_t i = 0; i < r.pieces(); ++i)
    std::cout << "piece " << i << "    t in [" << text_algebraic(r.T[i].t, opt.digits) << ", "
              << text_algebraic(r.T[i + 1].t, opt.digits) << "], s in [" << r.S[i].mid_decimal(pd) << ", "
              << r.S[i + 1].mid_decimal(pd) << "], alpha = " << format_ball(r.integrals[i].alpha, pd, Format::Text)
              << "\n";
  std::cout << "mu         " << format_ball(r.mu, pd, Format::Text) << "\n"
            << "u before   " << format_ball(r.u_before, pd, Format::Text) << "\n"
            << "u after    " << format_ball(r.u_after, pd, Format::Text) << "\n";
  if (r.speed_vanishes)
    std::cout << "note: the speed vanishes in [0, 1]; rational maps cannot lift its zeros "
                 "(see 'uniparam radical')\n";
  return 0;
}

}  // namespace uniparam::cli
