// The grey trace of `uniparam plot` follows the curve's geometry however
// the parameter is distributed (arcs crowded into a tiny range of t, huge
// weights) and stays on an ordinary curve.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "support/plot_svg.hpp"
#include "support/run.hpp"
#include "support/svg.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam::test_support;

namespace {

struct Pt {
  double x, y;
};

// The grey trace of a curve panel, in data coordinates (through the axes).
std::vector<Pt> trace_of(const std::string& svg, const std::string& panel) {
  const std::string g = group(svg, panel);
  const auto axes = axes_groups(g);
  EXPECT_EQ(axes.size(), 1u);
  if (axes.size() != 1) return {};
  const auto [x, y] = read_axes(axes[0].first, axes[0].second);
  const std::size_t p = g.find("<polyline points=\"");
  EXPECT_NE(p, std::string::npos);
  EXPECT_NE(g.substr(p, g.find('>', p) - p).find("#b8b8b8"), std::string::npos) << "the first polyline is the trace";
  const std::string pts = attr(g.substr(p, g.find('>', p) - p), "points");
  std::vector<Pt> v;
  std::istringstream in(pts);
  for (std::string pair; in >> pair;) {
    const std::size_t comma = pair.find(',');
    v.push_back({x.at(std::stod(pair.substr(0, comma))), y.at(std::stod(pair.substr(comma + 1)))});
  }
  return v;
}

double data_per_pixel(const std::string& svg, const std::string& panel) {
  const std::string g = group(svg, panel);
  const auto axes = axes_groups(g);
  return std::fabs(read_axes(axes[0].first, axes[0].second).first.per_pixel());
}

double segment_distance(Pt p, Pt a, Pt b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double u = l2 > 0 ? std::min(1.0, std::max(0.0, ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2)) : 0;
  return std::hypot(p.x - a.x - u * dx, p.y - a.y - u * dy);
}

}  // namespace

// The quarter circle x = (1-u²)/(1+u²), y = 2u/(1+u²) with u = t/(t + k(1-t)):
// for k = 10^6 the arc lies at t within about 10^-4 of 1 (between two of
// the equal steps of a dense sampling), for k = 10^-40 at t below 10^-38.
// The trace's vertices and the midpoints of its segments lie within a pixel
// of the unit circle, and it runs from (1, 0) to (0, 1).
TEST(PlotRobust, TraceFollowsACircleWhoseArcIsCrowdedIntoATinyRangeOfT) {
  for (const std::string k : {"10^6", "1/10^40"}) {
    const std::string D = "(" + k + " + (1 - " + k + ")*t)";
    const std::string curve = "((" + D + "^2 - t^2)/(" + D + "^2 + t^2), 2*t*" + D + "/(" + D + "^2 + t^2))";
    const std::string svg = plot_svg({curve});
    for (const std::string panel : {"panel before", "panel after"}) {
      const auto tr = trace_of(svg, panel);
      const double px = data_per_pixel(svg, panel);
      ASSERT_GE(tr.size(), 2u);
      EXPECT_LT(std::hypot(tr.front().x - 1, tr.front().y), 2 * px) << k;
      EXPECT_LT(std::hypot(tr.back().x, tr.back().y - 1), 2 * px) << k;
      double worst_vertex = 0, worst_mid = 0;
      for (std::size_t i = 0; i < tr.size(); ++i) {
        worst_vertex = std::max(worst_vertex, std::fabs(std::hypot(tr[i].x, tr[i].y) - 1));
        if (i > 0) {
          const Pt m{(tr[i - 1].x + tr[i].x) / 2, (tr[i - 1].y + tr[i].y) / 2};
          worst_mid = std::max(worst_mid, std::fabs(std::hypot(m.x, m.y) - 1));
        }
      }
      EXPECT_LT(worst_vertex, px) << k << " " << panel;
      EXPECT_LT(worst_mid, px) << k << " " << panel << ": a segment cuts across the arc";
    }
  }
}

// The rational quadratic Bezier curve of the issue: weights [1, 8e40, 1e82]
// put its arc at t ~ 1e-41. Points of the curve there (evaluated exactly by
// the library) lie within a pixel and a half of the trace.
TEST(PlotRobust, TraceCoversTheArcOfAHugeWeightBezierCurve) {
  const std::string control = "[[1,0],[1,1],[0,1]]", weights = "[1,8e40,1e82]";
  const std::string svg = plot_svg({"--control", control, "--weights", weights});
  const uniparam::Curve c = uniparam::BezierCurve::parse(control, weights).to_curve();
  for (const std::string panel : {"panel before", "panel after"}) {
    const auto tr = trace_of(svg, panel);
    const double px = data_per_pixel(svg, panel);
    ASSERT_GE(tr.size(), 2u);
    for (int e = -46; e <= -36; ++e)
      for (int m : {1, 2, 5}) {
        const uniparam::Rational t = uniparam::Rational::parse(std::to_string(m) + "e" + std::to_string(e));
        const auto p = c.eval(uniparam::Ball(t, 512), 512);
        const Pt q{uniparam::mid_double(p[0]), uniparam::mid_double(p[1])};
        double best = HUGE_VAL;
        for (std::size_t i = 1; i < tr.size(); ++i) best = std::min(best, segment_distance(q, tr[i - 1], tr[i]));
        EXPECT_LT(best, 1.5 * px) << panel << ": p(" << m << "e" << e << ") = (" << q.x << ", " << q.y
                                  << ") is off the trace";
      }
  }
}

// An ordinary curve: the trace stays on y = x^3 (vertices and segment
// midpoints within a pixel).
TEST(PlotRobust, TraceOfAnOrdinaryCurveStaysOnIt) {
  const std::string svg = plot_svg({"(t, t^3)"});
  const auto tr = trace_of(svg, "panel before");
  const double px = data_per_pixel(svg, "panel before");
  ASSERT_GE(tr.size(), 2u);
  for (std::size_t i = 0; i < tr.size(); ++i) {
    EXPECT_LT(std::fabs(tr[i].y - tr[i].x * tr[i].x * tr[i].x), px);
    if (i > 0) {
      const double mx = (tr[i - 1].x + tr[i].x) / 2, my = (tr[i - 1].y + tr[i].y) / 2;
      EXPECT_LT(std::fabs(my - mx * mx * mx), px);
    }
  }
}
