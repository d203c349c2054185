// `uniparam reparam` (and the Moebius output options): the JSON contract of
// the piecewise Moebius methods, the exact C1 condition read back from the
// printed rationals, the exit status of an unreached target, and bad options.
#include <gtest/gtest.h>

#include <regex>
#include <string>
#include <vector>

#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Rational;
using uniparam::test_support::run_uniparam;

namespace {

const char* kSlide =
    "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";

// The "exact" rationals of the array under `key` (top level), in order.
std::vector<Rational> exact_array(const std::string& json, const std::string& key) {
  const std::size_t start = json.find("\"" + key + "\": [");
  if (start == std::string::npos) return {};
  // the array ends at the first "]" at nesting depth 0 after its "["
  std::size_t i = json.find('[', start), depth = 0, end = i;
  for (; end < json.size(); ++end) {
    if (json[end] == '[') ++depth;
    if (json[end] == ']' && --depth == 0) break;
  }
  const std::string body = json.substr(i, end - i);
  std::vector<Rational> out;
  std::regex re("\"exact\": \"([^\"]+)\"");
  for (std::sregex_iterator it(body.begin(), body.end(), re), e; it != e; ++it) out.push_back(Rational::parse((*it)[1]));
  return out;
}

Rational mid_of(const std::string& json, const std::string& key) {
  std::regex re("\"" + key + "\": \\{\\s*\"mid\": \"([^\"]+)\"");
  std::smatch m;
  if (!std::regex_search(json, m, re)) return Rational(-1);
  return Rational::parse(m[1]);
}

}  // namespace

