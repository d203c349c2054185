#include "composite.hpp"

#include <algorithm>
#include <iostream>

#include "commands.hpp"
#include "output.hpp"
#include "input.hpp"
#include "moebius_report.hpp"
#include "nurbs_out.hpp"
#include "report.hpp"

namespace uniparam::cli {

namespace {

CompositeCurve to_composite(const PathInput& p, const Options& opt, const CompositeNames& names) {
  std::vector<Curve> segs;
  segs.reserve(p.segments.size());
  for (std::size_t j = 0; j < p.segments.size(); ++j) {
    const std::string& label = j < p.labels.size() ? p.labels[j] : "segment " + std::to_string(j);
    if (p.segments[j].degree() > opt.max_degree)
      throw BudgetExceeded(label + ": degree " + std::to_string(p.segments[j].degree()) + " is above " +
                           names.max_degree + " " + std::to_string(opt.max_degree));
    try {
      segs.push_back(p.segments[j].to_curve());
    } catch (const DomainError& e) {
      throw DomainError(label + ": " + e.what());
    }
  }
  return CompositeCurve(std::move(segs), p.knots, p.labels);
}

// "segment 3" (1-based), with the segment's label where it says more.
std::string segment_name(const CompositeCurve& c, std::size_t i) {
  const std::string n = "segment " + std::to_string(i + 1);
  const std::string& l = c.label(i);
  if (l == n) return n;
  if (l.rfind(n + ": ", 0) == 0) return n + " (" + l.substr(n.size() + 2) + ")";
  return n + " (" + l + ")";
}

std::string line(const std::string& label) {
  return label + std::string(label.size() < 11 ? 11 - label.size() : 1, ' ');
}

// What the text report says of a joint.
std::string joint_text(const CompositeCurve& c, const Joint& j, long pd) {
  std::string s = "t = " + c.knots()[j.index].str() + ": ";
  if (!j.continuous) s += "a gap (the segments do not meet), ";
  if (j.smooth) return s + "smooth";
  return s + "corner, turning angle " + format_ball(j.angle, pd, Format::Text) + " rad";
}

}  // namespace

std::vector<PathInput> read_svg_subpaths(const std::string& text, std::size_t max_length,
                                         const CompositeNames& names) {
  SvgLimits lim;
  lim.max_length = max_length;
  std::vector<PathInput> paths = parse_svg_path(text, lim);
  if (paths.empty()) throw InvalidArgument(names.svg + ": the path has no segment");
  return paths;
}

CompositeCurve svg_composite(const std::vector<PathInput>& paths, std::optional<std::size_t> subpath,
                             const Options& opt, const CompositeNames& names) {
  if (!subpath && paths.size() > 1)
    throw InvalidArgument(names.svg + ": the path has " + std::to_string(paths.size()) + " subpaths; pick one with " +
                          names.subpath + " (0 to " + std::to_string(paths.size() - 1) + ")" + names.subpaths_hint);
  const std::size_t k = subpath.value_or(0);
  if (k >= paths.size())
    throw InvalidArgument(names.svg + ": no subpath " + std::to_string(k) + " (the path has " +
                          std::to_string(paths.size()) + ")");
  return to_composite(paths[k], opt, names);
}

CompositeCurve read_nurbs_composite(const std::string& text, const Options& opt, const CompositeNames& names) {
  NurbsLimits lim;
  lim.max_degree = opt.max_degree;
  return to_composite(parse_nurbs(text, lim), opt, names);
}

std::optional<CompositeCurve> read_composite(const Args& a) {
  const Options opt = read_options(a);
  if (a.has("subpath") && !a.has("svg")) throw InvalidArgument("--subpath needs --svg");
  if (a.has("svg")) {
    const std::size_t max_length = read_parse_limits(a).max_length;
    const std::string text = read_argument_text("--svg", a.get("svg", ""), max_length, "--max-length");
    const std::vector<PathInput> paths = read_svg_subpaths(text, max_length);
    std::optional<std::size_t> k;
    if (a.has("subpath"))
      k = static_cast<std::size_t>(a.get_long("subpath", 0, 0, static_cast<long>(paths.size()) - 1));
    return svg_composite(paths, k, opt);
  }
  if (a.has("nurbs")) {
    const std::string text =
        read_argument_text("--nurbs", a.get("nurbs", ""), read_parse_limits(a).max_length, "--max-length");
    return read_nurbs_composite(text, opt);
  }
  return std::nullopt;
}

std::string composite_description(CompositeSource source, const CompositeCurve& c) {
  const std::string n = std::to_string(c.size()) + (c.size() == 1 ? " segment" : " segments");
  if (source == CompositeSource::Svg) return "SVG path of " + n;
  if (source == CompositeSource::Nurbs) return "NURBS curve of " + n;
  return "composite curve of " + n;
}

std::string composite_description(const Args& a, const CompositeCurve& c) {
  return composite_description(a.has("svg")     ? CompositeSource::Svg
                               : a.has("nurbs") ? CompositeSource::Nurbs
                                                : CompositeSource::Other,
                               c);
}

Json json_joints(const CompositeCurve& c, const std::vector<Joint>& joints, long pd) {
  Json arr = Json::array();
  for (const Joint& j : joints) {
    Json o = Json::object();
    o.set("index", Json::number(static_cast<long>(j.index)));
    o.set("t", json_rational(c.knots()[j.index], pd));
    o.set("continuous", Json::boolean(j.continuous));
    o.set("smooth", Json::boolean(j.smooth));
    o.set("angle", json_ball(j.angle, pd));
    arr.push(o);
  }
  return arr;
}

Json composite_uniformity_json(const std::string& description, const CompositeCurve& c, SpeedKind kind, long digits,
                               const CompositeUniformity& r) {
  const long pd = printed_digits(digits);
  Json j = Json::object();
  j.set("curve", Json::string(description));
  j.set("speed", Json::string(to_string(kind)));
  j.set("digits", Json::number(digits));
  j.set("segments", Json::number(static_cast<long>(c.size())));
  Json knots = Json::array();
  for (const Rational& k : c.knots()) knots.push(json_rational(k, pd));
  j.set("knots", knots);
  j.set("identically_zero", Json::boolean(r.identically_zero));
  j.set("mu", json_ball(r.mu, pd));
  j.set("mean_square", json_ball(r.mean_square, pd));
  j.set("u", json_ball(r.u, pd));
  j.set("joints", json_joints(c, r.joints, pd));
  if (kind == SpeedKind::Angular) j.set("corner_turning", json_ball(r.corner_turning, pd));
  Json parts = Json::array();
  for (std::size_t i = 0; i < c.size(); ++i) {
    const UniformityResult& s = r.segments[i];
    Json p = Json::object();
    p.set("label", Json::string(c.label(i)));
    p.set("curve", Json::string(c.segment(i).str()));
    p.set("t_interval", Json::array().push(json_rational(c.knots()[i], pd)).push(json_rational(c.knots()[i + 1], pd)));
    p.set("zeros", json_zeros(s.zeros, digits));
    p.set("identically_zero", Json::boolean(s.identically_zero));
    p.set("mu", json_ball(s.mu, pd));
    p.set("mean_square", json_ball(s.mean_square, pd));
    p.set("u", json_ball(s.u, pd));
    parts.push(p);
  }
  j.set("parts", parts);
  return j;
}

int run_uniformity_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt) {
  const CompositeUniformity r = uniformity(c, kind, opt);
  const long pd = printed_digits(opt.digits);
  if (wants_json(a)) {
    answer() << composite_uniformity_json(composite_description(a, c), c, kind, opt.digits, r).dump(2) << "\n";
    return 0;
  }
  answer() << line("curve") << composite_description(a, c) << "\n" << line("speed") << to_string(kind) << "\n";
  for (std::size_t i = 0; i < c.size(); ++i) {
    const UniformityResult& s = r.segments[i];
    answer() << segment_name(c, i) << "\n" << line("") << "t in [" << c.knots()[i].str() << ", "
             << c.knots()[i + 1].str() << "]: mu " << s.mu.mid_decimal(8) << ", u " << s.u.mid_decimal(8)
             << (s.zeros.empty() ? "" : ", speed vanishes") << (s.identically_zero ? " (straight)" : "") << "\n";
  }
  for (const Joint& jt : r.joints)
    answer() << line("joint " + std::to_string(jt.index)) << joint_text(c, jt, 8) << "\n";
  answer() << line("mu") << format_ball(r.mu, pd, Format::Text) << "\n"
            << line("int s^2") << format_ball(r.mean_square, pd, Format::Text) << "\n"
            << line("u") << format_ball(r.u, pd, Format::Text) << "\n";
  if (kind == SpeedKind::Angular)
    answer() << line("corners") << format_ball(r.corner_turning, pd, Format::Text)
              << " rad of turning at the joints (not in mu: no angular speed carries a corner)\n";
  return 0;
}

