// Composite curves from the command line (--svg, --nurbs) and `batch`:
// exact oracles (a polyline's length and uniformity, a curve split by de
// Casteljau at 1/2 is the same parameterized curve), every command on a
// path, and every refusal with a clear message.
#include <gtest/gtest.h>

#include <arb.h>

#include <sstream>
#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::json_ball;
using uniparam::test_support::run_uniparam;
using uniparam::test_support::run_uniparam_stdin;

namespace {

// The quadratic (0,0), (2,4), (4,0) split by de Casteljau at 1/2:
// (0,0), (1,2), (2,2) and (2,2), (3,2), (4,0). With knots 0, 1/2, 1 the
// path is the same parameterized curve as the single quadratic.
const char* kSplit = "M 0 0 Q 1 2 2 2 Q 3 2 4 0";
const char* kWhole = "[[0,0],[2,4],[4,0]]";
// A 3-4-5 triangle: length 12, three line segments.
const char* kTriangle = "M 0 0 L 3 0 L 3 4 Z";

bool overlaps(const std::string& a_json, const std::string& a_key, const std::string& b_json,
              const std::string& b_key) {
  Ball a, b;
  if (!json_ball(a_json, a_key, a) || !json_ball(b_json, b_key, b)) return false;
  return arb_overlaps(a.get(), b.get());
}

TEST(CompositeCli, SplitQuadraticIsTheWholeQuadratic) {
  for (const char* speed : {"parametric", "angular"}) {
    const auto whole = run_uniparam({"uniformity", "--control", kWhole, "--speed", speed, "--json"});
    const auto split = run_uniparam({"uniformity", "--svg", kSplit, "--speed", speed, "--json"});
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    ASSERT_EQ(split.exit_code, 0) << split.err;
    EXPECT_TRUE(overlaps(whole.out, "mu", split.out, "mu")) << speed;
    EXPECT_TRUE(overlaps(whole.out, "u", split.out, "u")) << speed;
    // The joint is smooth: angle exactly 0.
    EXPECT_NE(split.out.find("\"smooth\": true"), std::string::npos);
  }
}

TEST(CompositeCli, TriangleLengthAndUniformityAreExact) {
  const auto r = run_uniparam({"uniformity", "--svg", kTriangle, "--speed", "parametric", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Ball mu, u;
  ASSERT_TRUE(json_ball(r.out, "mu", mu));
  ASSERT_TRUE(json_ball(r.out, "u", u));
  EXPECT_TRUE(mu.contains(Rational(12)));
  // Speeds 3, 4, 5 on thirds of [0, 1]: u = 12^2 / (3 (9 + 16 + 25)) = 24/25.
  EXPECT_TRUE(u.contains(Rational(24, 25)));
  EXPECT_TRUE(mu.meets_digits(15));
  // Two corners inside the path: pi/2 at (3,0) and pi - atan(4/3)... the
  // exterior angle at (3,4) between (0,1) and (-3,-4)/5: acos(-4/5).
  EXPECT_NE(r.out.find("\"smooth\": false"), std::string::npos);
  const auto text = run_uniparam({"uniformity", "--svg", kTriangle, "--speed", "parametric"});
  EXPECT_NE(text.out.find("corner, turning angle 1.5707963"), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("corner, turning angle 2.4980915"), std::string::npos) << text.out;
}

TEST(CompositeCli, OneSegmentPathIsTheBezierCurve) {
  // A path of one segment goes through the one-curve commands: the same
  // answer as --control, bit for bit.
  for (const char* cmd : {"uniformity", "radical", "moebius"}) {
    const auto a = run_uniparam({cmd, "--svg", "M 0 0 Q 2 4 4 0", "--speed", "parametric", "--json"});
    const auto b = run_uniparam({cmd, "--control", kWhole, "--speed", "parametric", "--json"});
    ASSERT_EQ(a.exit_code, 0) << a.err;
    EXPECT_EQ(a.out, b.out) << cmd;
  }
}

// A clamped cubic B-spline with interior knots 1, 2 (uniform, domain [0, 3]) and
// the SVG path of its Bezier segments are the same composite curve (knots
// 0, 1/3, 2/3, 1): every result must be the same, bit for bit.
TEST(CompositeCli, CubicBSplineEqualsItsBezierSegments) {
  const std::string nurbs =
      R"({"degree": 3, "knots": [0, 0, 0, 0, 1, 2, 3, 3, 3, 3],
          "control": [[0, 0], [12, 36], [36, 48], [60, 12], [84, 24], [96, 0]]})";
  const PathInput p = parse_nurbs(nurbs);
  ASSERT_EQ(p.segments.size(), 3u);
  EXPECT_EQ(p.knots, (std::vector<Rational>{Rational(0), Rational(1, 3), Rational(2, 3), Rational(1)}));
  auto coord = [](const Rational& x) {
    EXPECT_EQ(x.den(), Integer(1)) << x.str();  // the test's points are integers
    return x.str();
  };
  std::string svg = "M " + coord(p.segments[0].points()[0][0]) + " " + coord(p.segments[0].points()[0][1]);
  for (const BezierCurve& b : p.segments) {
    svg += " C";
    for (int i = 1; i <= 3; ++i) svg += " " + coord(b.points()[i][0]) + " " + coord(b.points()[i][1]);
  }
  for (const std::vector<std::string>& cmd :
       {std::vector<std::string>{"uniformity"}, {"reparam", "--pieces", "5"}, {"radical"}, {"reparam", "--target", "0.999"}}) {
    std::vector<std::string> a = cmd, b = cmd;
    for (auto* v : {&a, &b}) v->insert(v->end(), {"--speed", "parametric", "--json"});
    a.insert(a.end(), {"--nurbs", nurbs});
    b.insert(b.end(), {"--svg", svg});
    const auto ra = run_uniparam(a), rb = run_uniparam(b);
    ASSERT_EQ(ra.exit_code, 0) << ra.err;
    ASSERT_EQ(rb.exit_code, 0) << rb.err;
    // Equal but for the description of the input and the segments' labels.
    JsonValue ja = parse_json(ra.out), jb = parse_json(rb.out);
    for (auto* j : {&ja, &jb})
      for (auto& [k, v] : j->members) {
        if (k == "curve") v = JsonValue{};
        if (k == "parts")
          for (auto& part : v.items)
            for (auto& [pk, pv] : part.members)
              if (pk == "label") pv = JsonValue{};
      }
    EXPECT_EQ(ja.dump(), jb.dump()) << cmd[0];
  }
}

TEST(CompositeCli, EveryMethodRunsOnAPath) {
  const std::string path = "M 0 0 C 1 2 3 2 4 0 S 7 -2 8 0 Q 9 1 10 0";
  const auto rad = run_uniparam({"radical", "--svg", path, "--speed", "parametric", "--json"});
  ASSERT_EQ(rad.exit_code, 0) << rad.err;
  const auto moe = run_uniparam({"moebius", "--svg", path, "--speed", "parametric", "--json"});
  ASSERT_EQ(moe.exit_code, 0) << moe.err;
  Ball before, after;
  ASSERT_TRUE(json_ball(moe.out, "u_before", before));
  ASSERT_TRUE(json_ball(moe.out, "u_after", after));
  Ball d;
  arb_sub(d.get(), after.get(), before.get(), 128);
  EXPECT_FALSE(d.certainly_negative());
  const auto c0 = run_uniparam({"reparam", "--svg", path, "--pieces", "6", "--speed", "parametric", "--json"});
  ASSERT_EQ(c0.exit_code, 0) << c0.err;
  EXPECT_NE(c0.out.find("\"pieces\": 6"), std::string::npos);
  const auto few = run_uniparam({"reparam", "--svg", path, "--pieces", "2", "--speed", "parametric"});
  EXPECT_EQ(few.exit_code, 2);
  EXPECT_NE(few.err.find("number of segments (3"), std::string::npos) << few.err;
  const auto c1 = run_uniparam({"reparam", "--svg", path, "--target", "0.99", "--speed", "parametric", "--json"});
  ASSERT_EQ(c1.exit_code, 0) << c1.err;
  Ball u1;
  ASSERT_TRUE(json_ball(c1.out, "u_after", u1));
  arb_sub(d.get(), u1.get(), Ball(Rational(99, 100), 128).get(), 128);
  EXPECT_TRUE(d.certainly_positive());
  const auto rat = run_uniparam({"moebius", "--svg", path, "--speed", "parametric", "--rational"});
  EXPECT_EQ(rat.exit_code, 0) << rat.err;
  EXPECT_NE(rat.out.find("exact rational maps"), std::string::npos);
}

TEST(CompositeCli, SamplesStartAndEndOnThePathAndMeetTheJoints) {
  const std::string path = "M 0 0 Q 1 2 2 2 L 5 2";
  for (const char* method : {"none", "radical", "c0", "c1", "exact"}) {
    const auto r = run_uniparam({"sample", "--svg", path, "--speed", "parametric", "--method", method, "--points",
                                 "11", "--format", "csv"});
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    std::istringstream in(r.out);
    std::string line;
    std::vector<std::string> rows;
    while (std::getline(in, line)) rows.push_back(line);
    ASSERT_EQ(rows.size(), 12u) << method;
    EXPECT_EQ(rows[0], "s,t,x,y,speed");
    EXPECT_EQ(rows[1].substr(0, 8), "0,0,0,0,") << method;
    EXPECT_EQ(rows[11].substr(0, 8), "1,1,5,2,") << method << " " << rows[11];
  }
  // --deviation on the 3-4-5 triangle with r = id (s = t, speeds 3, 4, 5 on
  // thirds): G(t)/mu - s is -1/12 at s = 1/3 and at s = 2/3, 0 at the ends.
  const auto dev = run_uniparam({"sample", "--svg", kTriangle, "--speed", "parametric", "--method", "none",
                                 "--points", "4", "--deviation", "--json"});
  ASSERT_EQ(dev.exit_code, 0) << dev.err;
  Ball worst;
  ASSERT_TRUE(json_ball(dev.out, "max_deviation", worst));
  EXPECT_TRUE(worst.contains(Rational(1, 12))) << dev.out.substr(dev.out.find("max_deviation"));
  EXPECT_TRUE(worst.meets_digits(15));
  // Equal arc length steps: the path has length L = int + 3; with 11 points
  // the located parameters increase.
  const auto ex = run_uniparam({"sample", "--svg", path, "--speed", "arclength", "--method", "exact", "--points",
                                "5", "--json"});
  ASSERT_EQ(ex.exit_code, 0) << ex.err;
}

TEST(CompositeCli, PlotDrawsAPathAndItsMap) {
  const std::string path = "M 0 0 C 1 2 3 2 4 0 S 7 -2 8 0 Q 9 1 10 0";
  for (const char* method : {"radical", "c0", "c1"}) {
    const auto r = run_uniparam({"plot", "--svg", path, "--speed", "parametric", "--method", method, "-o", "-"});
    ASSERT_EQ(r.exit_code, 0) << method << ": " << r.err;
    EXPECT_NE(r.out.find("SVG path of 3 segments"), std::string::npos);
    EXPECT_NE(r.out.find("</svg>"), std::string::npos);
    // The original points and the map's points: 40 of each by default.
    std::size_t dots = 0;
    for (std::size_t at = r.out.find("<circle"); at != std::string::npos; at = r.out.find("<circle", at + 1)) ++dots;
    EXPECT_GE(dots, 80u) << method;
  }
}

TEST(CompositeCli, LocateOnASymmetricPathFindsTheJoint) {
  // Two mirror-image arcs: half the length is exactly at the joint t = 1/2.
  const auto r = run_uniparam({"locate", "--svg", "M 0 0 Q 1 2 2 2 Q 3 2 4 0", "--fraction", "1/2", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Ball t;
  ASSERT_TRUE(json_ball(r.out, "t", t));
  EXPECT_TRUE(t.contains(Rational(1, 2)));
  EXPECT_TRUE(t.meets_digits(15));
  Ball x;
  const auto len = run_uniparam({"locate", "--svg", kTriangle, "--length", "5", "--json"});
  ASSERT_EQ(len.exit_code, 0) << len.err;
  // Length 5 along the triangle: 3 along the base, then 2 up: (3, 2) at t = 1/3 + 1/6.
  ASSERT_TRUE(json_ball(len.out, "t", t));
  EXPECT_TRUE(t.contains(Rational(1, 2)));
}

TEST(CompositeCli, RefusalsAreClear) {
  struct Case {
    std::vector<std::string> args;
    int exit;
    const char* message;
  } cases[] = {
      {{"uniformity", "--svg", "M 0 0 L 1 1 M 2 2 L 3 3"}, 2, "--subpath"},
      {{"uniformity", "--svg", "M 0 0 L 1 1 M 2 2 L 3 3", "--subpath", "2"}, 2, "--subpath"},
      {{"uniformity", "(t, t^2)", "--svg", "M 0 0 L 1 1"}, 2, "not both"},
      {{"uniformity", "--control", kWhole, "--svg", "M 0 0 L 1 1"}, 2, "were both given"},
      {{"uniformity", "--subpath", "0", "(t, t^2)"}, 2, "--subpath needs --svg"},
      {{"bezier", "--svg", kSplit}, 2, "takes one Bezier curve"},
      {{"radical", "--svg", "M 0 0 Q 1 2 2 2 L 5 2"}, 3, "straight"},
      {{"locate", "--svg", "M 0 0 L 1 0 Q 2 0 2 1 L 2 3 Q 2 4 3 4", "--fraction", "1/2"}, 3, "straight"},
      {{"sample", "--svg", "M 0 0 Q 1 2 2 2 L 5 2", "--method", "exact"}, 3, "straight"},
      {{"uniformity", "--svg", "M 0 0 Q 1 2"}, 2, ""},
      {{"uniformity", "--nurbs", "{\"degree\": 2}"}, 2, ""},
  };
  for (const auto& c : cases) {
    const auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, c.exit) << c.args[1] << " " << c.args[2] << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

// batch: one result per line in order, errors in place, results equal to
// the command's own --json answer.
TEST(Batch, ResultsAreInOrderAndEqualToTheCommand) {
  std::string input;
  std::vector<std::string> curves = {"(t, t^2)", "(t^2, t^3)", "(t, 1/(1+t))"};
  for (int rep = 0; rep < 30; ++rep)
    for (std::size_t i = 0; i < curves.size(); ++i)
      input += "{\"id\": " + std::to_string(rep * 10 + i) + ", \"curve\": \"" + curves[i] + "\"}\n";
  input += "{\"curve\": \"(t, \"}\n";                      // a parse error in the curve
  input += "not json\n";                                   // not JSON
  input += "\n";                                           // blank: skipped
  input += "{\"svg\": \"" + std::string(kTriangle) + "\", \"options\": {\"digits\": 20}}\n";
  input += "{\"control\": [[0, 0], [\"1/2\", 1], [1, 0]], \"weights\": [1, 2, 1]}\n";
  const auto r = run_uniparam_stdin({"batch", "uniformity", "--speed", "parametric", "--jobs", "2"}, input);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  std::istringstream in(r.out);
  std::string line;
  std::vector<JsonValue> rows;
  while (std::getline(in, line)) rows.push_back(parse_json(line));
  ASSERT_EQ(rows.size(), 94u) << r.out.substr(0, 500);
  for (std::size_t i = 0; i < 90; ++i) {
    ASSERT_EQ(rows[i].find("line")->text, std::to_string(i + 1));
    EXPECT_EQ(rows[i].find("id")->text, std::to_string((i / 3) * 10 + i % 3));
    EXPECT_EQ(rows[i].find("status")->text, "0");
  }
  // Bit for bit the command's own answer.
  const auto one = run_uniparam({"uniformity", "(t^2, t^3)", "--speed", "parametric", "--json"});
  const JsonValue own = parse_json(one.out);
  EXPECT_EQ(rows[1].find("result")->dump(), own.dump());
  EXPECT_EQ(rows[90].find("status")->text, "2");
  EXPECT_EQ(rows[90].find("error")->find("type")->text, "ParseError");
  EXPECT_EQ(rows[91].find("line")->text, "92");
  EXPECT_EQ(rows[91].find("error")->find("type")->text, "ParseError");
  EXPECT_EQ(rows[92].find("line")->text, "94");  // the blank line 93 is skipped
  EXPECT_EQ(rows[92].find("status")->text, "0");
  EXPECT_EQ(rows[92].find("result")->find("digits")->text, "20");
  EXPECT_EQ(rows[93].find("status")->text, "0");
  EXPECT_NE(r.err.find("94 lines"), std::string::npos) << r.err;
}

TEST(Batch, BadCommandLinesAreRefusedOnce) {
  EXPECT_EQ(run_uniparam_stdin({"batch", "plot"}, "").exit_code, 2);
  EXPECT_EQ(run_uniparam_stdin({"batch", "nonsense"}, "").exit_code, 2);
  const auto r = run_uniparam_stdin({"batch", "uniformity", "--no-such-option"}, "{\"curve\": \"(t, t^2)\"}\n");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--no-such-option"), std::string::npos);
  EXPECT_TRUE(r.out.empty());
  const auto key = run_uniparam_stdin({"batch", "uniformity"}, "{\"curv\": \"(t, t^2)\"}\n");
  EXPECT_EQ(key.exit_code, 2);
  EXPECT_NE(key.out.find("unknown key"), std::string::npos);
}

}  // namespace
