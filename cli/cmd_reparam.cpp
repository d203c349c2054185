// cli/cmd_reparam.cpp -- `uniparam reparam CURVE --pieces N | --breakpoints
// LIST | --target U [--rational]`: ImUp's ReparameterizationN (C0, optimised
// breakpoints) and ReparameterizationU (C1, refined to a target uniformity).
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "composite.hpp"
#include "moebius_report.hpp"
#include "nurbs_out.hpp"

namespace uniparam::cli {

CommandSpec reparam_spec() {
  auto opts = common_options();
  opts.push_back({"pieces", "N", "C0 with N pieces, breakpoints optimised (ImUp's ReparameterizationN)", ""});
  opts.push_back({"breakpoints", "LIST", "C0 with fixed breakpoints, e.g. 0,1/3,2/3,1", ""});
  opts.push_back({"target", "U", "C1, refined until u >= U, 0 < U < 1 (ImUp's ReparameterizationU)", ""});
  opts.push_back({"max-pieces", "N", "with --target: the largest number of pieces tried", "64"});
  for (auto& o : moebius_output_options()) opts.push_back(o);
  return {"reparam",
          "Piecewise Moebius reparameterization: C0 with N pieces, or C1 to a target uniformity.",
          "Give exactly one of --pieces, --breakpoints, --target. --pieces chooses the\n"
          "breakpoints by a local optimiser of sum sqrt(M_i) (never worse than equal\n"
          "spacing; its stationarity is reported). --target builds the C1 map of\n"
          "ImUp's slides and refines it until u >= U is certified or --max-pieces is\n"
          "reached (then the best map is printed and the exit status is 4).\n"
          "--rational rounds the data to short rationals and certifies the exact map.\n"
          "Rational maps cannot lift zeros of the speed: see 'uniparam radical'.",
          {"CURVE"},
          opts};
}

int run_reparam(int argc, char** argv) {
  const CommandSpec spec = reparam_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const MoebiusPrint how = read_moebius_print(a);
  const int given = a.has("pieces") + a.has("breakpoints") + a.has("target");
  if (given != 1) throw InvalidArgument("give exactly one of --pieces N, --breakpoints LIST, --target U");
  if (a.has("max-pieces") && !a.has("target")) throw InvalidArgument("--max-pieces needs --target");
  long pieces = 0;
  Rational target;
  std::vector<RealAlgebraic> T;
  const long max_pieces = a.get_long("max-pieces", 64, 1, kMaxPiecesLimit);
  if (a.has("pieces")) pieces = a.get_long("pieces", 1, 1, 1000);
  if (a.has("breakpoints")) T = parse_breakpoints(a.get("breakpoints", ""));
  if (a.has("target")) {
    target = read_rational("target", a.get("target", ""));
    if (!(target.sign() > 0 && target < Rational(1)))
      throw InvalidArgument("--target must lie strictly between 0 and 1, got " + a.get("target", ""));
  }
  if (auto cc = read_composite(a); cc && cc->size() > 1) {
    CompositeMethod m;
    m.kind = pieces ? CompositeMethod::Kind::Pieces
             : !T.empty() ? CompositeMethod::Kind::Breakpoints
                          : CompositeMethod::Kind::Target;
    m.pieces = pieces;
    for (const RealAlgebraic& t : T) m.breakpoints.push_back(t.rational());
    m.target = target;
    m.max_pieces = max_pieces;
    return run_map_composite(a, *cc, kind, opt, with_rational(a, m), "reparam");
  }
  const NurbsOutput no = read_nurbs_output(a);
  const Curve c = read_curve(a);
  MoebiusResult r = pieces    ? reparam_c0(c, kind, pieces, opt)
                    : !T.empty() ? moebius_c0(c, kind, T, opt)
                                 : reparam_c1(c, kind, target, opt, max_pieces);
  r = finish_moebius(c, r, a, opt);
  if (!no.replaces_report()) print_moebius(c, r, opt.digits, how);
  write_moebius_nurbs(c, r, no, opt);
  if (r.target.has_value() && !r.target->reached) {
    warn() << "uniparam reparam: " << target_missed_message(r, max_pieces, opt.digits) << "\n";
    return 4;
  }
  return 0;
}

}  // namespace uniparam::cli