TEST(CliReparam, PiecesGivesAnOptimisedC0MapAtLeastAsGoodAsEqualSpacing) {
  auto r = run_uniparam({"reparam", kSlide, "--pieces", "3", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"t\"", "\"s\"", "\"alpha\"", "\"mu\"", "\"u_before\"", "\"u_after\"", "\"continuity\": \"C0\"",
                          "\"pieces\"", "\"optimiser\"", "\"stationarity\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  auto eq = run_uniparam({"reparam", kSlide, "--breakpoints", "0,1/3,2/3,1", "--json"});
  ASSERT_EQ(eq.exit_code, 0) << eq.err;
  EXPECT_GE(mid_of(r.out, "u_after"), mid_of(eq.out, "u_after"));
  EXPECT_GT(mid_of(r.out, "u_after"), mid_of(r.out, "u_before"));
}

TEST(CliReparam, TargetWithRationalOutputIsExactlyC1) {
  auto r = run_uniparam({"reparam", kSlide, "--target", "0.99", "--rational", "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"continuity\": \"C1\""), std::string::npos);
  EXPECT_NE(r.out.find("\"reached\": true"), std::string::npos);
  const auto t = exact_array(r.out, "t"), s = exact_array(r.out, "s"), a = exact_array(r.out, "alpha");
  ASSERT_GE(t.size(), 3u);
  ASSERT_EQ(s.size(), t.size());
  ASSERT_EQ(a.size(), t.size() - 1);
  EXPECT_GE(mid_of(r.out, "u_after"), Rational(99, 100));
  for (std::size_t i = 0; i + 2 < t.size(); ++i) {
    // r'(s_{i+1}-) = (dt_i/ds_i) a_i/(1-a_i) equals r'(s_{i+1}+) = (dt_{i+1}/ds_{i+1}) (1-a_{i+1})/a_{i+1}
    const Rational left = (t[i + 1] - t[i]) / (s[i + 1] - s[i]) * a[i] / (Rational(1) - a[i]);
    const Rational right = (t[i + 2] - t[i + 1]) / (s[i + 2] - s[i + 1]) * (Rational(1) - a[i + 1]) / a[i + 1];
    EXPECT_EQ(left, right) << "joint " << i + 1;
  }
  // the printed formulas are exact
  EXPECT_EQ(r.out.find("\"exact\": false"), std::string::npos);
}

TEST(CliReparam, UnreachedTargetPrintsTheBestMapAndExitsWithFour) {
  auto r = run_uniparam({"reparam", kSlide, "--target", "0.9999999", "--max-pieces", "2"});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.out.find("NOT reached"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("--max-pieces"), std::string::npos) << r.err;
}

// Must show: sample and plot with an unreached C1 target say what reparam
// says (the same advice, the map "used" instead of "printed"), not a
// message of their own.
TEST(CliReparam, UnreachedTargetMessageIsTheSameForSampleAndPlot) {
  const auto r = run_uniparam({"reparam", kSlide, "--target", "0.9999999", "--max-pieces", "2"});
  ASSERT_EQ(r.exit_code, 4);
  const std::string line = r.err.substr(r.err.find(": ") + 2);
  for (const char* command : {"sample", "plot"}) {
    std::vector<std::string> args{command, kSlide, "--method", "c1", "--target", "0.9999999", "--max-pieces", "2"};
    if (std::string(command) == "plot") args.insert(args.end(), {"-o", "-"});
    const auto s = run_uniparam(args);
    EXPECT_EQ(s.exit_code, 4) << command;
    std::string expected = line;
    expected.replace(expected.find("is printed"), 10, "is used");
    EXPECT_NE(s.err.find(expected), std::string::npos) << command << ": " << s.err << " vs " << expected;
  }
}

TEST(CliReparam, FormulasInEveryFormat) {
  auto latex = run_uniparam({"reparam", "(t, t^2)", "--pieces", "2", "--rational", "--format", "latex"});
  ASSERT_EQ(latex.exit_code, 0) << latex.err;
  EXPECT_NE(latex.out.find("\\frac{"), std::string::npos);
  auto maple = run_uniparam({"moebius", "(t, t^2)", "--format", "maple"});
  ASSERT_EQ(maple.exit_code, 0) << maple.err;
  EXPECT_NE(maple.out.find("t = ("), std::string::npos);
  auto json = run_uniparam({"moebius", "(t, t^2)", "--format", "json"});
  ASSERT_EQ(json.exit_code, 0) << json.err;
  EXPECT_NE(json.out.find("\"alpha\""), std::string::npos);
}

TEST(CliReparam, BadOptionsAreRejectedWithExitTwo) {
  struct Case {
    std::vector<std::string> args;
    const char* message;
  };
  const std::vector<Case> cases = {
      {{"reparam", "(t, t^2)"}, "exactly one of"},
      {{"reparam", "(t, t^2)", "--pieces", "2", "--target", "0.9"}, "exactly one of"},
      {{"reparam", "(t, t^2)", "--pieces", "0"}, "--pieces"},
      {{"reparam", "(t, t^2)", "--pieces", "x"}, "--pieces"},
      {{"reparam", "(t, t^2)", "--target", "1.5"}, "--target"},
      {{"reparam", "(t, t^2)", "--target", "0"}, "--target"},
      {{"reparam", "(t, t^2)", "--breakpoints", "0,1/2,1/3,1"}, "increasing"},
      {{"reparam", "(t, t^2)", "--pieces", "2", "--rational-digits", "5"}, "--rational"},
      {{"reparam", "(t, t^2)", "--pieces", "2", "--max-pieces", "5"}, "--target"},
      {{"reparam", "(t, t^2)", "--pieces", "2", "--format", "svg"}, "format"},
  };
  for (const auto& c : cases) {
    auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args.back() << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args.back() << ": " << r.err;
    EXPECT_TRUE(r.out.empty());
  }
}

TEST(CliFormats, FormatJsonIsTheJsonOutputOnEveryFormulaCommand) {
  const std::vector<std::vector<std::string>> commands = {
      {"radical", "(t, t^3)"},
      {"moebius", "(t, t^2)"},
      {"reparam", "(t, t^2)", "--pieces", "2"},
      {"bezier", "--control", "[[0,0],[1,2],[3,1]]"},
  };
  for (const auto& base : commands) {
    auto with_format = base, with_flag = base;
    with_format.insert(with_format.end(), {"--format", "json"});
    with_flag.push_back("--json");
    auto a = run_uniparam(with_format), b = run_uniparam(with_flag);
    ASSERT_EQ(a.exit_code, 0) << base[0] << ": " << a.err;
    EXPECT_EQ(a.out, b.out) << base[0];
    EXPECT_EQ(a.out.rfind("{", 0), 0u) << base[0];
  }
}
