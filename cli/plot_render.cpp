// The picture of `uniparam plot`: three panels (the curve at equal steps of
// t, the reparameterized curve at equal steps of s, the two speeds) with
// axes, breakpoints, joints and the certified uniformities in the captions.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "output.hpp"
#include "plot_view.hpp"

namespace uniparam::cli::plot {

namespace {

using svg::Anchor;
using svg::Style;

const char* kGreen = "#1a9641";
const char* kRed = "#d7191c";
const char* kTrace = "#b8b8b8";
const char* kMark = "#111111";

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

}  // namespace

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

}  // namespace uniparam::cli::plot
