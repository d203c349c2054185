// Hostile input to the uniparam command: every row of the table below is a
// command line with the exit code and a fragment of the error message it
// must give (docs/robustness.md). Exit codes: 0 ok, 2 invalid input or
// option, 3 not regular / undefined, 4 a budget exceeded (the message names
// the option that raises it).
//
// To cover a new command or option, append rows to hostile_rows(); rows
// that any command must pass (unknown option, --help, ...) are generated for
// every command listed by `uniparam --help`, so new commands get them for
// free.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"

using uniparam::test_support::run_uniparam;

namespace {

struct HostileRow {
  std::vector<std::string> args;
  int exit_code;
  /// A fragment stderr must contain ("" for exit code 0: stderr must be empty).
  std::string message;
};

const char* const kCubic = "(t, t^3)";

std::vector<HostileRow> hostile_rows() {
  const std::string long_sum = [] {  // 100 KB: a single argument may not exceed 128 KiB
    std::string s = "(t, t";
    while (s.size() < 100000) s += "+t";
    return s + ")";
  }();
  return {
      // ---- commands, options and arguments --------------------------------------
      {{}, 2, "usage: uniparam"},
      {{"frobnicate", kCubic}, 2, "unknown command 'frobnicate'"},
      {{"--frobnicate"}, 2, "unknown command"},
      {{"uniformity"}, 2, "expects CURVE (or --control, --svg, --nurbs), got 0"},
      {{"uniformity", kCubic, "(t, t)"}, 2, "expects CURVE (or --control, --svg, --nurbs), got 2"},
      {{"uniformity", kCubic, "--digits", "-3"}, 2, "--digits must be between 1 and 2000, got -3"},
      {{"uniformity", kCubic, "--digits", "0"}, 2, "--digits must be between"},
      {{"uniformity", kCubic, "--digits", "2001"}, 2, "--digits must be between"},
      {{"uniformity", kCubic, "--digits", "abc"}, 2, "--digits expects an integer, got 'abc'"},
      {{"uniformity", kCubic, "--digits", "1e3"}, 2, "--digits expects an integer"},
      {{"uniformity", kCubic, "--digits", ""}, 2, "--digits expects an integer"},
      {{"uniformity", kCubic, "--digits", "99999999999999999999999"}, 2, "--digits expects an integer"},
      {{"uniformity", kCubic, "--digits"}, 2, "option '--digits' needs a value"},
      {{"uniformity", kCubic, "--json=yes"}, 2, "option '--json' takes no value"},
      {{"uniformity", kCubic, "--speed", "fast"}, 2, "unknown speed"},
      {{"uniformity", kCubic, "--max-prec", "10"}, 2, "--max-prec must be between"},
      {{"uniformity", kCubic, "--max-degree", "0"}, 2, "--max-degree must be between"},
      {{"uniformity", kCubic, "--max-bits", "many"}, 2, "--max-bits expects an integer"},
      {{"uniformity", kCubic, "--max-length", "-1"}, 2, "--max-length must be between"},
      {{"uniformity", kCubic, "--max-depth", "0"}, 2, "--max-depth must be between"},
      {{"uniformity", kCubic, "--timeout", "0"}, 2, "--timeout must be above 0"},
      {{"uniformity", kCubic, "--timeout", "-5"}, 2, "--timeout must be above 0"},
      {{"uniformity", kCubic, "--timeout", "1e10"}, 2, "--timeout must be above 0 and at most 1e9"},
      {{"uniformity", kCubic, "--timeout", "nan"}, 2, "--timeout expects a number of seconds"},
      {{"uniformity", kCubic, "--timeout", "inf"}, 2, "--timeout expects a number of seconds"},
      {{"uniformity", kCubic, "--timeout", "10s"}, 2, "--timeout expects a number of seconds"},
      {{"radical", kCubic, "--format", "pdf"}, 2, "unknown format 'pdf'"},
      {{"radical", kCubic, "--at", "3/2"}, 2, "--at must lie in [0, 1]"},
      {{"radical", kCubic, "--at", "-1/2"}, 2, "--at must lie in [0, 1]"},
      {{"radical", kCubic, "--at", "x"}, 2, "--at: 'x' is not a rational number"},
      {{"radical", kCubic, "--at", "1/0"}, 2, "--at: '1/0' is not a rational number"},
      {{"radical", kCubic, "--at", "1e-99999"}, 2, "--at: the number '1e-99999' is too large"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,1/2,1/3,1"}, 2, "strictly increasing"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,1/2,1/2,1"}, 2, "strictly increasing"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,2,1"}, 2, "strictly increasing"},
      {{"moebius", "(t, t^2)", "--breakpoints", "1/2,1"}, 2, "must start at 0 and end at 1"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,1/2"}, 2, "must start at 0 and end at 1"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0"}, 2, "breakpoints"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,,1"}, 2, "--breakpoints: empty entry"},
      {{"moebius", "(t, t^2)", "--breakpoints", ""}, 2, "--breakpoints: empty entry"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,x,1"}, 2, "--breakpoints: 'x' is not a rational number"},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,1/0,1"}, 2, "--breakpoints: '1/0' is not a rational"},

      // ---- malformed curves: exit 2, with the column -----------------------------
      {{"uniformity", "(t, t^3"}, 2, "column 8: missing ')' to close the '(' at column 1"},
      {{"uniformity", "((t, t)"}, 2, "column 4: unexpected ','"},
      {{"uniformity", "(t, t))"}, 2, "column 7: unexpected ')'"},
      {{"uniformity", "(t, t)("}, 2, "after the closing ')'"},
      {{"uniformity", "(t, (t+1)"}, 2, "missing ')'"},
      {{"uniformity", "(t, t+)"}, 2, "column 7: unexpected ')' (expected a number, 't' or '(')"},
      {{"uniformity", "(t, *t)"}, 2, "column 5: unexpected '*'"},
      {{"uniformity", "(t, t**2)"}, 2, "write powers with '^'"},
      {{"uniformity", "(t, t^)"}, 2, "expected an integer exponent"},
      {{"uniformity", "(t, 2 3)"}, 2, "unexpected number '3'"},
      {{"uniformity", "(t, x)"}, 2, "unknown symbol 'x'"},
      {{"uniformity", "(s, s^2)"}, 2, "unknown symbol 's'"},
      {{"uniformity", "(t, sin(t))"}, 2, "unknown function 'sin'"},
      {{"uniformity", "(t, exp(t))"}, 2, "unknown function 'exp'"},
      {{"uniformity", "(t, )"}, 2, "column 5: empty component"},
      {{"uniformity", "(, t)"}, 2, "column 2: empty component"},
      {{"uniformity", "()"}, 2, "empty component"},
      {{"uniformity", ""}, 2, "empty input"},
      {{"uniformity", "   "}, 2, "empty input"},
      {{"uniformity", "t, t^2"}, 2, "a curve is written as a tuple"},
      {{"uniformity", "(t)"}, 2, "at least two components, got 1"},
      {{"uniformity", "(t, t^3) trailing"}, 2, "after the closing ')'"},
      {{"uniformity", "(t, t^1.5)"}, 2, "the exponent must be an integer"},
      {{"uniformity", "(t, t^t)"}, 2, "exponents must be integer constants"},
      {{"uniformity", "(t, 1.)"}, 2, "incomplete number"},
      {{"uniformity", "(t, [t])"}, 2, "use '(' for grouping"},
      {{"uniformity", "(t, \xff\xfe)"}, 2, "non-ASCII byte 0xFF"},
      {{"uniformity", "(t, \xc3\xa9)"}, 2, "non-ASCII byte 0xC3"},
      {{"uniformity", "(t,\x01t)"}, 2, "invalid control character 0x01"},
      {{"uniformity", "(t, t; t)"}, 2, "unexpected character ';'"},
      {{"uniformity", "(t, t^3)\x7f"}, 2, "invalid control character 0x7F"},

      // ---- undefined mathematics: exit 3, naming the parameter -------------------
      {{"uniformity", "(t, 1/0)"}, 3, "division by zero"},
      {{"uniformity", "(t, 1/(t-t))"}, 3, "division by zero"},
      {{"uniformity", "(t, 0^-1)"}, 3, "division by zero"},
      {{"uniformity", "(1/(t-1/2), t)"}, 3, "pole in [0, 1]: component 1 is infinite at t = 1/2"},
      {{"uniformity", "(t, 1/t)"}, 3, "component 2 is infinite at t = 0"},
      {{"uniformity", "(t, 1/(t-1))"}, 3, "component 2 is infinite at t = 1"},
      {{"uniformity", "(1/(2t^2-1), t)"}, 3, "infinite at t = root of 2*t^2 - 1"},
      {{"uniformity", "(1/(2t^2-1), t)"}, 3, "t ~ 0.7071067812"},
      {{"radical", "(t, 1/(1000000t^2-1))"}, 3, "t ~ 0.001"},
      {{"uniformity", "(1, 2)"}, 3, "the curve is constant"},
      {{"uniformity", "(t-t, (t+1)^2 - t^2 - 2t)"}, 3, "the curve is constant"},
      {{"radical", "(1/2, 3/4, 5)"}, 3, "the curve is constant"},
      {{"moebius", "(t^2/t, t^3/t^2)"}, 0, ""},  // removable: t and t, a line

      // ---- budgets: exit 4, naming the limit and its option ----------------------
      {{"uniformity", "(t, t^100000)"}, 4, "exponent limit of 1000 (raise it with --max-degree)"},
      {{"uniformity", "(t, t^3)", "--max-degree", "2"}, 4, "exponent limit of 2 (raise it with --max-degree)"},
      {{"uniformity", "(t, t*t*t)", "--max-degree", "2"}, 4, "degree limit of 2 (raise it with --max-degree)"},
      {{"uniformity", "(t, t^800*t^800)"}, 4, "degree limit of 1000 (raise it with --max-degree)"},
      {{"uniformity", "(t, t^2^2^2^2^2)"}, 4, "--max-degree"},
      {{"uniformity", "(t, 1e999999999)"}, 4, "size limit of 268435456 bits (raise it with --max-bits)"},
      {{"uniformity", "(t, (99999t+1)^200)", "--max-bits", "1000"}, 4, "size limit of 1000 bits (raise it with --max-bits)"},
      {{"uniformity", long_sum, "--max-length", "50000"}, 4, "length limit of 50000 (raise it with --max-length)"},
      {{"uniformity", "(t, ((((t)))))", "--max-depth", "3"}, 4, "depth limit of 3 (raise it with --max-depth)"},
      {{"uniformity", "(t, ----t)", "--max-depth", "3"}, 4, "--max-depth"},
      {{"uniformity", kCubic, "--digits", "30", "--max-prec", "64"}, 4, "precision limit of 64 bits (raise it with --max-prec)"},
      {{"uniformity", kCubic, "--digits", "2000", "--max-prec", "4096"}, 4, "(raise it with --max-prec)"},
      {{"radical", kCubic, "--digits", "30", "--max-prec", "100"}, 4, "--max-prec"},
      {{"moebius", kCubic, "--digits", "30", "--max-prec", "100"}, 4, "--max-prec"},
      {{"uniformity", kCubic, "--timeout", "0.000001"}, 4, "within 1e-06 s (raise it with --timeout SECONDS)"},
      {{"radical", kCubic, "--timeout", "0.000001"}, 4, "--timeout"},
      {{"moebius", kCubic, "--timeout", "0.000001"}, 4, "--timeout"},
      // Minutes of uninterruptible Gauss-Legendre node computation inside Arb:
      // the CLI's watchdog still stops it shortly after the deadline.
      {{"uniformity", kCubic, "--digits", "2000", "--timeout", "0.5"}, 4, "--timeout"},

      // ---- reparam: the piecewise Moebius methods ---------------------------------
      {{"reparam", kCubic}, 2, "exactly one of --pieces N, --breakpoints LIST, --target U"},
      {{"reparam", kCubic, "--pieces", "3", "--target", "0.9"}, 2, "exactly one of"},
      {{"reparam", kCubic, "--pieces", "0"}, 2, "--pieces must be between 1 and 1000, got 0"},
      {{"reparam", kCubic, "--pieces", "-1"}, 2, "--pieces must be between"},
      {{"reparam", kCubic, "--pieces", "abc"}, 2, "--pieces expects an integer"},
      {{"reparam", kCubic, "--pieces", "1e3"}, 2, "--pieces expects an integer"},
      {{"reparam", kCubic, "--pieces", "1001"}, 2, "--pieces must be between"},
      {{"reparam", kCubic, "--target", "1.5"}, 2, "--target must lie strictly between 0 and 1"},
      {{"reparam", kCubic, "--target", "0"}, 2, "--target must lie strictly between 0 and 1"},
      {{"reparam", kCubic, "--target", "-0.1"}, 2, "--target must lie strictly between 0 and 1"},
      {{"reparam", kCubic, "--target", "abc"}, 2, "--target: 'abc' is not a rational number"},
      {{"reparam", kCubic, "--target", "1/0"}, 2, "--target"},
      {{"reparam", kCubic, "--target", "0.9", "--max-pieces", "0"}, 2, "--max-pieces must be between"},
      {{"reparam", kCubic, "--breakpoints", "0,1/2"}, 2, "breakpoints"},
      {{"reparam", kCubic, "--breakpoints", "0,2/3,1/3,1"}, 2, "increasing"},
      {{"reparam", kCubic, "--pieces", "2", "--rational-digits", "0", "--rational"}, 2, "--rational-digits"},
      {{"reparam", kCubic, "--pieces", "2", "--rational-digits", "4"}, 2, "--rational-digits needs --rational"},
      // ---- bezier ------------------------------------------------------------------
      {{"bezier"}, 2, "--control"},
      {{"bezier", "--control", "[[0,0]]"}, 2, "needs at least 2 control points"},
      {{"bezier", "--control", "[[0,0],[1,2,3]]"}, 2, "dimension"},
      {{"bezier", "--control", "[[0,0],[1,2]]", "--weights", "[1,0]"}, 2, "positive"},
      {{"bezier", "--control", "[[0,0],[1,2]]", "--weights", "[1,-2]"}, 2, "positive"},
      {{"bezier", "--control", "[[0,0],[1,2]]", "--weights", "[1,2,3]"}, 2, "weights"},
      {{"bezier", "--control", "[[0,0],[1,x]]"}, 2, "column"},
      {{"uniformity", kCubic, "--weights", "[1,2]"}, 2, "--weights needs --control"},

      // ---- hard but valid: exit 0, nothing on stderr -----------------------------
      {{"uniformity", long_sum}, 0, ""},
      {{"uniformity", "(t, 2t)"}, 0, ""},
      {{"radical", "(t^2, t^3)"}, 0, ""},
      {{"radical", "(t^2, t^3)", "--speed", "parametric"}, 0, ""},
      {{"moebius", "(t, t^2)", "--breakpoints", "0,1e-30,2e-30,1"}, 0, ""},
      {{"radical", kCubic, "--at", "1e-999"}, 0, ""},
      {{"radical", "(t, (t-1)^3)", "--at", "1"}, 0, ""},  // zero of the speed at t = 1, z = 1 exactly
      {{"radical", "(t, t^3 (1-t)^3)", "--at", "1", "--digits", "40"}, 0, ""},
      {{"uniformity", "(t^2/t, t^3/t^2)", "--speed", "parametric"}, 0, ""},
  };
}

