// cli/cmd_plot.cpp -- `uniparam plot CURVE -o FILE.svg|FILE.png`: ImUp's
// three panels (ImUpPlotN / ImUpPlotU): p sampled at equal steps of t, p o r
// sampled at equal steps of s (over the curve's adaptively sampled trace),
// and the two speed functions, with axes, the breakpoints and the certified
// uniformities in the captions.
//
// The view of one or a composite curve is built here; plot_trace.cpp
// computes what is drawn, plot_render.cpp draws it.
#include <algorithm>
#include <functional>
#include <optional>
#include <cmath>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "commands.hpp"
#include "composite.hpp"
#include "output.hpp"
#include "json_reports.hpp"
#include "svg.hpp"
#include "uniparam/reparam/sample.hpp"
#include "plot_view.hpp"

namespace uniparam::cli {

CommandSpec plot_spec() {
  std::vector<OptionSpec> opts;
  for (const auto& o : common_options())
    if (o.name != "json" && o.name != "digits") opts.push_back(o);  // a picture has no digits to choose
  for (const auto& o : method_options(false)) opts.push_back(o);
  opts.push_back({"points", "K", "number of sample points in the two curve panels", "40"});
  opts.push_back({"projection", "P",
                  "for space curves: iso (isometric view of x, y, z) or I,J (coordinates I and J, from 1)",
                  "iso for 3 or more components"});
  opts.push_back({"output", "FILE", "the picture: FILE.svg, FILE.png (needs rsvg-convert) or - (SVG on stdout); "
                                    "also -o FILE", ""});
  return {"plot",
          "Plot p and p o r sampled at equal parameter steps, and their speeds (SVG or PNG).",
          "Three panels as ImUp's ImUpPlotN / ImUpPlotU: the curve p at K equal steps of t,\n"
          "the reparameterized curve p o r at K equal steps of s, and the speed of p (against t)\n"
          "and of p o r (against s). The breakpoints p(t_i) are marked, the joints s_i of r\n"
          "drawn in the speed panel, and the captions give the certified u before and after.\n"
          "The grey curve is p itself, sampled adaptively along it. Space curves are drawn\n"
          "in a projection, named in the picture. PNG output is rendered from the SVG by\n"
          "rsvg-convert (Debian package librsvg2-bin) at 2x size. The output file is checked\n"
          "before computing (exit 2 with the reason when it cannot be written).\n"
          "When --method c1 misses its target, the best map is drawn and the exit status is 4.",
          {"CURVE"},
          opts};
}

namespace plot {

/// The projection named by `given` ("iso" or "I,J"; empty: the default,
/// iso for 3 or more components) for a curve of n components.
Projection read_projection(const std::string& given, std::size_t n) {
  Projection p;
  const std::string v = given.empty() ? (n >= 3 ? "iso" : "1,2") : given;
  if (v == "iso") {
    if (n < 3) throw InvalidArgument("--projection iso needs a curve with at least 3 components");
    p.iso = true;
    p.xlabel = "X";
    p.ylabel = "Y";
    p.caption = "isometric projection of (" + coordinate_name(0, n) + ", " + coordinate_name(1, n) + ", " +
                coordinate_name(2, n) + "): X = (" + coordinate_name(0, n) + " \u2212 " + coordinate_name(1, n) +
                ")/\u221a2, Y = (2" + coordinate_name(2, n) + " \u2212 " + coordinate_name(0, n) + " \u2212 " +
                coordinate_name(1, n) + ")/\u221a6" + (n > 3 ? " (further coordinates ignored)" : "");
    return p;
  }
  const auto comma = v.find(',');
  auto index = [&](const std::string& s) -> std::size_t {
    char* end = nullptr;
    const long k = std::strtol(s.c_str(), &end, 10);
    if (s.empty() || *end || k < 1 || k > static_cast<long>(n))
      throw InvalidArgument("--projection expects iso or I,J with 1 <= I, J <= " + std::to_string(n) + ", got '" +
                            v + "'");
    return static_cast<std::size_t>(k - 1);
  };
  if (comma == std::string::npos)
    throw InvalidArgument("--projection expects iso or I,J (two coordinates), got '" + v + "'");
  p.i = index(v.substr(0, comma));
  p.j = index(v.substr(comma + 1));
  if (p.i == p.j) throw InvalidArgument("--projection: I and J must differ, got '" + v + "'");
  p.xlabel = coordinate_name(p.i, n);
  p.ylabel = coordinate_name(p.j, n);
  if (n > 2) p.caption = "projection onto (" + p.xlabel + ", " + p.ylabel + ")";
  return p;
}

}  // namespace plot

namespace {

using plot::PlotData;
using plot::PlotView;
using plot::Projection;
using plot::collect;
using plot::read_projection;
using plot::render;

// "2*t^4 - 16*t^3 + 9" -> "2t⁴ − 16t³ + 9" for the subtitle.
std::string pretty(const std::string& s) {
  static const char* sup[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                              "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string o;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '*') continue;
    if (c == '^') {
      while (i + 1 < s.size() && s[i + 1] >= '0' && s[i + 1] <= '9') o += sup[s[++i] - '0'];
      continue;
    }
    if (c == '-' && i > 0 && s[i - 1] == ' ') { o += "\u2212"; continue; }
    if (c == '-' && (i == 0 || s[i - 1] == '(')) { o += "\u2212"; continue; }
    o += c;
  }
  return o;
}

std::string method_title(const Reparameterization& r, const std::string& target) {
  const std::size_t N = r.pieces();
  const std::string pieces = std::to_string(N) + (N == 1 ? " piece" : " pieces");
  if (r.radical_result()) return "Optimal piecewise radical reparameterization r = \u03c6\u2218m (" + pieces + ")";
  const auto* m = r.moebius_result();
  if (m && m->continuity == Continuity::C1)
    return "C1 piecewise M\u00f6bius reparameterization (" + pieces + ", target \u016b = " + target +
           (m->target->reached ? " reached" : " NOT reached") + ")";
  return "Optimal C0 piecewise M\u00f6bius reparameterization (" + pieces + ")";
}

/// The view of one curve c (speed sp) reparameterized by r, with K samples;
/// `target` is the text of --target named in the title of a C1 map. The
/// view's evaluations refer to c, sp and r, which must outlive it.
PlotView single_view(const Curve& c, const Speed& sp, const Reparameterization& r, long K, const std::string& target,
                     const Options& opt) {
  PlotView v;
  v.text = "p(t) = " + pretty(c.str());
  v.title = method_title(r, target);
  v.method = r.method();
  v.mu = r.mu();
  v.u_before = r.u_before();
  v.u_after = r.u_after();
  const Reparameterization id = Reparameterization::identity(r.mu(), r.u_before());
  v.point = [&c](const Ball& t, long prec) { return c.eval(t, prec); };
  v.r = [&r](const Ball& s, long prec) { return r.eval_r(s, prec); };
  v.speed_after = [&r, &sp](const Ball& s, long prec) { return r.eval_speed(sp, s, prec); };
  v.speed_before = [&sp, id](const Ball& t, long prec) { return id.eval_speed(sp, t, prec); };
  for (std::size_t i = 0; i < r.joints_s().size(); ++i)
    v.joints.emplace_back(r.joints_s()[i], r.joints_t()[i].to_ball(64));
  // The dots need only drawing accuracy; they are certified to 6 digits anyway.
  v.samples = sample(c, sp, r, K, std::min<long>(6, opt.digits), opt.max_prec);
  return v;
}

}  // namespace

std::string plot_svg(const Curve& c, SpeedKind kind, const Reparameterization& r, long K,
                     const std::string& projection, const std::string& target, const Options& opt) {
  const Speed sp(c, kind);
  const PlotView v = single_view(c, sp, r, K, target, opt);
  const Projection proj = read_projection(projection, c.dimension());
  const PlotData d = collect(v, proj, opt.max_prec);
  return render(v, kind, d, proj, K);
}

std::string composite_plot_svg(const std::string& description, const CompositeCurve& cc, SpeedKind kind,
                               const CompositeMethod& m, long K, const std::string& projection, const Options& opt,
                               const std::function<void()>& missed) {
  PlotView v;
  const std::vector<Speed> csp = cc.speeds(kind);
  const CompositeMap cr = composite_map(cc, csp, m, opt);
  CompositeMethod none;
  const CompositeMap id = composite_map(cc, csp, none, opt);
  const std::size_t N = cr.pieces();
  v.text = description;
  v.title = (m.kind == CompositeMethod::Kind::Radical ? "Piecewise radical reparameterization per segment ("
             : m.kind == CompositeMethod::Kind::Target ? "C1 piecewise M\u00f6bius reparameterization per segment ("
                                                       : "Optimal C0 piecewise M\u00f6bius reparameterization (") +
            std::to_string(N) + (N == 1 ? " piece" : " pieces") + ")";
  v.method = cr.method();
  v.mu = cr.mu();
  v.u_before = cr.u_before();
  v.u_after = cr.u_after();
  v.point = [&](const Ball& t, long prec) { return cc.eval(t, prec); };
  v.r = [&](const Ball& s, long prec) { return cr.eval_r(cc, s, prec); };
  v.speed_after = [&](const Ball& s, long prec) { return cr.eval_speed(cc, csp, s, prec); };
  v.speed_before = [&](const Ball& t, long prec) { return id.eval_speed(cc, csp, t, prec); };
  v.joints = cr.joints(cc, 128);
  const long digits = std::min<long>(6, opt.digits);
  CompositeSampler before(cc, csp, id, digits, opt.max_prec), after(cc, csp, cr, digits, opt.max_prec);
  for (long k = 0; k < K; ++k) {
    check_time_budget();
    v.samples.before.push_back(before.at(Rational(k, K - 1)));
    v.samples.after.push_back(after.at(Rational(k, K - 1)));
  }
  if (m.kind == CompositeMethod::Kind::Target && !cr.target_reached() && missed) missed();
  const Projection proj = read_projection(projection, cc.dimension());
  const PlotData d = collect(v, proj, opt.max_prec);
  return render(v, kind, d, proj, K);
}

int run_plot(int argc, char** argv) {
  const CommandSpec spec = plot_spec();
  Args a = parse_args(spec, argc, argv, 2);  // "-o FILE" is read as "--output FILE"

  if (a.help) { answer() << help_text(spec); return 0; }
  if (!a.has("output")) throw InvalidArgument("plot needs -o FILE.svg or -o FILE.png (or -o - for SVG on stdout)");
  const std::string out = a.get("output", "");
  auto ends_with = [&](const char* e) {
    const std::size_t n = std::strlen(e);
    if (out.size() <= n) return false;
    std::string tail = out.substr(out.size() - n);
    for (auto& ch : tail) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return tail == e;
  };
  const bool png = ends_with(".png");
  if (out != "-" && !png && !ends_with(".svg"))
    throw InvalidArgument("-o: the file name must end in .svg or .png (or be - for SVG on stdout), got '" + out + "'");
  // The output is checked before any computing: a file that cannot be
  // written, or PNG without rsvg-convert, fails at once.
  if (out != "-") {
    try {
      svg::check_writable(out);
    } catch (const std::runtime_error& e) {
      throw InvalidArgument(e.what());
    }
    if (png) {
      try {
        svg::find_rsvg_convert();
      } catch (const std::runtime_error& e) {
        warn() << "uniparam plot: " << e.what() << "\n";
        return 1;
      }
    }
  }
  // 15 digits (no --digits): the drawing evaluates r next to its joints (1e-9
  // of a piece inside), so the joints must be known far better than that.
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const long K = a.get_long("points", 40, 2, 100000);
  int status = 0;
  // One curve, or a composite one (its own maps per segment).
  const std::optional<CompositeCurve> cc = read_composite(a);
  std::string text;
  if (cc && cc->size() > 1) {
    const CompositeMethod m = read_composite_method(a, *cc, false);
    text = composite_plot_svg(composite_description(a, *cc), *cc, kind, m, K, a.get("projection", ""), opt, [&] {
      warn() << "uniparam plot: the target u >= " << m.target.str()
             << " was not reached on every segment; the best map is drawn\n";
      status = 4;
    });
  } else {
    const Curve c = read_curve(a);
    const Reparameterization r = read_method(a, c, kind, opt, false);
    const Speed sp(c, kind);
    const PlotView v = single_view(c, sp, r, K, a.get("target", "0.99"), opt);
    status = target_status(r, "plot", a, opt.digits);
    const Projection proj = read_projection(a.get("projection", ""), c.dimension());
    const PlotData d = collect(v, proj, opt.max_prec);
    text = render(v, kind, d, proj, K);
  }
  if (out == "-") {
    answer() << text;
    return status;
  }
  try {
    if (png) {
      svg::write_png(text, out, 2);
    } else {
      svg::write_file(out, text);
    }
  } catch (const std::runtime_error& e) {
    if (dynamic_cast<const Error*>(&e)) throw;
    warn() << "uniparam plot: " << e.what() << "\n";
    return 1;
  }
  return status;
}

}  // namespace uniparam::cli
