#include "nurbs_out.hpp"

#include <cstdio>
#include <iostream>
#include <sstream>

#include "output.hpp"
#include "report.hpp"
#include "svg.hpp"

namespace uniparam::cli {

OptionSpec nurbs_output_option() {
  return {"output", "FORM",
          "instead of the report: 'nurbs' (p o r as NURBS JSON) or 'step' (STEP AP214 on stdout); "
          "or FILE.stp / FILE.step to also write the STEP file",
          ""};
}

NurbsOutput read_nurbs_output(const Args& a) {
  if (!a.has("output")) return NurbsOutput{};
  const NurbsOutput o = parse_nurbs_output(a.get("output", ""));
  if (o.form == NurbsOutput::Form::Json && a.flag("json"))
    throw InvalidArgument("--output nurbs prints JSON already; drop --json");
  return o;
}

NurbsOutput parse_nurbs_output(const std::string& v) {
  NurbsOutput o;
  auto ends = [&](const std::string& suf) {
    return v.size() > suf.size() && v.compare(v.size() - suf.size(), suf.size(), suf) == 0;
  };
  if (v == "nurbs") {
    o.form = NurbsOutput::Form::Json;
  } else if (v == "step") {
    o.form = NurbsOutput::Form::Step;
  } else if (ends(".stp") || ends(".step") || ends(".STP") || ends(".STEP")) {
    o.form = NurbsOutput::Form::Step;
    o.file = v;
    try {
      svg::check_writable(v);
    } catch (const std::runtime_error& e) {
      throw InvalidArgument(std::string("--output: ") + e.what());
    }
  } else {
    throw InvalidArgument("--output expects nurbs, step, or a file name ending in .stp or .step, got '" + v + "'");
  }
  return o;
}

namespace {

const char* kind_name(Nurbs::Kind k) {
  switch (k) {
    case Nurbs::Kind::Exact: return "rational";
    case Nurbs::Kind::Surd: return "surd";
    default: return "balls";
  }
}

Json weight_json(const Nurbs& n, std::size_t i, long pd) {
  if (n.kind == Nurbs::Kind::Exact) return json_rational(n.weights_exact[i], pd);
  if (n.kind == Nurbs::Kind::Surd) {
    return json_surd(n.weights_surd[i], n.weights[i], pd);
  }
  return json_ball(n.weights[i], pd);
}

}  // namespace

Json nurbs_json(const Nurbs& n, long digits) {
  const long pd = printed_digits(digits);
  Json j = Json::object();
  j.set("type", Json::string("nurbs"));
  j.set("degree", Json::number(n.degree));
  j.set("dimension", Json::number(static_cast<long>(n.dimension)));
  j.set("kind", Json::string(kind_name(n.kind)));
  Json k = Json::array();
  for (std::size_t i = 0; i < n.knots.size(); ++i)
    k.push(n.knots_exact.empty() ? json_ball(n.knots[i], pd) : json_rational(n.knots_exact[i], pd));
  j.set("knots", k);
  Json pts = Json::array();
  for (std::size_t i = 0; i < n.points.size(); ++i) {
    Json p = Json::array();
    for (std::size_t c = 0; c < n.dimension; ++c)
      p.push(n.points_exact.empty() ? json_ball(n.points[i][c], pd) : json_rational(n.points_exact[i][c], pd));
    pts.push(p);
  }
  j.set("control_points", pts);
  Json w = Json::array();
  for (std::size_t i = 0; i < n.weights.size(); ++i) w.push(weight_json(n, i, pd));
  j.set("weights", w);
  j.set("segments", Json::number(static_cast<long>(n.segments)));
  j.set("subdivided_segments", Json::number(static_cast<long>(n.subdivided)));
  return j;
}

std::string nurbs_step(const Nurbs& n, const std::string& name) {
  if (n.dimension > 3)
    throw InvalidArgument("STEP carries curves in 2 or 3 dimensions; this curve has " + std::to_string(n.dimension) +
                          " (use --output nurbs)");
  return step_text(n, name);
}

long nurbs_prec(const Options& opt) { return digits_to_bits(opt.digits) + 32; }

void write_moebius_nurbs(const Curve& c, const MoebiusResult& r, const NurbsOutput& o, const Options& opt) {
  if (o.form == NurbsOutput::Form::None) return;
  write_nurbs(moebius_nurbs(c, r, nurbs_prec(opt)), o, opt.digits);
}

void write_nurbs(const Nurbs& n, const NurbsOutput& o, long digits) {
  if (o.form == NurbsOutput::Form::Json) {
    answer() << nurbs_json(n, digits).dump(2) << "\n";
  } else if (o.form == NurbsOutput::Form::Step) {
    std::string name = o.file.empty() ? std::string("uniparam.stp") : o.file;
    const std::size_t slash = name.find_last_of('/');
    if (slash != std::string::npos) name = name.substr(slash + 1);
    std::string clean;
    for (char c : name) clean += (c == '\'' || c == '\\' || static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) ? '_' : c;
    const std::string text = nurbs_step(n, clean);
    if (o.file.empty()) answer() << text;
    else svg::write_file(o.file, text);
  }
}

}  // namespace uniparam::cli