// The command names listed by `uniparam --help` (the lines after "commands:").
std::vector<std::string> listed_commands() {
  std::vector<std::string> names;
  std::istringstream in(run_uniparam({"--help"}).out);
  std::string line;
  bool in_list = false;
  while (std::getline(in, line)) {
    if (line == "commands:") { in_list = true; continue; }
    if (!in_list) continue;
    if (line.empty()) break;
    // "  name ARGS   description"; continuation lines are indented further
    if (line.size() < 3 || line.compare(0, 2, "  ") != 0 || line[2] == ' ') continue;
    std::istringstream words(line);
    std::string name;
    if (words >> name) names.push_back(name);
  }
  return names;
}

void check_row(const HostileRow& row) {
  std::string shown;
  for (const auto& a : row.args) shown += " '" + (a.size() > 60 ? a.substr(0, 60) + "...'" : a + "'");
  SCOPED_TRACE("uniparam" + shown);
  const auto r = run_uniparam(row.args);
  EXPECT_EQ(r.exit_code, row.exit_code) << "stderr: " << r.err;
  if (row.exit_code == 0) {
    EXPECT_TRUE(r.err.empty()) << r.err;
    EXPECT_FALSE(r.out.empty());
    return;
  }
  EXPECT_NE(r.err.find(row.message), std::string::npos) << "stderr: " << r.err;
  // One clear line, no partial result, no sanitizer or crash report.
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("ERROR:"), std::string::npos) << r.err;
  if (!row.args.empty()) EXPECT_TRUE(r.out.empty()) << "partial output: " << r.out.substr(0, 200);
}

}  // namespace