CompositeMethod read_composite_method(const Args& a, const CompositeCurve& c, bool with_none) {
  const std::string m = read_method_name(a, with_none);
  CompositeMethod cm;
  if (m == "radical") cm.kind = CompositeMethod::Kind::Radical;
  if (m == "c0") {
    cm.kind = CompositeMethod::Kind::Pieces;
    cm.pieces = a.get_long("pieces", std::max<long>(3, static_cast<long>(c.size())), 1, 1000);
  }
  if (m == "c1") {
    cm.kind = CompositeMethod::Kind::Target;
    cm.target = read_rational("target", a.get("target", "0.99"));
    if (cm.target <= Rational(0) || cm.target >= Rational(1))
      throw InvalidArgument("--target must lie strictly between 0 and 1, got " + cm.target.str());
    cm.max_pieces = a.get_long("max-pieces", 64, 1, 1000);
  }
  return cm;
}

CompositeMethod with_rational(const Args& a, CompositeMethod m) {
  if (a.has("rational-digits") && !a.flag("rational")) throw InvalidArgument("--rational-digits needs --rational");
  m.rational = a.flag("rational");
  m.rational_digits = a.get_long("rational-digits", 8, 1, 100);
  return m;
}

std::string composite_target_missed_message(const CompositeMethod& m) {
  return "the target u >= " + m.target.str() + " was not reached on every segment with at most " +
         std::to_string(m.max_pieces) + " pieces each; the best map is printed (raise --max-pieces, or lower --target)";
}

