// cli/cmd_radical.cpp -- `uniparam radical CURVE`: Hong, Wang, Yang 2023, Algorithm 1.
#include <iostream>
#include <optional>

#include "commands.hpp"
#include "output.hpp"
#include "composite.hpp"
#include "json_reports.hpp"
#include "report.hpp"
#include "uniparam/reparam/formula.hpp"
#include "uniparam/reparam/radical.hpp"
#include "uniparam/reparam/sample.hpp"

namespace uniparam::cli {

CommandSpec radical_spec() {
  auto opts = common_options();
  opts.push_back({"format", "F", "formulas of the pieces: text, latex, maple (or json, the same as --json)", "text"});
  opts.push_back({"output", "FORM", "not available: radical pieces are not rational (see --help)", ""});
  opts.push_back({"at", "Z", "also evaluate r(z), p(r(z)) and the new speed at a rational z in [0, 1]", ""});
  return {"radical",
          "Optimal piecewise radical reparameterization r = phi o m (Hong, Wang, Yang 2023, Algorithm 1).",
          "T holds 0, 1 and every zero of sigma * sigma' in (0, 1); phi lifts the zeros\n"
          "of the speed by radicals (optimal S), m is the optimal piecewise Moebius map\n"
          "on top (optimal alpha and Z). Prints T, S, Z, alpha, L, A, B, C, M, the pieces\n"
          "of phi, m, r and p o r, and u before, after phi and after phi o m.\n"
          "For a curve without zeros of the speed this is the C0 piecewise Moebius\n"
          "reparameterization with T from sigma' = 0.",
          {"CURVE"},
          opts};
}

bool wants_json(const Args& a) { return a.flag("json") || a.get("format", "") == "json"; }

Format read_format(const Args& a) {
  const std::string f = a.get("format", "text");
  return f == "json" ? Format::Text : parse_format(f);
}

Format parse_format(const std::string& s) {
  if (s == "text") return Format::Text;
  if (s == "latex") return Format::Latex;
  if (s == "maple") return Format::Maple;
  throw InvalidArgument("unknown format '" + s + "' (expected text, latex, maple or json)");
}

Json radical_at_json(const Rational& z, const SamplePoint& v, long digits) {
  const long pd = printed_digits(digits);
  Json e = Json::object();
  e.set("z", json_rational(z, pd));
  e.set("r", json_ball(v.t, pd));
  e.set("p_r", json_balls(v.point, pd));
  e.set("speed", json_ball(v.speed, pd));
  e.set("at_joint", Json::boolean(v.at_joint));
  return e;
}

Rational unit_at(const std::string& name, const Rational& z) {
  if (z < Rational(0) || z > Rational(1)) throw InvalidArgument(name + " must lie in [0, 1], got " + z.str());
  return z;
}

SamplePoint radical_at(const Curve& c, SpeedKind kind, const RadicalResult& r, const Rational& z, const Options& opt) {
  const Speed s(c, kind);
  Sampler ev(c, s, Reparameterization(r), opt.digits + 1, opt.max_prec);
  return ev.at(z);
}

Json radical_json(const Curve& c, const RadicalResult& r, long digits, Format fmt) {
  const long pd = printed_digits(digits);
  const auto formulas = radical_formulas(c, r, fmt, digits);
  const std::size_t N = r.pieces();
  Json j = Json::object();
  j.set("curve", Json::string(c.str()));
  j.set("speed", Json::string(to_string(r.kind)));
  j.set("digits", Json::number(digits));
  Json t = Json::array(), mult = Json::array();
  for (const auto& b : r.T) {
    t.push(json_algebraic(b.t, digits));
    mult.push(Json::number(static_cast<long>(b.multiplicity)));
  }
  j.set("t", t);
  j.set("multiplicity", mult);
  auto arr = [&](const std::vector<Ball>& v) { return json_balls(v, pd); };
  auto per_piece = [&](Ball PieceIntegrals::*m) {
    Json x = Json::array();
    for (const auto& p : r.integrals) x.push(json_ball(p.*m, pd));
    return x;
  };
  j.set("s", arr(r.S));
  j.set("z", arr(r.Z));
  j.set("alpha", per_piece(&PieceIntegrals::alpha));
  j.set("L", per_piece(&PieceIntegrals::L));
  j.set("A", arr(r.A));
  j.set("B", arr(r.B));
  j.set("C", arr(r.C));
  j.set("M", per_piece(&PieceIntegrals::M));
  j.set("mu", json_ball(r.mu, pd));
  j.set("u_before", json_ball(r.u_before, pd));
  j.set("u_radical", json_ball(r.u_radical, pd));
  j.set("u_after", json_ball(r.u_after, pd));
  Json pieces = Json::array();
  for (std::size_t i = 0; i < N; ++i) {
    Json p = Json::object();
    p.set("t_interval", Json::array().push(json_algebraic(r.T[i].t, digits)).push(
                            json_algebraic(r.T[i + 1].t, digits)));
    p.set("s_interval", Json::string(formulas[i].s_interval));
    p.set("z_interval", Json::string(formulas[i].z_interval));
    p.set("radical_index", Json::number(static_cast<long>(r.root_index(i))));
    if (!r.outer_k.empty()) p.set("outer_k", json_ball(r.outer_k[i], pd));
    p.set("phi", Json::string(formulas[i].phi));
    p.set("m", Json::string(formulas[i].m));
    p.set("r", Json::string(formulas[i].r));
    Json pr = Json::array();
    for (const auto& s : formulas[i].p_r) pr.push(Json::string(s));
    p.set("p_r", pr);
    pieces.push(p);
  }
  j.set("pieces", pieces);
  return j;
}

int run_radical(int argc, char** argv) {
  const CommandSpec spec = radical_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  if (a.has("output"))
    throw InvalidArgument("--output " + a.get("output", "") +
                          ": the radical pieces are not rational functions of s, so p o r is not a NURBS curve; "
                          "use 'uniparam sample --method exact' for certified points of it, or a rational method "
                          "(moebius, reparam, bezier) with --output nurbs or step");
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const Format fmt = read_format(a);
  if (auto cc = read_composite(a); cc && cc->size() > 1) {
    if (a.has("at")) throw InvalidArgument("--at on a composite curve: use 'uniparam sample' (its rows are r(s))");
    CompositeMethod m;
    m.kind = CompositeMethod::Kind::Radical;
    return run_map_composite(a, *cc, kind, opt, m, "radical");
  }
  const Curve c = read_curve(a);
  std::optional<Rational> at;
  if (a.has("at")) at = unit_at("--at", read_rational("at", a.get("at", "")));
  const RadicalResult r = radical(c, kind, opt);
  std::optional<SamplePoint> atv;
  if (at) atv = radical_at(c, kind, r, *at, opt);
  const long pd = printed_digits(opt.digits);
  if (wants_json(a)) {
    Json j = radical_json(c, r, opt.digits, fmt);
    if (atv) j.set("at", radical_at_json(*at, *atv, opt.digits));
    answer() << j.dump(2) << "\n";
    return 0;
  }

  const auto formulas = radical_formulas(c, r, fmt, opt.digits);
  const std::size_t N = r.pieces();
  answer() << "curve      " << c.str() << "\nspeed      " << to_string(kind) << "\n";
  if (r.identically_zero)
    answer() << "the angular speed is identically zero (a straight line): r = id, u = 1\n";
  auto list = [&](const char* name, const std::vector<Ball>& v) {
    answer() << name;
    for (std::size_t i = 0; i < v.size(); ++i) answer() << (i ? ", " : "(") << v[i].mid_decimal(pd);
    answer() << ")\n";
  };
  answer() << "T          (";
  for (std::size_t i = 0; i < r.T.size(); ++i) answer() << (i ? ", " : "") << text_algebraic(r.T[i].t, opt.digits);
  answer() << ")\nmult       (";
  for (std::size_t i = 0; i < r.T.size(); ++i) answer() << (i ? ", " : "") << r.T[i].multiplicity;
  answer() << ")\n";
  list("S          ", r.S);
  list("Z          ", r.Z);
  std::vector<Ball> alpha, L, M;
  for (const auto& p : r.integrals) { alpha.push_back(p.alpha); L.push_back(p.L); M.push_back(p.M); }
  list("alpha      ", alpha);
  list("L          ", L);
  list("A          ", r.A);
  list("B          ", r.B);
  list("C          ", r.C);
  list("M          ", M);
  for (std::size_t i = 0; i < N; ++i) {
    answer() << "piece " << i << "    z in " << formulas[i].z_interval << ", s in " << formulas[i].s_interval << "\n"
              << "  phi(s) = " << formulas[i].phi << "\n"
              << "  m(z)   = " << formulas[i].m << "\n"
              << "  r(z)   = " << formulas[i].r << "\n";
    for (std::size_t k = 0; k < formulas[i].p_r.size(); ++k)
      answer() << "  p_" << k + 1 << "(r(z)) = " << formulas[i].p_r[k] << "\n";
  }
  answer() << "mu         " << format_ball(r.mu, pd, Format::Text) << "\n"
            << "u(p)       " << format_ball(r.u_before, pd, Format::Text) << "\n"
            << "u(p o phi) " << format_ball(r.u_radical, pd, Format::Text) << "\n"
            << "u(p o r)   " << format_ball(r.u_after, pd, Format::Text) << "\n"
            ;
  if (atv) {
    answer() << "at z = " << at->str() << ": r(z) = " << format_ball(atv->t, pd, Format::Text) << "\n  p(r(z)) = (";
    for (std::size_t k = 0; k < atv->point.size(); ++k)
      answer() << (k ? ", " : "") << format_ball(atv->point[k], pd, Format::Text);
    answer() << ")\n  speed of p o r = " << format_ball(atv->speed, pd, Format::Text)
              << (atv->at_joint ? " (z is on a joint: the union of both one-sided speeds)" : "") << "\n";
  }
  answer() << "(every number is certified to " << opt.digits
            << " digits; the formulas print ball midpoints)\n";
  return 0;
}

}  // namespace uniparam::cli