TEST(Hostile, EveryRowGivesItsExitCodeAndMessage) {
  for (const auto& row : hostile_rows()) check_row(row);
}

TEST(Hostile, EveryCommandRejectsBadOptionsAndHasHelp) {
  const auto names = listed_commands();
  ASSERT_GE(names.size(), 3u) << "could not read the command list from uniparam --help";
  for (const auto& cmd : names) {
    // batch hands its options to the command it runs (Batch.* in test_composite_cli.cpp)
    if (cmd == "batch") continue;
    check_row({{cmd, "--bogus"}, 2, "unknown option '--bogus' for 'uniparam " + cmd + "'"});
    check_row({{cmd, "--timeout"}, 2, "option '--timeout' needs a value"});
    const auto help = run_uniparam({cmd, "--help"});
    EXPECT_EQ(help.exit_code, 0) << cmd;
    // --json and --digits where the command has them ('plot' draws, it has neither)
    if (help.out.find("--json") != std::string::npos)
      check_row({{cmd, "--json=1"}, 2, "option '--json' takes no value"});
    if (help.out.find("--digits") != std::string::npos)
      check_row({{cmd, "--digits"}, 2, "option '--digits' needs a value"});
    for (const char* opt : {"--max-prec", "--max-degree", "--max-bits", "--max-length", "--max-depth", "--timeout"})
      EXPECT_NE(help.out.find(opt), std::string::npos) << cmd << " --help does not list " << opt;
  }
}
