// The uniparam command: exit codes, messages and the JSON contract.
#include <gtest/gtest.h>

#include <regex>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::test_support::encloses;
using uniparam::test_support::run_uniparam;

TEST(Cli, UniformityJsonMeetsTheCertifiedRealContract) {
  for (long digits : {5L, 15L, 30L}) {
    auto r = run_uniparam({"uniformity", "(t, t^3)", "--json", "--digits", std::to_string(digits)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(encloses(r.out, "u", "0.845695243153366341883011346954", "1e-30", digits));
    // mu > 1: the radius bound scales with |mid|, so check it against 10^-(digits-1).
    EXPECT_TRUE(encloses(r.out, "mu", "1.249045772398254425829917077281", "1e-30", digits - 1));
  }
}

// Text output: each ball is "MID +/- RAD", MID with D + 3 significant digits;
// only the ball is certified (rad <= 10^-D for u < 1), so the test checks
// that it holds the true value, not the digits of MID beyond it.
TEST(Cli, TextOutputNamesZerosAndUniformity) {
  auto r = run_uniparam({"uniformity", "(t, t^3)"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("t = 0, multiplicity 1"), std::string::npos) << r.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex("\\nu +(0\\.([0-9]+)) \\+/- ([0-9.e+-]+)\\n"))) << r.out;
  const uniparam::Rational mid = uniparam::Rational::parse(m[1]), rad = uniparam::Rational::parse(m[3]),
                           ref = uniparam::Rational::parse("0.845695243153366341883011346954"),
                           slack = uniparam::Rational::parse("1e-30");
  EXPECT_LE(mid - rad - slack, ref) << r.out;
  EXPECT_GE(mid + rad + slack, ref) << r.out;
  EXPECT_LE(rad, uniparam::Rational::parse("1e-15")) << r.out;  // the default --digits 15
  EXPECT_EQ(std::string(m[2]).size(), 18u) << "D + 3 significant digits: " << r.out;
}

TEST(Cli, HelpIsAvailableForEveryCommand) {
  auto r = run_uniparam({"--help"});
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("uniformity"), std::string::npos);
  auto u = run_uniparam({"uniformity", "--help"});
  EXPECT_EQ(u.exit_code, 0);
  for (const char* opt : {"--speed", "--digits", "--json", "--max-prec"})
    EXPECT_NE(u.out.find(opt), std::string::npos) << opt;
}

struct BadInput {
  std::vector<std::string> args;
  int exit_code;
  const char* message;  // a fragment the error message must contain
};

TEST(Cli, BadInputGivesClearErrorAndNonZeroExit) {
  const BadInput cases[] = {
      {{"frobnicate"}, 2, "unknown command"},
      {{"uniformity"}, 2, "expects CURVE"},
      {{"uniformity", "(t, t^3"}, 2, "column"},
      {{"uniformity", "(t, x)"}, 2, "'x'"},
      {{"uniformity", "(t, t^3)", "--digits", "-3"}, 2, "--digits"},
      {{"uniformity", "(t, t^3)", "--digits", "abc"}, 2, "--digits"},
      {{"uniformity", "(t, t^3)", "--speed", "fast"}, 2, "unknown speed"},
      {{"uniformity", "(t, t^3)", "--bogus"}, 2, "unknown option"},
      {{"uniformity", "(t)"}, 2, "two components"},
      {{"uniformity", "(1/(t-1/2), t)"}, 3, "pole"},
      {{"uniformity", "(1, 2)"}, 3, "constant"},
      {{"uniformity", "(t, 1/0)"}, 3, "division by zero"},
  };
  for (const auto& c : cases) {
    auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, c.exit_code) << c.args.back() << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args.back() << ": " << r.err;
    EXPECT_TRUE(r.out.empty()) << "no partial result on error: " << r.out;
  }
}

TEST(Cli, RadicalJsonHasEveryKeyAndContainsTheReferenceValues) {
  auto r = run_uniparam({"radical", "(t, t^3)", "--json", "--digits", "30", "--at", "1/2"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"t\"", "\"multiplicity\"", "\"s\"", "\"z\"", "\"alpha\"", "\"L\"", "\"A\"", "\"B\"", "\"C\"",
                          "\"M\"", "\"mu\"", "\"u_before\"", "\"u_radical\"", "\"u_after\"", "\"pieces\"", "\"phi\"",
                          "\"m\"", "\"r\"", "\"p_r\"", "\"at\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  EXPECT_TRUE(encloses(r.out, "u_after", "0.996507782374800406168303796755", "1e-30", 30));
}

TEST(Cli, RadicalFormatsAndErrors) {
  auto latex = run_uniparam({"radical", "(t, t^3)", "--format", "latex"});
  ASSERT_EQ(latex.exit_code, 0) << latex.err;
  EXPECT_NE(latex.out.find("\\sqrt{"), std::string::npos);
  auto maple = run_uniparam({"radical", "(t, t^3)", "--format", "maple"});
  ASSERT_EQ(maple.exit_code, 0) << maple.err;
  EXPECT_NE(maple.out.find("^(1/2)"), std::string::npos);
  auto bad = run_uniparam({"radical", "(t, t^3)", "--format", "pdf"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("unknown format"), std::string::npos);
  auto at = run_uniparam({"radical", "(t, t^3)", "--at", "3/2"});
  EXPECT_EQ(at.exit_code, 2);
  auto param = run_uniparam({"radical", "(t^2, t^3)", "--speed", "parametric"});
  EXPECT_EQ(param.exit_code, 0) << param.err;
  EXPECT_NE(param.out.find("mult       (1, 0"), std::string::npos) << param.out;
}

TEST(Cli, MoebiusOptimalAlphaOfTheQuarterCircleIsTwoMinusSqrtTwo) {
  auto r = run_uniparam({"moebius", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "--json", "--digits", "20"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* key : {"\"alpha\"", "\"mu\"", "\"u_before\"", "\"u_after\"", "\"continuity\""})
    EXPECT_NE(r.out.find(key), std::string::npos) << key;
  EXPECT_TRUE(encloses(r.out, "u_after", "0.9977912002415711604419615", "1e-25", 20));
  auto bad = run_uniparam({"moebius", "(t, t^2)", "--breakpoints", "0,1/2,1/3,1"});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("increasing"), std::string::npos) << bad.err;
}