Json composite_map_json(const std::string& description, const CompositeCurve& c, SpeedKind kind, long digits,
                        const CompositeMethod& m, const CompositeMap& r, const std::vector<Joint>& joints, Format fmt) {
  const long pd = printed_digits(digits);
  Json j = Json::object();
  j.set("curve", Json::string(description));
  j.set("speed", Json::string(to_string(kind)));
  j.set("digits", Json::number(digits));
  j.set("method", Json::string(r.method()));
  j.set("segments", Json::number(static_cast<long>(c.size())));
  j.set("pieces", Json::number(static_cast<long>(r.pieces())));
  Json knots = Json::array(), S = Json::array();
  for (const Rational& k : c.knots()) knots.push(json_rational(k, pd));
  for (const Rational& s : r.S()) S.push(json_rational(s, pd));
  j.set("knots", knots);
  j.set("S", S);
  j.set("mu", json_ball(r.mu(), pd));
  j.set("u_before", json_ball(r.u_before(), pd));
  j.set("u_after", json_ball(r.u_after(), pd));
  j.set("joints", json_joints(c, joints, pd));
  if (m.kind == CompositeMethod::Kind::Target) {
    Json t = Json::object();
    t.set("value", json_rational(m.target, pd));
    t.set("reached", Json::boolean(r.target_reached()));
    j.set("target", t);
  }
  Json parts = Json::array();
  MoebiusPrint how;
  how.format = fmt;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Reparameterization& part = r.parts()[i];
    Json p = Json::object();
    p.set("label", Json::string(c.label(i)));
    p.set("t_interval", Json::array().push(json_rational(c.knots()[i], pd)).push(json_rational(c.knots()[i + 1], pd)));
    p.set("s_interval", Json::array().push(json_rational(r.S()[i], pd)).push(json_rational(r.S()[i + 1], pd)));
    if (const MoebiusResult* mr = part.moebius_result()) p.set("map", moebius_json(c.segment(i), *mr, digits + 2, how));
    else if (const RadicalResult* rr = part.radical_result()) p.set("map", radical_json(c.segment(i), *rr, digits + 2, fmt));
    parts.push(p);
  }
  j.set("parts", parts);
  return j;
}

int run_map_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt,
                      const CompositeMethod& m, const std::string& command) {
  const NurbsOutput no = read_nurbs_output(a);
  const std::vector<Speed> sp = c.speeds(kind);
  const CompositeMap r = composite_map(c, sp, m, opt);
  if (no.form != NurbsOutput::Form::None) write_nurbs(composite_nurbs(c, r, nurbs_prec(opt)), no, opt.digits);
  if (no.replaces_report()) return m.kind == CompositeMethod::Kind::Target && !r.target_reached() ? 4 : 0;
  const std::vector<Joint> joints = uniparam::joints(c, 128);
  const long pd = printed_digits(opt.digits);
  const Format fmt = read_format(a);
  const bool missed = m.kind == CompositeMethod::Kind::Target && !r.target_reached();
  if (missed) warn() << "uniparam " << command << ": " << composite_target_missed_message(m) << "\n";
  if (wants_json(a)) {
    answer() << composite_map_json(composite_description(a, c), c, kind, opt.digits, m, r, joints, fmt).dump(2)
             << "\n";
    return missed ? 4 : 0;
  }
  answer() << line("curve") << composite_description(a, c) << "\n"
            << line("speed") << to_string(kind) << "\n"
            << line("method") << r.method() << ", " << r.pieces() << (r.pieces() == 1 ? " piece" : " pieces")
            << (m.rational ? " (exact rational maps)" : "") << "\n";
  for (std::size_t i = 0; i < c.size(); ++i) {
    const Reparameterization& part = r.parts()[i];
    answer() << segment_name(c, i) << "\n" << line("") << "t in [" << c.knots()[i].str() << ", "
             << c.knots()[i + 1].str() << "] <- s in [" << decimal_string(r.S()[i], 10) << ", "
             << decimal_string(r.S()[i + 1], 10) << "]: " << part.pieces()
             << (part.pieces() == 1 ? " piece" : " pieces") << ", u " << part.u_before().mid_decimal(8) << " -> "
             << part.u_after().mid_decimal(8) << "\n";
  }
  for (const Joint& jt : joints) answer() << line("joint " + std::to_string(jt.index)) << joint_text(c, jt, 8) << "\n";
  answer() << line("mu") << format_ball(r.mu(), pd, Format::Text) << "\n"
            << line("u before") << format_ball(r.u_before(), pd, Format::Text) << "\n"
            << line("u after") << format_ball(r.u_after(), pd, Format::Text) << "\n"
            << "(s in [S_j, S_j+1] runs segment j's own map at (s - S_j) / (S_j+1 - S_j); --json gives each "
               "segment's map with its breakpoints, parameters and formulas)\n";
  return missed ? 4 : 0;
}

