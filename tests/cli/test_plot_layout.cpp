// `uniparam plot` at extreme scales and with long text: tick labels stay
// short, correct and inside their panel, and title lines fit the page.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "support/plot_svg.hpp"
#include "support/run.hpp"
#include "support/svg.hpp"

using namespace uniparam::test_support;

// ---- Ticks at extreme scales ----------------------------------------------

TEST(PlotRobust, TickLabelsStayShortCorrectAndInsideTheirPanelAtExtremeScales) {
  struct Case {
    std::vector<std::string> args;
    double x0, x1, y0, y1;  // the curve's extent in the curve panels
  };
  const Case cases[] = {
      {{"(t*10^40, t^2*10^40)"}, 0, 1e40, 0, 1e40},
      {{"(t/10^30, t^3/10^30)"}, 0, 1e-30, 0, 1e-30},
      {{"(10^10 + t, t^2)"}, 1e10, 1e10 + 1, 0, 1},
      {{"(-10^20 - t*10^14, t*10^14)"}, -1e20 - 1e14, -1e20, 0, 1e14},
      {{"(t/10^9, 1 + t^2/10^9)"}, 0, 1e-9, 1, 1 + 1e-9},
      {{"(t, t^3)"}, 0, 1, 0, 1},
      // the speed panel's y axis reaches 1.2e41
      {{"--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,8e40,1e82]"}, 0, 1, 0, 1},
  };
  for (const auto& c : cases) {
    const std::string svg = plot_svg(c.args);
    const auto groups = axes_groups(svg);
    ASSERT_EQ(groups.size(), 3u) << c.args[0];
    for (std::size_t k = 0; k < groups.size(); ++k) {
      const auto& [frame, g] = groups[k];
      std::vector<Text> labels;
      const auto [x, y] = read_axes(frame, g, &labels);
      for (const auto& t : labels) {
        EXPECT_LE(code_points(t.text).size(), 6u) << c.args[0] << ": tick label '" << t.text << "'";
        if (k > 0 && t.anchor == "end")  // clear of the panel on the left
          EXPECT_GT(t.x - width_px(t), groups[k - 1].first.x + groups[k - 1].first.w)
              << c.args[0] << ": '" << t.text << "'";
      }
      EXPECT_TRUE(affine(x)) << c.args[0] << " panel " << k << " x";
      EXPECT_TRUE(affine(y)) << c.args[0] << " panel " << k << " y";
      if (k < 2 && x.pixel.size() >= 2 && y.pixel.size() >= 2) {
        // the frame shows the curve's extent, not much more (equal aspect
        // and 6% padding: at most 1.4 x the larger side)
        const double fx0 = x.at(frame.x), fx1 = x.at(frame.x + frame.w);
        const double fy0 = y.at(frame.y + frame.h), fy1 = y.at(frame.y);
        const double side = std::max(c.x1 - c.x0, c.y1 - c.y0);
        EXPECT_LE(fx0, c.x0 + 1e-6 * side) << c.args[0];
        EXPECT_GE(fx1, c.x1 - 1e-6 * side) << c.args[0];
        EXPECT_LE(fy0, c.y0 + 1e-6 * side) << c.args[0];
        EXPECT_GE(fy1, c.y1 - 1e-6 * side) << c.args[0];
        EXPECT_LE(fx1 - fx0, 1.4 * side) << c.args[0];
        EXPECT_LE(fy1 - fy0, 1.4 * side) << c.args[0];
      }
      // the y axis label (rotated; reaches about 10 px left of its x) is clear
      // of the left panel too
      if (k > 0) {
        const auto ts = texts(g);
        for (const auto& t : ts)
          if (t.size == 13 && t.anchor == "middle" && t.x < frame.x)
            EXPECT_GT(t.x - 0.8 * t.size, groups[k - 1].first.x + groups[k - 1].first.w) << c.args[0];
      }
    }
  }
}

// ---- Titles ------------------------------------------------------------------

TEST(PlotRobust, TitleLinesFitThePage) {
  const std::string zeros(300, '0');
  const std::string slide = "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";
  struct Case {
    std::vector<std::string> args;
    std::string title_start, title_end;  // a long number: its start and end stay visible
  };
  const Case cases[] = {
      {{"--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,8e40,1e82]"}, "", ""},
      {{slide, "--method", "c1", "--target", "0.99" + zeros + "1"}, "0.9900000", "0001reached"},
      {{"(t, t^3)"}, "", ""},
  };
  for (const auto& c : cases) {
    const std::string svg = plot_svg(c.args);
    const double W = std::stod(attr(svg.substr(svg.find("<svg "), 400), "width"));
    const auto ts = texts(group(svg, "title"));
    ASSERT_FALSE(ts.empty());
    std::string all;
    for (const auto& t : ts) {
      const double w = width_px(t);
      EXPECT_LE(t.x - w / 2, W) << "'" << t.text << "'";  // anchored middle at W / 2
      EXPECT_LE(w, W - 20) << "'" << t.text << "' (" << w << " px of " << W << ")";
      if (t.bold) all += t.text;
    }
    if (!c.title_start.empty()) {
      std::string compact;
      for (char ch : all)
        if (ch != ' ') compact += ch;
      EXPECT_NE(compact.find(c.title_start), std::string::npos) << all;
      EXPECT_NE(compact.find(c.title_end), std::string::npos) << all;
    }
    // the subtitle starts with the curve's start and ends with its end
    bool start = false;
    for (const auto& t : ts) start = start || t.text.rfind("p(t) = (", 0) == 0;
    EXPECT_TRUE(start);
  }
}
