// `uniparam bezier` and the --control / --weights inputs of every command:
// exact P, Q and alpha, certified values enclosing closed forms, the JSON
// keys of the issue, and the errors of the control-point input.
#include <gtest/gtest.h>

#include <regex>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Rational;
using uniparam::test_support::certified_real;
using uniparam::test_support::encloses;
using uniparam::test_support::run_uniparam;

namespace {

// The "exact" string of a key whose value carries one ("exact": "p/q").
std::string exact_of(const std::string& json, const std::string& key) {
  std::regex re("\"" + key + "\": \\{[^{}]*\"exact\": \"([^\"]+)\"");
  std::smatch m;
  return std::regex_search(json, m, re) ? std::string(m[1]) : std::string();
}

const char* kCircleControl = "[[1,0],[1,1],[0,1]]";  // ((1-t^2)/(1+t^2), 2t/(1+t^2)) with weights 1, 1, 2
const char* kCircleWeights = "[1,1,2]";

}  // namespace

// p = (3t^2, 2t - t^2): |p'|^2 = 36 t^2 + 4 (1-t)^2, so by hand
// A = 36/30 + 4/5 = 2, C = 36/5 + 4/30 = 22/3, B = 72/20 + 8/20 = 4 and
// alpha = 1/(1 + sqrt(11/3)) = (sqrt(33) - 3)/8.
TEST(CliBezier, IntegralQuadraticIsExact) {
  auto r = run_uniparam({"bezier", "--control", "[[0,0],[0,1],[3,1]]", "--json", "--digits", "20"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(Rational::parse(exact_of(r.out, "P")), Rational(-2));
  EXPECT_EQ(Rational::parse(exact_of(r.out, "Q")), Rational(22, 3));
  EXPECT_EQ(Rational::parse(exact_of(r.out, "mean_square")), Rational(40, 3));
  EXPECT_NE(r.out.find("\"text\": \"(-3 + sqrt(33))/8\""), std::string::npos) << r.out;
  EXPECT_TRUE(encloses(r.out, "alpha", "0.34307033081725358248132643352736616", "1e-35", 20));
  for (const char* key : {"\"P\"", "\"Q\"", "\"alpha\"", "\"weights\"", "\"mu\"", "\"u_before\"", "\"u_after\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  // the same alpha in LaTeX in the text output
  auto t = run_uniparam({"bezier", "--control", "[[0,0],[0,1],[3,1]]", "--format", "latex"});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("\\frac{-3 + \\sqrt{33}}{8}"), std::string::npos) << t.out;
}

// The rational quadratic of the quarter circle: docs/math.md section 6 reference
// u after = 0.9977912002415711604419615, alpha = 2 - sqrt 2, mu = pi/2.
TEST(CliBezier, QuarterCircleReachesReference) {
  auto r = run_uniparam({"bezier", "--control", kCircleControl, "--weights", kCircleWeights, "--json", "--digits", "22"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(encloses(r.out, "u_after", "0.9977912002415711604419615", "1e-25", 22));
  EXPECT_TRUE(encloses(r.out, "u_before", "0.9597808564432393298507263", "1e-25", 22));
  EXPECT_TRUE(encloses(r.out, "alpha", "0.58578643762690495119831127579", "1e-29", 22));
  EXPECT_TRUE(encloses(r.out, "mu", "1.5707963267948966192313216916", "1e-28", 22));
  // P = 2 - pi, Q = pi/2 - 1
  EXPECT_TRUE(encloses(r.out, "P", "-1.1415926535897932384626433833", "1e-28", 22));
  EXPECT_TRUE(encloses(r.out, "Q", "0.5707963267948966192313216916", "1e-28", 22));
  EXPECT_EQ(exact_of(r.out, "alpha"), "");  // certified quadrature, no exact value claimed
}

// --control and --weights work with every command; the curve is the one the
// power basis gives.
TEST(CliBezier, ControlPointsAcceptedByEveryCommand) {
  auto u = run_uniparam({"uniformity", "--control", kCircleControl, "--weights", kCircleWeights, "--speed",
                         "parametric", "--json"});
  ASSERT_EQ(u.exit_code, 0) << u.err;
  EXPECT_TRUE(encloses(u.out, "u", "0.9597808564432393298507263", "1e-25", 15));
  EXPECT_NE(u.out.find("\"curve\": \"((-t^2 + 1)/(t^2 + 1), (2*t)/(t^2 + 1))\""), std::string::npos) << u.out;

  auto m = run_uniparam({"moebius", "--control", "[[0,0],[0,1],[3,1]]", "--speed", "parametric", "--json"});
  ASSERT_EQ(m.exit_code, 0) << m.err;
  // alpha = (sqrt(33) - 3)/8 (IntegralQuadraticIsExact), certified to the
  // default 15 digits: its ball (the first of the "alpha" list) holds it.
  std::smatch first;
  ASSERT_TRUE(std::regex_search(m.out, first, std::regex("\"alpha\": \\[\\s*(\\{[^{}]*\\})"))) << m.out;
  EXPECT_TRUE(encloses("\"alpha\": " + std::string(first[1]), "alpha", "0.3430703308172535824813264335273661647775",
                       "1e-40", 15));

  // A cubic with a cusp at t = 1/2: x' = 3 (1 - 2t)^2, y' = 3 (1 - 2t).
  auto rad = run_uniparam({"radical", "--control", "[[0,0],[1,1],[0,1],[1,0]]", "--speed", "parametric", "--json"});
  ASSERT_EQ(rad.exit_code, 0) << rad.err;
  std::regex mult("\"multiplicity\": \\[\\s*0,\\s*1,\\s*0\\s*\\]");
  EXPECT_TRUE(std::regex_search(rad.out, mult)) << rad.out;
  std::string ub, rb, ua, ra;
  ASSERT_TRUE(certified_real(rad.out, "u_before", ub, rb));
  ASSERT_TRUE(certified_real(rad.out, "u_after", ua, ra));
  EXPECT_GT(Rational::parse(ua) - Rational::parse(ra), Rational::parse(ub) + Rational::parse(rb));
  EXPECT_NE(rad.out.find("\"exact\": \"1/2\""), std::string::npos) << rad.out;
}

TEST(CliBezier, HelpListsTheNewOptions) {
  auto b = run_uniparam({"bezier", "--help"});
  EXPECT_EQ(b.exit_code, 0);
  for (const char* opt : {"--control", "--weights", "--format", "--digits", "--json"})
    EXPECT_NE(b.out.find(opt), std::string::npos) << opt;
  for (const char* cmd : {"uniformity", "moebius", "radical"}) {
    auto h = run_uniparam({cmd, "--help"});
    EXPECT_EQ(h.exit_code, 0);
    EXPECT_NE(h.out.find("(CURVE | --control POINTS | --svg PATH | --nurbs JSON)"), std::string::npos) << cmd;
    EXPECT_NE(h.out.find("--weights"), std::string::npos) << cmd;
  }
  auto main = run_uniparam({"--help"});
  EXPECT_NE(main.out.find("bezier"), std::string::npos);
}

TEST(CliBezier, BadControlPointsGiveClearErrors) {
  struct Bad {
    std::vector<std::string> args;
    int exit_code;
    const char* message;
  };
  const Bad cases[] = {
      {{"bezier"}, 2, "--control"},
      {{"bezier", "--control", "[[0,0]]"}, 2, "at least 2 control points"},
      {{"bezier", "--control", "[[0,0],[1,1,1]]"}, 2, "mixed dimensions"},
      {{"bezier", "--control", "[[0,0],[1,1]]", "--weights", "[1,-1]"}, 2, "positive"},
      {{"bezier", "--control", "[[0,0],[1,1]]", "--weights", "[1,2,3]"}, 2, "one weight per point"},
      {{"bezier", "--control", "[[0,0],[1,x]]"}, 2, "column 11"},
      {{"bezier", "--control", "[[0,0],[1,1]"}, 2, "column"},
      {{"bezier", "--control", "[[0,0],[1,1/0]]"}, 2, "division by zero"},
      {{"bezier", "--control", "[[2,3],[2,3]]"}, 3, "constant"},
      {{"bezier", "--control", "[[0,0],[1,1]]", "--speed", "angular"}, 2, "unknown option"},
      {{"bezier", "--control", "[[0,0],[1,1],[2,0]]", "--max-degree", "1"}, 2, "control points"},
      {{"uniformity", "(t, t^2)", "--control", "[[0,0],[1,1]]"}, 2, "not both"},
      {{"uniformity"}, 2, "CURVE (or --control"},
      {{"uniformity", "(t, t^2)", "--weights", "[1,2]"}, 2, "--weights needs --control"},
      {{"radical", "--control", "[[0,0],[1,1]]", "--weights", "[0,1]"}, 2, "positive"},
  };
  for (const auto& c : cases) {
    auto r = run_uniparam(c.args);
    std::string all;
    for (const auto& a : c.args) all += a + " ";
    EXPECT_EQ(r.exit_code, c.exit_code) << all << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << all << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << all;
  }
}
