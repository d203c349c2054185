// --output nurbs | step | FILE.stp of moebius, reparam and bezier; radical
// refuses. The exact JSON strings are read back and the NURBS they define is
// evaluated exactly (de Boor) against p(r(s)) from the map the same command
// prints with --json.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <regex>
#include <set>
#include <sstream>

#include "support/de_boor.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::run_uniparam;

namespace {

// The text of the JSON array that follows "key": (matching brackets).
std::string section(const std::string& j, const std::string& key) {
  const std::size_t k = j.find("\"" + key + "\": [");
  if (k == std::string::npos) return "";
  std::size_t i = j.find('[', k);
  const std::size_t start = i;
  int depth = 0;
  for (; i < j.size(); ++i) {
    if (j[i] == '[') ++depth;
    if (j[i] == ']' && --depth == 0) break;
  }
  return j.substr(start, i - start + 1);
}

// Every "exact": "p/q" string of a text, read as rationals.
std::vector<Rational> exacts(const std::string& text) {
  std::vector<Rational> out;
  static const std::regex re("\"exact\": \"([^\"]*)\"");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), re); it != std::sregex_iterator(); ++it)
    out.push_back(Rational::parse((*it)[1].str()));
  return out;
}

long json_long(const std::string& j, const std::string& key) {
  const std::size_t k = j.find("\"" + key + "\": ");
  EXPECT_NE(k, std::string::npos) << key;
  return std::atol(j.c_str() + k + key.size() + 4);
}

struct ExactNurbs {
  long degree, dim;
  std::vector<Rational> knots, weights;
  std::vector<std::vector<Rational>> points;
};

ExactNurbs read_exact(const std::string& j) {
  ExactNurbs n;
  n.degree = json_long(j, "degree");
  n.dim = json_long(j, "dimension");
  n.knots = exacts(section(j, "knots"));
  n.weights = exacts(section(j, "weights"));
  const std::vector<Rational> flat = exacts(section(j, "control_points"));
  for (std::size_t i = 0; i + n.dim <= flat.size(); i += n.dim)
    n.points.emplace_back(flat.begin() + i, flat.begin() + i + n.dim);
  return n;
}

std::vector<Rational> de_boor(const ExactNurbs& n, const Rational& s) {
  return test_support::de_boor(n.degree, n.knots, n.points, n.weights, s);
}

// The exact map of `--rational --json` and the curve; checks the NURBS of
// `--output nurbs` (same arguments) against p(r(s)) at random rational s.
void check_round_trip(const std::vector<std::string>& args) {
  auto report_args = args;
  report_args.push_back("--json");
  const auto rep = run_uniparam(report_args);
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  auto nurbs_args = args;
  nurbs_args.push_back("--output");
  nurbs_args.push_back("nurbs");
  const auto out = run_uniparam(nurbs_args);
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_NE(out.out.find("\"kind\": \"rational\""), std::string::npos);
  const ExactNurbs n = read_exact(out.out);
  ASSERT_EQ(n.points.size(), n.weights.size());
  ASSERT_EQ(n.knots.size(), n.points.size() + static_cast<std::size_t>(n.degree) + 1);
  for (const auto& w : n.weights) EXPECT_GT(w.sign(), 0);

  const std::vector<Rational> T = exacts(section(rep.out, "t"));
  const std::vector<Rational> S = exacts(section(rep.out, "s"));
  const std::vector<Rational> A = exacts(section(rep.out, "alpha"));
  ASSERT_EQ(T.size(), S.size());
  ASSERT_EQ(A.size() + 1, S.size());
  const Curve c = Curve::parse(args[1]);
  std::mt19937_64 rng(38);
  std::uniform_int_distribution<long> num(0, 1000);
  std::vector<Rational> ss = S;
  for (int k = 0; k < 12; ++k) ss.push_back(Rational(num(rng), 1000));
  for (const Rational& s : ss) {
    std::size_t i = 0;
    while (i + 1 < A.size() && s > S[i + 1]) ++i;
    const Rational u = (s - S[i]) / (S[i + 1] - S[i]);
    const Rational q = (Rational(1) - A[i]) * u;
    const Rational t = T[i] + (T[i + 1] - T[i]) * q / (q + A[i] * (Rational(1) - u));
    const std::vector<Rational> v = de_boor(n, s);
    ASSERT_EQ(v.size(), c.dimension());
    for (std::size_t k = 0; k < c.dimension(); ++k) EXPECT_EQ(v[k], c.components()[k](t)) << "s = " << s.str();
  }
}

}  // namespace

