// python/src/module_support.cpp -- the Python module's readers of its
// arguments (with the CLI's checks and ranges), its NURBS and report
// answers, and the composite-curve commands (see module_support.hpp).
#include "module_support.hpp"

namespace uniparam::python_support {

long in_range(const char* name, long v, long lo, long hi) {
  if (v < lo || v > hi)
    throw InvalidArgument(std::string(name) + " must be an integer from " + std::to_string(lo) + " to " +
                          std::to_string(hi) + ", got " + std::to_string(v));
  return v;
}

/// The options of c, in the CLI's ranges (read_options).
Options options_of(const Common& c) {
  Options o;
  o.digits = in_range("digits", c.digits, 1, kMaxDigits);
  o.max_prec = c.max_prec == 0 ? default_max_prec(o.digits) : in_range("max_prec", c.max_prec, 64, 1L << 24);
  o.max_degree = in_range("max_degree", c.max_degree, 1, 20000);
  return o;
}

/// The curve of c: the Bezier curve of control (and weights), else the text
/// read with the CLI's parse limits (read_curve, read_parse_limits).
Curve curve_of(const Common& c) {
  const Options o = options_of(c);
  if (!c.control.empty()) {
    BezierCurve b = BezierCurve::parse(c.control, c.weights, static_cast<std::size_t>(o.max_degree) + 1);
    if (!c.weights.empty() && !b.is_rational()) throw InvalidArgument("weights: empty list");
    return b.to_curve();
  }
  if (!c.weights.empty()) throw InvalidArgument("weights need control points (a rational Bezier curve)");
  ParseLimits lim;
  lim.max_degree = o.max_degree;
  lim.max_exponent = lim.max_degree;
  lim.max_bits = in_range("max_bits", c.max_bits, 64, 1L << 40);
  lim.max_length = static_cast<std::size_t>(in_range("max_length", c.max_length, 1, 1L << 30));
  lim.max_depth = static_cast<int>(in_range("max_depth", c.max_depth, 1, 1L << 30));
  return Curve::parse(c.curve, lim);
}

/// How the composite readers' messages name the Python parameters.
cli::CompositeNames python_names() {
  cli::CompositeNames n;
  n.svg = "svg";
  n.subpath = "subpath=K";
  n.max_degree = "max_degree";
  n.subpaths_hint = "";
  return n;
}

/// The composite curve of c's svg or nurbs, or nullopt for a curve given as
/// text or control points (the CLI's read_composite, with the text given
/// directly; a NURBS text longer than max_length is refused as the CLI
/// refuses such a file).
std::optional<CompositeCurve> composite_of(const Common& c) {
  if (c.subpath && !c.svg) throw InvalidArgument("subpath needs an SVG path (Curve.svg)");
  if (!c.svg && !c.nurbs) return std::nullopt;
  const Options o = options_of(c);
  const std::size_t max_length = static_cast<std::size_t>(in_range("max_length", c.max_length, 1, 1L << 30));
  if (c.svg) {
    const std::vector<PathInput> paths = cli::read_svg_subpaths(*c.svg, max_length, python_names());
    std::optional<std::size_t> k;
    if (c.subpath) k = static_cast<std::size_t>(in_range("subpath", *c.subpath, 0, static_cast<long>(paths.size()) - 1));
    return cli::svg_composite(paths, k, o, python_names());
  }
  if (c.nurbs->size() > max_length)
    throw BudgetExceeded("nurbs: the text holds more than " + std::to_string(max_length) +
                         " characters (the limit for nurbs; raise it with max_length)");
  return cli::read_nurbs_composite(*c.nurbs, o, python_names());
}

Input input_of(const Common& c) {
  Input in;
  if (std::optional<CompositeCurve> cc = composite_of(c)) {
    if (cc->size() == 1) {
      in.curve = cc->segment(0);
      return in;
    }
    in.description =
        cli::composite_description(c.svg ? cli::CompositeSource::Svg : cli::CompositeSource::Nurbs, *cc);
    in.composite = std::move(cc);
    return in;
  }
  in.curve = curve_of(c);
  return in;
}

/// An exact rational given as text to parameter `name` (as the CLI's
/// read_rational, naming the Python parameter).
Rational rational_arg(const std::string& name, const std::string& text) {
  const auto e = text.find_first_of("eE");
  if (text.size() > 100000 || (e != std::string::npos && text.size() - e > 5))
    throw InvalidArgument(name + ": the number '" + text.substr(0, 20) + (text.size() > 20 ? "..." : "") +
                          "' is too large (at most 100000 characters and a decimal exponent below 1000)");
  try {
    return Rational::parse(text);
  } catch (const Error& ex) {
    throw InvalidArgument(name + ": '" + text.substr(0, 40) + (text.size() > 40 ? "..." : "") +
                          "' is not a rational number such as 1/3, 0.25 or 1e-3 (" + ex.what() + ")");
  }
}

std::string dump(const Json& j) { return j.dump(-1); }

/// The reparameterization `method` (radical, c0, c1, none) of cli's
/// read_method, with its checks.
Reparameterization method_of(const std::string& method, const Curve& cv, SpeedKind kind, const Options& opt,
                             std::optional<long> pieces, const std::optional<std::string>& target,
                             std::optional<long> max_pieces, bool with_none) {
  const std::string& m = method;
  cli::check_method_name(m, pieces.has_value(), target.has_value(), max_pieces.has_value(), with_none, "");
  if (m == "radical") return Reparameterization(radical(cv, kind, opt));
  if (m == "c0") return Reparameterization(reparam_c0(cv, kind, in_range("pieces", pieces.value_or(3), 1, 1000), opt));
  if (m == "c1") {
    const Rational t = rational_arg("target", target.value_or("0.99"));
    if (t <= Rational(0) || t >= Rational(1))
      throw InvalidArgument("target must lie strictly between 0 and 1, got " + t.str());
    return Reparameterization(reparam_c1(cv, kind, t, opt, in_range("max_pieces", max_pieces.value_or(64), 1, 1000)));
  }
  const UniformityResult u = uniformity(cv, kind, opt);
  return Reparameterization::identity(u.mu, u.u);
}

MoebiusResult finish(const Curve& cv, const MoebiusResult& r, bool rational, std::optional<long> rational_digits,
                     const Options& opt) {
  if (rational_digits && !rational) throw InvalidArgument("rational_digits needs rational=True");
  const long rd = in_range("rational_digits", rational_digits.value_or(8), 1, 100);
  return rational ? make_rational(cv, r, rd, opt) : r;
}

std::vector<RealAlgebraic> breakpoints_of(const std::vector<std::string>& list) {
  std::vector<RealAlgebraic> T;
  for (const auto& s : list) T.emplace_back(rational_arg("breakpoints", s));
  return T;
}

/// The output form `output` names ("" none; "nurbs", "step" or a .stp/.step
/// file, checked writable before computing: cli::parse_nurbs_output).
cli::NurbsOutput output_of(const std::string& output) {
  if (output.empty()) return cli::NurbsOutput{};
  try {
    return cli::parse_nurbs_output(output);
  } catch (const InvalidArgument& e) {
    const std::string m = e.what();
    throw InvalidArgument(m.rfind("--output", 0) == 0 ? "output" + m.substr(8) : m);
  }
}

cli::MoebiusPrint json_print(const std::string& format) {
  cli::MoebiusPrint how;
  how.json = true;
  how.format = cli::parse_format(format);
  return how;
}

/// The NURBS n as `o` asks, as the CLI's write_nurbs: the NURBS JSON or the
/// STEP text in place of `report`, or the STEP file written and `report`.
Answer nurbs_answer(const Nurbs& n, const cli::NurbsOutput& o, long digits, const std::function<Json()>& report,
                    const std::string& missed) {
  if (o.form == cli::NurbsOutput::Form::Json) return Answer("nurbs", dump(cli::nurbs_json(n, digits)), missed);
  if (o.form == cli::NurbsOutput::Form::Step && o.file.empty())
    return Answer("step", cli::nurbs_step(n, "uniparam.stp"), missed);
  Json doc = report();  // the report first, then the file (as the CLI)
  if (o.form == cli::NurbsOutput::Form::Step) {
    try {
      cli::write_nurbs(n, o, digits);
    } catch (const Error&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw InvalidArgument(e.what());
    }
  }
  return Answer("report", dump(doc), missed);
}

/// The C1 map's message when it missed its target ("" otherwise).
std::string missed(const MoebiusResult& r, long max_pieces, long digits) {
  if (!r.target.has_value() || r.target->reached) return "";
  return cli::target_missed_message(r, max_pieces, digits);
}

/// The map of `method` (radical, c0, c1, none) for a composite curve, as
/// the CLI's read_composite_method: pieces (c0; default max(3, segments)),
/// target (c1; default 0.99), max_pieces (c1, per segment).
CompositeMethod composite_method_of(const std::string& m, const CompositeCurve& cc, std::optional<long> pieces,
                                    const std::optional<std::string>& target, std::optional<long> max_pieces,
                                    bool with_none) {
  cli::check_method_name(m, pieces.has_value(), target.has_value(), max_pieces.has_value(), with_none, "");
  CompositeMethod cm;
  if (m == "radical") cm.kind = CompositeMethod::Kind::Radical;
  if (m == "c0") {
    cm.kind = CompositeMethod::Kind::Pieces;
    cm.pieces = in_range("pieces", pieces.value_or(std::max<long>(3, static_cast<long>(cc.size()))), 1, 1000);
  }
  if (m == "c1") {
    cm.kind = CompositeMethod::Kind::Target;
    cm.target = rational_arg("target", target.value_or("0.99"));
    if (cm.target <= Rational(0) || cm.target >= Rational(1))
      throw InvalidArgument("target must lie strictly between 0 and 1, got " + cm.target.str());
    cm.max_pieces = in_range("max_pieces", max_pieces.value_or(64), 1, 1000);
  }
  return cm;
}

/// `m` with rational (and rational_digits) as the CLI's with_rational.
CompositeMethod with_rational(CompositeMethod m, bool rational, std::optional<long> rational_digits) {
  if (rational_digits && !rational) throw InvalidArgument("rational_digits needs rational=True");
  m.rational = rational;
  m.rational_digits = in_range("rational_digits", rational_digits.value_or(8), 1, 100);
  return m;
}

/// radical, moebius and reparam on a composite curve (the CLI's
/// run_map_composite): the report, or the NURBS of p o r as `no` asks.
Answer composite_answer(const Input& in, SpeedKind kind, const Options& opt, const CompositeMethod& m, Format fmt,
                        const cli::NurbsOutput& no) {
  const CompositeCurve& cc = *in.composite;
  const std::vector<Speed> sp = cc.speeds(kind);
  const CompositeMap r = composite_map(cc, sp, m, opt);
  const bool missed = m.kind == CompositeMethod::Kind::Target && !r.target_reached();
  const std::string message = missed ? cli::composite_target_missed_message(m) : "";
  auto report = [&] {
    return cli::composite_map_json(in.description, cc, kind, opt.digits, m, r, joints(cc, 128), fmt);
  };
  if (no.form == cli::NurbsOutput::Form::None) return Answer("report", dump(report()), message);
  return nurbs_answer(composite_nurbs(cc, r, cli::nurbs_prec(opt)), no, opt.digits, report, message);
}

/// sample on a composite curve (the CLI's run_sample_composite): the
/// document and the missed-target message.
std::pair<std::string, std::string> sample_composite(const Input& in, SpeedKind kind, const Options& opt,
                                                     const std::string& method, std::optional<long> pieces,
                                                     const std::optional<std::string>& target,
                                                     std::optional<long> max_pieces, long K, bool deviation) {
  const CompositeCurve& cc = *in.composite;
  if (method == "exact" && (pieces || target || max_pieces))
    throw InvalidArgument("pieces, target and max_pieces do not apply to method exact");
  if (method == "exact" && deviation)
    throw InvalidArgument("deviation measures a map's rows against method exact's; it does not apply to "
                          "method exact itself");
  const std::vector<Speed> sp = cc.speeds(kind);
  Json rows = Json::array();
  if (method == "exact") {
    Json j = cli::composite_sample_header_json(in.description, cc, kind, "exact", nullptr, opt.digits, K);
    Ball mu;
    exact_samples_each(cc, sp, K, opt, mu, [&](long k, const LocatedPoint& p) {
      rows.push(cli::sample_row_json(cli::exact_sample_row(k, K, p, mu), opt.digits));
    });
    j.set("mu", json_ball(mu, cli::printed_digits(opt.digits)));
    j.set("samples", rows);
    return std::make_pair(dump(j), std::string());
  }
  const CompositeMethod cm = composite_method_of(method, cc, pieces, target, max_pieces, true);
  Options ropt = opt;
  ropt.digits = opt.digits + 3;
  const CompositeMap r = composite_map(cc, sp, cm, ropt);
  Json j = cli::composite_sample_header_json(in.description, cc, kind, method == "none" ? "none" : r.method(), &r,
                                             opt.digits, K);
  CompositeSampler smp(cc, sp, r, opt.digits, opt.max_prec);
  std::unique_ptr<ArcFraction> frac;
  if (deviation) frac = std::make_unique<ArcFraction>(cc, sp, digits_to_bits(opt.digits) + 8, opt);
  Ball worst(0);
  const long pd = cli::printed_digits(opt.digits);
  for (long k = 0; k < K; ++k) {
    check_time_budget();
    const SamplePoint p = smp.at(Rational(k, K - 1));
    Json row = cli::sample_row_json(p, opt.digits);
    if (deviation) row.set("deviation", json_ball(cli::row_deviation(*frac, p, opt.digits, worst), pd));
    rows.push(row);
  }
  j.set("samples", rows);
  if (deviation) j.set("max_deviation", json_ball(worst, pd));
  std::string message;
  if (cm.kind == CompositeMethod::Kind::Target && !r.target_reached())
    message = "the target u >= " + cm.target.str() + " was not reached on every segment; the best map was sampled";
  return std::make_pair(dump(j), message);
}

}  // namespace uniparam::python_support
