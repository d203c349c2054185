// cli/cmd_plot.cpp -- `uniparam plot CURVE -o FILE.svg|FILE.png`: ImUp's
// three panels (ImUpPlotN / ImUpPlotU): p sampled at equal steps of t, p o r
// sampled at equal steps of s (over the curve's adaptively sampled trace),
// and the two speed functions, with axes, the breakpoints and the certified
// uniformities in the captions.
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

namespace {

using svg::Anchor;
using svg::Point;
using svg::Style;

const char* kGreen = "#1a9641";
const char* kRed = "#d7191c";
const char* kTrace = "#b8b8b8";
const char* kMark = "#111111";

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

// The uniformity for a caption: enough digits to tell it from 1.
std::string u_text(const Ball& u) {
  if (u.certainly_zero()) return "0";
  const double x = mid_double(u);
  if (x == 1 && u.is_exact()) return "1";
  long digits = 4;
  if (x < 1 && 1 - x < 1e-3) digits = 3 + static_cast<long>(std::ceil(-std::log10(1 - x)));
  digits = std::min<long>(digits, 15);
  std::string t = u.mid_decimal(digits);
  // keep trailing zeros (0.7320, not 0.732) for u in [0.1, 1): `digits` decimals
  if (x >= 0.1 && x < 1 && t.compare(0, 2, "0.") == 0)
    while (static_cast<long>(t.size()) - 2 < digits) t += '0';
  return t;
}

struct Projection {
  bool iso = false;
  std::size_t i = 0, j = 1;
  std::string caption, xlabel, ylabel;
  Point operator()(const std::vector<double>& x) const {
    if (iso) return {(x[0] - x[1]) / std::sqrt(2.0), (2 * x[2] - x[0] - x[1]) / std::sqrt(6.0)};
    return {x[i], x[j]};
  }
};

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

std::vector<double> mids(const std::vector<Ball>& v) {
  std::vector<double> o;
  for (const auto& b : v) o.push_back(mid_double(b));
  return o;
}

// A data range padded by `pad` of its width (a point gets width 1).
struct Range {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  void add(double x) {
    if (!std::isfinite(x)) return;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  void pad(double f) {
    if (!(hi > lo)) { lo -= 0.5; hi += 0.5; return; }
    const double w = hi - lo;
    lo -= f * w;
    hi += f * w;
  }
};

// Extends the shorter of two ranges so that both have the same data-per-pixel
// scale in a w x h panel (equal aspect ratio: the curve is not distorted).
void equal_aspect(Range& x, Range& y, double w, double h) {
  const double sx = (x.hi - x.lo) / w, sy = (y.hi - y.lo) / h;
  if (sx > sy) {
    const double c = (y.lo + y.hi) / 2, half = sx * h / 2;
    y.lo = c - half;
    y.hi = c + half;
  } else {
    const double c = (x.lo + x.hi) / 2, half = sy * w / 2;
    x.lo = c - half;
    x.hi = c + half;
  }
}

// What the plot draws: a curve p and a map r, seen through evaluations (one
// curve, or a composite curve with its per-segment maps).
struct PlotView {
  std::string text;  // "p(t) = ..." or what the composite curve is
  std::function<std::vector<Ball>(const Ball& t, long prec)> point;  // p(t)
  std::function<Ball(const Ball& s, long prec)> r;                   // r(s)
  std::function<Ball(const Ball& t, long prec)> speed_before;        // sigma_p(t)
  std::function<Ball(const Ball& s, long prec)> speed_after;         // sigma_{p o r}(s)
  std::vector<std::pair<Ball, Ball>> joints;                         // (s_i, t_i), 0 and 1 included
  std::string method, title;
  Ball mu, u_before, u_after;
  Samples samples;
};

// ---- The trace: the curve itself, sampled in its own geometry ----------
//
// Equal steps of t can miss most of a curve (a circle with weights [1, 8e40,
// 1e82] runs its whole arc for t below 1e-39). The trace starts from seeds
// spread in t and in the curve's geometry (t_j = j/64 and r(j/64), r the
// uniformizing map), then bisects each piece [a, b] in t until the chord
// p(a)p(b) is at most kChordPx pixels long and p at a quarter, half and three
// quarters of the piece lies within kFlatPx pixels of it. Parameters are exact
// dyadic numbers (so pieces near t = 1 stay resolved), and each point is
// evaluated with the precision raised until its ball is below kEvalPx pixels.

constexpr double kPanelPx = 330;   // the curve panels' size
constexpr double kChordPx = 8;     // longest segment of the trace
constexpr double kFlatPx = 0.2;    // largest distance of a tested point from its segment
constexpr double kEvalPx = 0.02;   // accuracy of a trace point
constexpr int kMaxBisections = 1100;
constexpr long kMaxTraceEvaluations = 200000;

// The midpoint of an exact ball, as an exact ball clamped to [0, 1].
Ball exact_unit(const Ball& b) {
  Ball t;
  arf_set(arb_midref(t.get()), arb_midref(b.get()));
  if (arf_sgn(arb_midref(t.get())) < 0) arf_zero(arb_midref(t.get()));
  if (arf_cmp_si(arb_midref(t.get()), 1) > 0) arf_one(arb_midref(t.get()));
  return t;
}

Ball exact_middle(const Ball& a, const Ball& b) {
  Ball m;
  arb_add(m.get(), a.get(), b.get(), ARF_PREC_EXACT);
  arb_mul_2exp_si(m.get(), m.get(), -1);
  return m;
}

// p(t) projected, for an exact t, with balls below `tol` (data units; for
// tol <= 0 below 2^-40 of the point's size). False when no finite point
// came out within max_prec.
bool trace_point(const PlotView& pv, const Projection& proj, const Ball& t, double tol, long max_prec, Point& out) {
  const long bits = static_cast<long>(arf_bits(arb_midref(t.get())));
  for (long prec = bits + 64;; prec *= 2) {
    const std::vector<Ball> v = pv.point(t, prec);
    std::vector<double> m;
    double rad = 0, size = 0;
    bool finite = true;
    for (const auto& b : v) {
      finite = finite && b.is_finite();
      m.push_back(mid_double(b));
      rad = std::max(rad, mag_get_d(arb_radref(b.get())));
      size = std::max(size, std::fabs(m.back()));
    }
    out = proj(m);
    // a projection adds at most 1.7 x the largest radius (isometric Y)
    const bool good = finite && std::isfinite(out.first) && std::isfinite(out.second) &&
                      1.7 * rad <= (tol > 0 ? tol : std::ldexp(size, -40));
    if (good) return true;
    if (prec >= std::max(max_prec, bits + 64)) return finite && std::isfinite(out.first) && std::isfinite(out.second);
  }
}

double segment_distance(Point p, Point a, Point b) {
  const double dx = b.first - a.first, dy = b.second - a.second;
  const double l2 = dx * dx + dy * dy;
  double u = l2 > 0 ? ((p.first - a.first) * dx + (p.second - a.second) * dy) / l2 : 0;
  u = std::min(1.0, std::max(0.0, u));
  return std::hypot(p.first - a.first - u * dx, p.second - a.second - u * dy);
}

/// The trace of c (projected) for the curve panels: a polyline from p(0) to
/// p(1) whose segments are at most kChordPx pixels long and within about
/// kFlatPx pixels of the curve at the scale of the panels (see above).
/// \pre r was computed for c. Checks the time budget (BudgetExceeded).
std::vector<Point> trace_curve(const PlotView& c, const Projection& proj, long max_prec) {
  // Seeds: equal steps of t and of s (through r), sorted, without repeats.
  std::vector<Ball> seeds;
  const int n = 64;
  for (int j = 0; j <= n; ++j) seeds.push_back(Ball(Rational(j, n), 64));  // dyadic: exact
  for (int j = 1; j < n; ++j) {
    check_time_budget();
    try {
      const Ball t = c.r(Ball(Rational(j, n), 128), 128);
      if (arf_is_finite(arb_midref(t.get()))) seeds.push_back(exact_unit(t));
    } catch (const BudgetExceeded&) {
      throw;
    } catch (const Error&) {
      // a seed is only a starting point: the equal steps of t remain
    }
  }
  std::sort(seeds.begin(), seeds.end(),
            [](const Ball& a, const Ball& b) { return arf_cmp(arb_midref(a.get()), arb_midref(b.get())) < 0; });
  seeds.erase(std::unique(seeds.begin(), seeds.end(),
                          [](const Ball& a, const Ball& b) { return arf_equal(arb_midref(a.get()), arb_midref(b.get())); }),
              seeds.end());
  std::vector<Ball> ts;
  std::vector<Point> ps;
  Range xr, yr;
  for (const auto& t : seeds) {
    Point p;
    if (!trace_point(c, proj, t, 0, max_prec, p)) continue;
    ts.push_back(t);
    ps.push_back(p);
    xr.add(p.first);
    yr.add(p.second);
  }
  if (ps.size() < 2) return ps;
  double extent = std::max(xr.hi - xr.lo, yr.hi - yr.lo);
  if (!(extent > 0)) extent = std::max({1.0, std::fabs(xr.lo), std::fabs(yr.lo)});
  const double px = extent * 1.12 / kPanelPx;  // data per pixel (the panels pad by 6% a side)
  const double chord = kChordPx * px, flat = kFlatPx * px, tol = kEvalPx * px;

  struct Piece {
    Ball ta, tb;
    Point pa, pb;
    int depth = 0;
    bool has_mid = false;
    Ball tm;
    Point pm;
  };
  std::vector<Point> out = {ps.front()};
  long evaluations = 0;
  std::vector<Piece> stack;
  for (std::size_t i = ps.size() - 1; i > 0; --i) stack.push_back({ts[i - 1], ts[i], ps[i - 1], ps[i], 0, false, {}, {}});
  while (!stack.empty()) {
    Piece q = std::move(stack.back());
    stack.pop_back();
    check_time_budget();
    if (q.depth >= kMaxBisections || evaluations >= kMaxTraceEvaluations) {
      out.push_back(q.pb);
      continue;
    }
    if (!q.has_mid) {
      q.tm = exact_middle(q.ta, q.tb);
      ++evaluations;
      if (!trace_point(c, proj, q.tm, tol, max_prec, q.pm)) { out.push_back(q.pb); continue; }
    }
    const Ball t1 = exact_middle(q.ta, q.tm), t3 = exact_middle(q.tm, q.tb);
    Point p1, p3;
    evaluations += 2;
    if (!trace_point(c, proj, t1, tol, max_prec, p1) || !trace_point(c, proj, t3, tol, max_prec, p3)) {
      out.push_back(q.pb);
      continue;
    }
    const bool done = std::hypot(q.pb.first - q.pa.first, q.pb.second - q.pa.second) <= chord &&
                      segment_distance(p1, q.pa, q.pb) <= flat && segment_distance(q.pm, q.pa, q.pb) <= flat &&
                      segment_distance(p3, q.pa, q.pb) <= flat;
    if (done) {
      out.push_back(q.pb);
      continue;
    }
    stack.push_back({q.tm, q.tb, q.pm, q.pb, q.depth + 1, true, t3, p3});
    stack.push_back({q.ta, q.tm, q.pa, q.pm, q.depth + 1, true, t1, p1});
  }
  return out;
}

struct PlotData {
  std::vector<Point> trace;                 // the curve (projected), trace_curve
  std::vector<Point> before, after;         // the K samples (projected)
  std::vector<Point> breakpoints;           // p(t_i), interior i
  std::vector<Point> speed_before;          // (t, sigma_p(t)), dense
  std::vector<std::vector<Point>> speed_after;  // per piece (s, sigma_{p o r}(s)), dense
  std::vector<Point> breakpoint_speeds;     // (t_i, sigma_p(t_i)), interior i
  std::vector<double> joints_s;             // interior s_i
};

PlotData collect(const PlotView& v, const Projection& proj, long max_prec) {
  const long prec = 64;
  PlotData d;
  d.trace = trace_curve(v, proj, max_prec);
  const int dense = 800;
  for (int j = 0; j <= dense; ++j) {
    const Ball t(Rational(j, dense), prec);
    d.speed_before.push_back({static_cast<double>(j) / dense, mid_double(v.speed_before(t, prec))});
  }
  for (const auto& p : v.samples.before) d.before.push_back(proj(mids(p.point)));
  for (const auto& p : v.samples.after) d.after.push_back(proj(mids(p.point)));
  const std::size_t N = v.joints.size() - 1;
  for (std::size_t i = 1; i < N; ++i) {
    const Ball& t = v.joints[i].second;
    d.breakpoints.push_back(proj(mids(v.point(t, prec))));
    d.breakpoint_speeds.push_back({mid_double(t), mid_double(v.speed_before(t, prec))});
    d.joints_s.push_back(mid_double(v.joints[i].first));
  }
  // p o r's speed piece by piece, so that jumps at C0 joints show; interior
  // piece ends are moved inside by 1e-9 of the piece so that only one piece
  // is evaluated there.
  const int per_piece = std::max(24, 800 / static_cast<int>(N));
  for (std::size_t i = 0; i < N; ++i) {
    const double a = mid_double(v.joints[i].first), b = mid_double(v.joints[i + 1].first);
    const double ia = i == 0 ? 0 : 1e-9 * (b - a), ib = i + 1 == N ? 0 : 1e-9 * (b - a);
    std::vector<Point> piece;
    for (int j = 0; j <= per_piece; ++j) {
      double s = a + ia + (b - ib - a - ia) * j / per_piece;
      s = std::min(1.0, std::max(0.0, s));
      Ball sb;
      arb_set_d(sb.get(), s);  // s is the exact double; only a drawing position
      piece.push_back({s, mid_double(v.speed_after(sb, prec))});
    }
    d.speed_after.push_back(std::move(piece));
  }
  return d;
}

std::string method_title(const Reparameterization& r, const std::string& target) {
  const std::size_t N = r.pieces();
  const std::string pieces = std::to_string(N) + (N == 1 ? " piece" : " pieces");
  if (r.radical_result()) return "Optimal piecewise radical reparameterization r = \u03c6\u2218m (" + pieces + ")";
  const auto* m = r.moebius_result();
  if (m && m->continuity == Continuity::C1)
    return "C1 piecewise M\u00f6bius reparameterization (" + pieces + ", target \u016b = " + target +
           (m->target.reached ? " reached" : " NOT reached") + ")";
  return "Optimal C0 piecewise M\u00f6bius reparameterization (" + pieces + ")";
}

std::string render(const PlotView& r, SpeedKind kind, const PlotData& d, const Projection& proj, long K) {
  const double col = 430, plot = 330, left0 = 78;
  const double W = 3 * col + 20;
  // Title, subtitle (the curve) and projection, wrapped to the page: the
  // curve panels start below them.
  const double text_w = W - 40;
  const auto title = svg::wrap_text(
      r.title + ", " + (kind == SpeedKind::Angular ? "angular" : "parametric") + " speed", 18, text_w, true, 2);
  const auto subtitle = svg::wrap_text(r.text, 13, text_w, false, 4);
  const auto projection =
      proj.caption.empty() ? std::vector<std::string>{} : svg::wrap_text("drawn in the " + proj.caption, 12, text_w, false, 2);
  double y = 30;
  std::vector<std::pair<double, std::string>> title_at, subtitle_at, projection_at;
  for (std::size_t i = 0; i < title.size(); ++i) title_at.push_back({y += i ? 22 : 0, title[i]});
  y += 24;
  for (std::size_t i = 0; i < subtitle.size(); ++i) subtitle_at.push_back({y += i ? 17 : 0, subtitle[i]});
  if (!projection.empty()) y += 20;
  for (std::size_t i = 0; i < projection.size(); ++i) projection_at.push_back({y += i ? 15 : 0, projection[i]});
  const double top = y + (projection.empty() ? 30 : 28);
  const double H = top + plot + 168;
  svg::Document doc(W, H);
  doc.comment("uniparam plot: " + r.text + "; speed " + to_string(kind) + "; method " + r.method + "; " +
              std::to_string(r.joints.size() - 1) + " pieces; u before " + r.u_before.mid_decimal(10) +
              ", u after " + r.u_after.mid_decimal(10));
  doc.begin_group("title");
  for (const auto& [yy, line] : title_at) doc.text({W / 2, yy}, line, 18, Anchor::Middle, "#111", true);
  for (const auto& [yy, line] : subtitle_at) doc.text({W / 2, yy}, line, 13, Anchor::Middle, "#333");
  for (const auto& [yy, line] : projection_at) doc.text({W / 2, yy}, line, 12, Anchor::Middle, "#555");
  doc.end_group();

  const bool angular = kind == SpeedKind::Angular;
  // legend names of the two speeds: omega_p(t), omega_{p o r}(s) or |p'(t)|, |(p o r)'(s)|
  const std::string speed_before = angular ? "\u03c9_{p}(t)" : "|p\u2032(t)|";
  const std::string speed_after = angular ? "\u03c9_{p\u2218r}(s)" : "|(p\u2218r)\u2032(s)|";
  const std::string Ks = std::to_string(K);

  // Curve panels: same range and scale in both.
  Range xr, yr;
  for (const auto& p : d.trace) { xr.add(p.first); yr.add(p.second); }
  for (const auto& p : d.before) { xr.add(p.first); yr.add(p.second); }
  for (const auto& p : d.after) { xr.add(p.first); yr.add(p.second); }
  xr.pad(0.06);
  yr.pad(0.06);
  equal_aspect(xr, yr, plot, plot);
  const svg::Ticks xt = svg::nice_ticks(xr.lo, xr.hi, 5), yt = svg::nice_ticks(yr.lo, yr.hi, 5);

  auto caption = [&](double x, double y, const std::string& head, const std::vector<std::pair<int, std::string>>& items,
                     const std::string& color) {
    doc.begin_group("caption");
    doc.text({x, y}, head, 14, Anchor::Start, "#111", true);
    double yy = y + 20;
    for (const auto& [kindm, label] : items) {
      const Point m{x + 7, yy - 4};
      if (kindm == 0) doc.circle(m, 3.5, Style{"#ffffff", color, 0.7, "", 1});
      if (kindm == 1) doc.diamond(m, 6, Style{kMark, "none", 1.6, "", 1});
      if (kindm == 2) doc.line({x, yy - 4}, {x + 16, yy - 4}, Style{color, "none", 2.2, "", 1});
      if (kindm == 3) doc.line({x, yy - 4}, {x + 16, yy - 4}, Style{"#666", "none", 1.4, "6 4", 1});
      if (kindm == 4) doc.line({x + 7, yy - 11}, {x + 7, yy + 3}, Style{color, "none", 1.2, "3 3", 1});
      doc.text({x + 22, yy}, label, 12.5, Anchor::Start, "#222");
      yy += 18;
    }
    doc.end_group();
  };

  const bool has_bp = !d.breakpoints.empty();
  for (int k = 0; k < 2; ++k) {
    const double left = k * col + left0;
    const svg::Panel P{left, top, plot, plot, xr.lo, xr.hi, yr.lo, yr.hi};
    doc.begin_group(k == 0 ? "panel before" : "panel after");
    svg::draw_axes(doc, P, xt, yt, proj.xlabel.empty() ? "x" : proj.xlabel, proj.ylabel.empty() ? "y" : proj.ylabel);
    doc.begin_clip(P.left, P.top, P.width, P.height);
    std::vector<Point> tr;
    for (const auto& p : d.trace) tr.push_back(P.map(p));
    doc.polyline(tr, Style{kTrace, "none", 1.3, "", 1});
    doc.begin_group(k == 0 ? "samples before" : "samples after");
    const char* color = k == 0 ? kGreen : kRed;
    // dots shrink with many points so that neighbours stay apart (3.5 px up to 40 points)
    const double dot = std::max(1.2, std::min(3.5, 3.5 * std::sqrt(40.0 / static_cast<double>(K))));
    for (const auto& p : k == 0 ? d.before : d.after)
      doc.circle(P.map(p), dot, Style{"#ffffff", color, dot < 2 ? 0.3 : 0.7, "", 1});
    doc.end_group();
    doc.begin_group("breakpoints");
    for (const auto& p : d.breakpoints) doc.diamond(P.map(p), 6, Style{kMark, "none", 1.6, "", 1});
    doc.end_group();
    doc.end_clip();
    std::vector<std::pair<int, std::string>> items;
    if (k == 0) {
      items.push_back({0, Ks + " points p(t) at equal steps of t"});
      if (has_bp) items.push_back({1, "breakpoints p(t_{i})"});
      caption(left - 50, top + plot + 62, "original p:  u(p) = " + u_text(r.u_before), items, color);
    } else {
      items.push_back({0, Ks + " points p(r(s)) at equal steps of s"});
      if (has_bp) items.push_back({1, "breakpoints p(t_{i}) = p(r(s_{i}))"});
      caption(left - 50, top + plot + 62, "reparameterized p\u2218r:  u(p\u2218r) = " + u_text(r.u_after), items,
              color);
    }
    doc.end_group();
  }

  // Speed panel.
  {
    const double left = 2 * col + left0;
    double ymax = 0;
    for (const auto& p : d.speed_before) ymax = std::max(ymax, std::isfinite(p.second) ? p.second : 0);
    for (const auto& piece : d.speed_after)
      for (const auto& p : piece) ymax = std::max(ymax, std::isfinite(p.second) ? p.second : 0);
    if (!(ymax > 0)) ymax = 1;
    svg::Ticks yt3 = svg::nice_ticks(0, ymax * 1.04, 5);
    const double ytop = std::max(ymax * 1.06, yt3.values.empty() ? ymax : yt3.values.back());
    const svg::Panel P{left, top, plot, plot, 0, 1, 0, ytop};
    doc.begin_group("panel speed");
    svg::draw_axes(doc, P, svg::nice_ticks(0, 1, 5), yt3, "t (for p),  s (for p\u2218r)",
                   angular ? "angular speed \u03c9" : "parametric speed |p\u2032|");
    doc.begin_clip(P.left, P.top, P.width, P.height);
    doc.begin_group("joints");
    for (double s : d.joints_s)
      doc.line(P.map(s, 0), P.map(s, ytop), Style{kRed, "none", 1.2, "3 3", 0.8});
    doc.end_group();
    const double mu = mid_double(r.mu);
    doc.line(P.map(0, mu), P.map(1, mu), Style{"#666", "none", 1.4, "6 4", 1});
    std::vector<Point> sb;
    for (const auto& p : d.speed_before) sb.push_back(P.map(p));
    doc.begin_group("speed before");
    doc.polyline(sb, Style{kGreen, "none", 2.2, "", 1});
    doc.end_group();
    doc.begin_group("speed after");
    for (const auto& piece : d.speed_after) {
      std::vector<Point> pa;
      for (const auto& p : piece) pa.push_back(P.map(p));
      doc.polyline(pa, Style{kRed, "none", 2.2, "", 1});
    }
    doc.end_group();
    doc.begin_group("breakpoints");
    for (const auto& p : d.breakpoint_speeds) doc.diamond(P.map(p), 6, Style{kMark, "none", 1.6, "", 1});
    doc.end_group();
    doc.end_clip();
    std::vector<std::pair<int, std::string>> items = {
        {2, speed_before + ", the original speed"},
        {2, speed_after + ", the new speed"},
        {3, "\u03bc = " + r.mu.mid_decimal(4) + ", the speed of a uniform p\u2218r"},
    };
    caption(left - 50, top + plot + 62, "speeds:  u(p) = " + u_text(r.u_before) + " \u2192 u(p\u2218r) = " +
                                            u_text(r.u_after),
            {}, kRed);
    // two colours in one legend: draw the items one by one
    double yy = top + plot + 82;
    const double x = left - 50;
    doc.begin_group("legend");
    doc.line({x, yy - 4}, {x + 16, yy - 4}, Style{kGreen, "none", 2.2, "", 1});
    doc.text({x + 22, yy}, items[0].second, 12.5, Anchor::Start, "#222");
    yy += 18;
    doc.line({x, yy - 4}, {x + 16, yy - 4}, Style{kRed, "none", 2.2, "", 1});
    doc.text({x + 22, yy}, items[1].second, 12.5, Anchor::Start, "#222");
    yy += 18;
    doc.line({x, yy - 4}, {x + 16, yy - 4}, Style{"#666", "none", 1.4, "6 4", 1});
    doc.text({x + 22, yy}, items[2].second, 12.5, Anchor::Start, "#222");
    if (has_bp) {
      yy += 18;
      doc.line({x + 7, yy - 11}, {x + 7, yy + 3}, Style{kRed, "none", 1.2, "3 3", 1});
      doc.text({x + 22, yy}, "joints s_{i} of r (where p\u2218r's pieces meet)", 12.5, Anchor::Start, "#222");
      yy += 18;
      doc.diamond({x + 7, yy - 4}, 5.5, Style{kMark, "none", 1.5, "", 1});
      doc.text({x + 22, yy}, speed_before + " at the breakpoints t_{i}", 12.5, Anchor::Start, "#222");
    }
    doc.end_group();
    doc.end_group();
  }
  return doc.str();
}

}  // namespace

namespace {

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
    status = target_status(r, "plot");
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