TEST(NurbsCli, RationalMoebiusJsonRoundTripsExactly) {
  check_round_trip({"moebius", "(t, t^3/(1+t^2))", "--breakpoints", "0,1/3,1", "--rational"});
  check_round_trip({"moebius", "((1-t^2)/(1+t^2), 2*t/(1+t^2), t)", "--rational", "--speed", "parametric"});
}

TEST(NurbsCli, RationalReparamJsonRoundTripsExactly) {
  check_round_trip({"reparam", "(t, t^3/(1+t^2))", "--pieces", "3", "--rational"});
  check_round_trip({"reparam", "((1-t^2)/(1+t^2), 2*t/(1+t^2))", "--target", "0.999", "--rational"});
  // negative Bernstein coefficients of the denominator: subdivided, still exact
  check_round_trip({"reparam", "(t/(t^2-t+3/10), 1/(t^2-t+3/10))", "--pieces", "2", "--rational"});
}

TEST(NurbsCli, BallJsonShape) {
  const auto r = run_uniparam({"reparam", "(t, t^3/(1+t^2))", "--pieces", "3", "--output", "nurbs"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"kind\": \"balls\""), std::string::npos);
  const long d = json_long(r.out, "degree");
  const long segs = json_long(r.out, "segments");
  const std::string w = section(r.out, "weights"), k = section(r.out, "knots");
  const std::regex ball("\\{\\s*\"mid\": \"[-0-9.e]+\",\\s*\"rad\": \"[-0-9.e]+\"");
  const auto count = [&](const std::string& t) {
    return std::distance(std::sregex_iterator(t.begin(), t.end(), ball), std::sregex_iterator());
  };
  EXPECT_EQ(count(w), segs * d + 1);
  EXPECT_EQ(count(k), segs * d + 1 + d + 1);
  EXPECT_EQ(count(section(r.out, "control_points")), 2 * (segs * d + 1));
}

TEST(NurbsCli, BezierIntegralWeightsAreTheExactSurds) {
  const std::string ctrl = "[[0,0],[1,2],[3,1],[4,4]]";
  const auto rep = run_uniparam({"bezier", "--control", ctrl, "--json"});
  const auto out = run_uniparam({"bezier", "--control", ctrl, "--output", "nurbs"});
  ASSERT_EQ(out.exit_code, 0) << out.err;
  EXPECT_NE(out.out.find("\"kind\": \"surd\""), std::string::npos);
  static const std::regex re("\"text\": \"([^\"]*)\"");
  auto texts = [&](const std::string& t) {
    std::vector<std::string> v;
    for (auto it = std::sregex_iterator(t.begin(), t.end(), re); it != std::sregex_iterator(); ++it)
      v.push_back((*it)[1].str());
    return v;
  };
  const auto a = texts(section(out.out, "weights"));
  EXPECT_EQ(a.size(), 4u);
  EXPECT_EQ(a, texts(section(rep.out, "weights")));
  EXPECT_NE(a[0].find("sqrt"), std::string::npos);
  // control points exactly the given ones
  const std::vector<Rational> p = exacts(section(out.out, "control_points"));
  const std::vector<Rational> expect{0, 0, 1, 2, 3, 1, 4, 4};
  EXPECT_EQ(p, expect);
}

