// cli/plot_view.hpp -- internal to `uniparam plot` (cmd_plot.cpp, plot_trace.cpp,
// plot_render.cpp): what the plot draws (a curve and a map seen through
// evaluations), the projection of space curves, the data collected from
// them, and the two steps from view to picture.
#pragma once

#include <cmath>
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "commands.hpp"
#include "svg.hpp"
#include "uniparam/reparam/sample.hpp"

namespace uniparam::cli::plot {

using svg::Point;

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
/// iso for 3 or more components) for a curve of n components; InvalidArgument
/// for a name that does not fit n.
Projection read_projection(const std::string& given, std::size_t n);

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

struct PlotData {
  std::vector<Point> trace;                 // the curve (projected), trace_curve
  std::vector<Point> before, after;         // the K samples (projected)
  std::vector<Point> breakpoints;           // p(t_i), interior i
  std::vector<Point> speed_before;          // (t, sigma_p(t)), dense
  std::vector<std::vector<Point>> speed_after;  // per piece (s, sigma_{p o r}(s)), dense
  std::vector<Point> breakpoint_speeds;     // (t_i, sigma_p(t_i)), interior i
  std::vector<double> joints_s;             // interior s_i
};

/// The trace of v (the curve sampled adaptively in its own geometry, at
/// most max_prec bits per point), the K samples, the speeds and the
/// breakpoints, projected by proj (plot_trace.cpp).
PlotData collect(const PlotView& v, const Projection& proj, long max_prec);

/// The SVG picture of the three panels (plot_render.cpp): the curve with
/// its samples before and after, and the two speeds; K names the samples.
std::string render(const PlotView& v, SpeedKind kind, const PlotData& d, const Projection& proj, long K);

}  // namespace uniparam::cli::plot
