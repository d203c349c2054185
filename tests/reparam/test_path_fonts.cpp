// The font test data (tests/data, written by scripts/extract_font_segments.py
// from DejaVu Sans) read through the JSON and SVG readers: every letter
// contour of glyphs.jsonl is one closed SVG subpath whose quadratic segments
// are exactly the lines of font_quadratics.jsonl for that glyph and contour,
// in order ("p/2" coordinates read exactly).
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "uniparam/core/json.hpp"
#include "uniparam/reparam/path.hpp"

namespace uniparam {
namespace {

std::vector<std::string> lines_of(const std::string& name) {
  std::ifstream f(std::string(UNIPARAM_TEST_DATA_DIR) + "/" + name);
  EXPECT_TRUE(f.good()) << "cannot open " << name;
  std::vector<std::string> out;
  for (std::string line; std::getline(f, line);)
    if (!line.empty()) out.push_back(line);
  return out;
}

using Points = std::vector<std::vector<Rational>>;

TEST(FontData, GlyphContoursMatchTheQuadraticSegments) {
  // (glyph, contour) -> its quadratics in order, from font_quadratics.jsonl.
  std::map<std::pair<std::string, long>, std::vector<Points>> quads;
  const auto quad_lines = lines_of("font_quadratics.jsonl");
  EXPECT_GE(quad_lines.size(), 2000u);
  for (const auto& line : quad_lines) {
    const JsonValue v = parse_json(line);
    Points pts;
    for (const auto& p : v.find("control")->as_array("control")) {
      const auto& xy = p.as_array("point");
      ASSERT_EQ(xy.size(), 2u) << line;
      pts.push_back({xy[0].as_rational("x"), xy[1].as_rational("y")});
    }
    ASSERT_EQ(pts.size(), 3u) << line;
    EXPECT_NO_THROW(BezierCurve{pts}) << line;
    quads[{v.find("glyph")->as_string("glyph"), v.find("contour")->as_long("contour", 0, 1000)}].push_back(pts);
  }
  const auto glyph_lines = lines_of("glyphs.jsonl");
  EXPECT_GE(glyph_lines.size(), 52u);
  std::size_t matched = 0;
  for (const auto& line : glyph_lines) {
    SCOPED_TRACE(line.substr(0, 60));
    const JsonValue v = parse_json(line);
    const auto paths = parse_svg_path(v.find("svg")->as_string("svg"));
    ASSERT_EQ(paths.size(), 1u);
    const PathInput& p = paths[0];
    EXPECT_EQ(p.segments.front().points().front(), p.segments.back().points().back());  // closed
    std::vector<Points> q;
    for (const auto& s : p.segments) {
      ASSERT_TRUE(s.degree() == 1 || s.degree() == 2);
      if (s.degree() == 2) q.push_back(s.points());
    }
    const auto key = std::make_pair(v.find("glyph")->as_string("glyph"), v.find("contour")->as_long("contour", 0, 1000));
    const auto it = quads.find(key);
    if (q.empty()) {
      EXPECT_EQ(it, quads.end());
    } else {
      ASSERT_NE(it, quads.end());
      EXPECT_EQ(it->second, q);
      matched += q.size();
    }
  }
  EXPECT_GE(matched, 300u);
}

}  // namespace
}  // namespace uniparam