TEST(NurbsCli, StepFileIsWellFormed) {
  const std::string curve = "(t/(t^2-t+3/10), 1/(t^2-t+3/10))";
  const auto js = run_uniparam({"reparam", curve, "--pieces", "2", "--output", "nurbs"});
  const auto st = run_uniparam({"reparam", curve, "--pieces", "2", "--output", "step"});
  ASSERT_EQ(st.exit_code, 0) << st.err;
  const std::string& s = st.out;
  EXPECT_EQ(s.rfind("ISO-10303-21;\n", 0), 0u);
  EXPECT_NE(s.find("FILE_SCHEMA(('AUTOMOTIVE_DESIGN"), std::string::npos);
  EXPECT_NE(s.find("B_SPLINE_CURVE_WITH_KNOTS("), std::string::npos);
  EXPECT_NE(s.find("RATIONAL_B_SPLINE_CURVE(("), std::string::npos);
  EXPECT_EQ(s.substr(s.size() - 18), "END-ISO-10303-21;\n");
  // every entity defined once, every reference defined, parentheses balanced
  std::set<long> defined, used;
  std::istringstream in(s.substr(s.find("DATA;\n") + 6));
  std::string line;
  const std::regex ref("#([0-9]+)");
  while (std::getline(in, line) && line != "ENDSEC;") {
    ASSERT_EQ(line[0], '#') << line;
    ASSERT_EQ(line.back(), ';') << line;
    const long id = std::atol(line.c_str() + 1);
    EXPECT_TRUE(defined.insert(id).second) << id;
    const std::string body = line.substr(line.find('='));
    for (auto it = std::sregex_iterator(body.begin(), body.end(), ref); it != std::sregex_iterator(); ++it)
      used.insert(std::stol((*it)[1].str()));
    int depth = 0;
    for (char c : line) {
      depth += c == '(' ? 1 : c == ')' ? -1 : 0;
      ASSERT_GE(depth, 0) << line;
    }
    EXPECT_EQ(depth, 0) << line;
  }
  for (long u : used) EXPECT_TRUE(defined.count(u)) << "#" << u << " used, not defined";
  // as many points and weights as the JSON, multiplicities summing to points + degree + 1
  const long d = json_long(js.out, "degree"), segs = json_long(js.out, "segments");
  long points = 0;
  for (std::size_t p = s.find("CARTESIAN_POINT"); p != std::string::npos; p = s.find("CARTESIAN_POINT", p + 1)) ++points;
  EXPECT_EQ(points, segs * d + 1);
  const std::size_t m = s.find("B_SPLINE_CURVE_WITH_KNOTS((") + 27;
  std::istringstream mult(s.substr(m, s.find(')', m) - m));
  long sum = 0;
  for (std::string x; std::getline(mult, x, ',');) sum += std::stol(x);
  EXPECT_EQ(sum, points + d + 1);
}

TEST(NurbsCli, StepFileOptionWritesTheFileAndKeepsTheReport) {
  char name[] = "/tmp/uniparam_nurbs_cli_XXXXXX";
  const int fd = mkstemp(name);
  close(fd);
  std::remove(name);
  const std::string path = std::string(name) + ".stp";
  const auto r = run_uniparam({"moebius", "(t, t^2)", "--output", path});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("u after"), std::string::npos);  // the usual report
  std::ifstream f(path);
  std::stringstream text;
  text << f.rdbuf();
  std::remove(path.c_str());
  const auto st = run_uniparam({"moebius", "(t, t^2)", "--output", "step"});
  const std::string base = path.substr(path.rfind('/') + 1);
  std::string expect = st.out;
  const std::size_t k = expect.find("'uniparam.stp'");
  ASSERT_NE(k, std::string::npos);
  expect.replace(k, 14, "'" + base + "'");
  EXPECT_EQ(text.str(), expect);
}

TEST(NurbsCli, RadicalIsRefusedWithAPointer) {
  const auto r = run_uniparam({"radical", "(t, t^3)", "--output", "nurbs"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("not rational"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sample --method exact"), std::string::npos) << r.err;
}

TEST(NurbsCli, BadOutputRequestsAreRefused) {
  EXPECT_EQ(run_uniparam({"moebius", "(t, t^2)", "--output", "iges"}).exit_code, 2);
  EXPECT_EQ(run_uniparam({"moebius", "(t, t^2)", "--output", "/nonexistent-dir/x.stp"}).exit_code, 2);
  const auto r = run_uniparam({"moebius", "(t, t^2, t^3, t^4)", "--output", "step"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_TRUE(r.out.empty());
  EXPECT_NE(r.err.find("STEP"), std::string::npos);
  EXPECT_EQ(run_uniparam({"moebius", "(t, t^2, t^3, t^4)", "--output", "nurbs"}).exit_code, 0);
}