Json composite_locate_json(const std::string& description, SpeedKind kind, long digits, const std::string& option,
                           const Rational& value, const LocateResult& r) {
  // Also the one-curve document (locate_json), with the curve's formula as its description.
  const long pd = printed_digits(digits);
  const char* measure = kind == SpeedKind::Parametric ? "length" : "angle";
  Json j = Json::object();
  j.set("curve", Json::string(description));
  j.set("speed", Json::string(to_string(kind)));
  j.set("digits", Json::number(digits));
  j.set("given", Json::string(option));
  j.set("value", Json::string(value.str()));
  j.set("mu", json_ball(r.mu, pd));
  j.set(measure, json_ball(r.target, pd));
  j.set("t", json_ball(r.at.t, pd));
  j.set("point", json_balls(r.at.point, pd));
  return j;
}

Json composite_sample_header_json(const std::string& description, const CompositeCurve& c, SpeedKind kind,
                                  const std::string& method, const CompositeMap* r, long digits, long K) {
  const long pd = printed_digits(digits);
  Json head = Json::object();
  head.set("curve", Json::string(description));
  head.set("speed", Json::string(to_string(kind)));
  head.set("method", Json::string(method));
  head.set("digits", Json::number(digits));
  head.set("points", Json::number(K));
  if (!r) return head;
  head.set("mu", json_ball(r->mu(), pd));
  head.set("u_before", json_ball(r->u_before(), pd));
  head.set("u_after", json_ball(r->u_after(), pd));
  Json S = Json::array(), knots = Json::array();
  for (const Rational& x : r->S()) S.push(json_rational(x, pd));
  for (const Rational& x : c.knots()) knots.push(json_rational(x, pd));
  Json joints = Json::object();
  joints.set("s", S);
  joints.set("t", knots);
  head.set("segment_joints", joints);
  return head;
}

int run_locate_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt,
                         const Rational& value, LocateTarget target, const std::string& option) {
  const std::vector<Speed> sp = c.speeds(kind);
  const LocateResult r = locate_for_option(option, c, sp, value, target, opt);
  if (wants_json(a)) {
    answer() << composite_locate_json(composite_description(a, c), kind, opt.digits, option, value, r).dump(2)
             << "\n";
    return 0;
  }
  print_locate_text(composite_description(a, c), kind,
                    kind == SpeedKind::Parametric ? "arc length" : "turning angle, corners not included", value,
                    target, r, opt.digits);
  return 0;
}

void print_locate_text(const std::string& description, SpeedKind kind, const std::string& whole, const Rational& value,
                       LocateTarget target, const LocateResult& r, long digits) {
  const long pd = printed_digits(digits);
  const char* measure = kind == SpeedKind::Parametric ? "length" : "angle";
  answer() << line("curve") << description << "\n"
            << line("speed") << to_string(kind) << "\n"
            << line("mu") << format_ball(r.mu, pd, Format::Text) << "  (the whole curve's " << whole << ")\n";
  if (target == LocateTarget::Fraction) answer() << line("fraction") << value.str() << "\n";
  answer() << line(measure) << format_ball(r.target, pd, Format::Text) << "\n"
            << line("t") << format_ball(r.at.t, pd, Format::Text) << "\n";
  for (std::size_t i = 0; i < r.at.point.size(); ++i)
    answer() << line(coordinate_name(i, r.at.point.size())) << format_ball(r.at.point[i], pd, Format::Text) << "\n";
}

}  // namespace uniparam::cli
