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

// A STEP real: the ball's midpoint with 17 significant digits.
std::string step_real(const Ball& b) {
  const double x = arf_get_d(arb_midref(b.get()), ARF_RND_NEAR);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.16E", x);
  return buf;
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
  std::ostringstream o;
  o << "ISO-10303-21;\nHEADER;\n"
    << "FILE_DESCRIPTION(('uniparam: the reparameterized curve p o r as a rational B-spline; "
       "reals are the midpoints of certified values, rounded to double'),'2;1');\n"
    << "FILE_NAME('" << name << "','',(''),(''),'uniparam','uniparam','');\n"
    << "FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n"
    << "#1=APPLICATION_CONTEXT('automotive design');\n"
    << "#2=APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#1);\n"
    << "#3=PRODUCT_CONTEXT('',#1,'mechanical');\n"
    << "#4=PRODUCT('uniparam','uniparam','',(#3));\n"
    << "#5=PRODUCT_RELATED_PRODUCT_CATEGORY('part',$,(#4));\n"
    << "#6=PRODUCT_DEFINITION_FORMATION('','',#4);\n"
    << "#7=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');\n"
    << "#8=PRODUCT_DEFINITION('design','',#6,#7);\n"
    << "#9=PRODUCT_DEFINITION_SHAPE('','',#8);\n"
    << "#10=SHAPE_DEFINITION_REPRESENTATION(#9,#20);\n"
    << "#11=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));\n"
    << "#12=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));\n"
    << "#13=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());\n"
    << "#14=UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE(1.E-07),#11,'distance_accuracy_value','confusion accuracy');\n"
    << "#15=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#14))"
       "GLOBAL_UNIT_ASSIGNED_CONTEXT((#11,#12,#13))REPRESENTATION_CONTEXT('',''));\n"
    << "#20=GEOMETRICALLY_BOUNDED_WIREFRAME_SHAPE_REPRESENTATION('',(#21),#15);\n"
    << "#21=GEOMETRIC_CURVE_SET('',(#30));\n";
  // distinct knots and multiplicities
  std::vector<std::string> kv;
  std::vector<int> mult;
  const std::vector<Ball> br = n.breaks();
  const long d = n.degree;
  for (std::size_t i = 0; i < br.size(); ++i) {
    kv.push_back(step_real(br[i]));
    mult.push_back(i == 0 || i + 1 == br.size() ? static_cast<int>(d + 1) : static_cast<int>(d));
  }
  const std::size_t first_point = 100;
  o << "#30=(BOUNDED_CURVE()B_SPLINE_CURVE(" << d << ",(";
  for (std::size_t i = 0; i < n.points.size(); ++i) o << (i ? "," : "") << "#" << first_point + i;
  o << "),.UNSPECIFIED.,.F.,.F.)B_SPLINE_CURVE_WITH_KNOTS((";
  for (std::size_t i = 0; i < mult.size(); ++i) o << (i ? "," : "") << mult[i];
  o << "),(";
  for (std::size_t i = 0; i < kv.size(); ++i) o << (i ? "," : "") << kv[i];
  o << "),.UNSPECIFIED.)CURVE()GEOMETRIC_REPRESENTATION_ITEM()RATIONAL_B_SPLINE_CURVE((";
  for (std::size_t i = 0; i < n.weights.size(); ++i) o << (i ? "," : "") << step_real(n.weights[i]);
  o << "))REPRESENTATION_ITEM(''));\n";
  for (std::size_t i = 0; i < n.points.size(); ++i) {
    o << "#" << first_point + i << "=CARTESIAN_POINT('',(";
    for (std::size_t c = 0; c < 3; ++c)
      o << (c ? "," : "") << (c < n.dimension ? step_real(n.points[i][c]) : std::string("0.E+00"));
    o << "));\n";
  }
  o << "ENDSEC;\nEND-ISO-10303-21;\n";
  return o.str();
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
