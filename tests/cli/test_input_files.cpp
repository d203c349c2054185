// CURVE, --control and --weights given as @FILE or as - (standard input):
// the same results as the inline text, bounded reads, and clear errors for
// missing files, directories, a bare '@', two values reading standard input
// and files over the length limit.
#include <gtest/gtest.h>

#include <unistd.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <vector>
#include <string>

#include "support/run.hpp"

using uniparam::test_support::RunResult;
using uniparam::test_support::run_uniparam;
using uniparam::test_support::shell_quote;

namespace {

// A scratch file holding `text`; removed at the end of the test.
class TempFile {
 public:
  explicit TempFile(const std::string& text) {
    char name[] = "/tmp/uniparam_input_XXXXXX";
    const int fd = mkstemp(name);
    if (fd >= 0) close(fd);
    path_ = name;
    std::ofstream(path_) << text;
  }
  ~TempFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// Runs uniparam with standard input read from `stdin_file`.
RunResult run_with_stdin(const std::vector<std::string>& args, const std::string& stdin_file) {
  const char* bin = std::getenv("UNIPARAM_BIN");
  std::string cmd = shell_quote(bin ? bin : "uniparam");
  for (const auto& x : args) cmd += " " + shell_quote(x);
  cmd += " < " + shell_quote(stdin_file);
  TempFile err("");
  cmd += " 2>" + shell_quote(err.path());
  RunResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  std::size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) r.out.append(buf, n);
  const int status = pclose(p);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream f(err.path());
  r.err.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
  return r;
}

const char* kCurve = "(t^2 - 1, t^3 + 2*t)";

TEST(InputFiles, CurveFromFileEqualsInline) {
  const TempFile f(std::string(kCurve) + "\n");
  const RunResult inline_run = run_uniparam({"uniformity", kCurve, "--json"});
  const RunResult file_run = run_uniparam({"uniformity", "@" + f.path(), "--json"});
  ASSERT_EQ(inline_run.exit_code, 0) << inline_run.err;
  EXPECT_EQ(file_run.exit_code, 0) << file_run.err;
  EXPECT_EQ(file_run.out, inline_run.out);
}

TEST(InputFiles, CurveFromStandardInputEqualsInline) {
  const TempFile f(kCurve);
  const RunResult inline_run = run_uniparam({"radical", kCurve, "--json"});
  const RunResult stdin_run = run_with_stdin({"radical", "-", "--json"}, f.path());
  ASSERT_EQ(inline_run.exit_code, 0) << inline_run.err;
  EXPECT_EQ(stdin_run.exit_code, 0) << stdin_run.err;
  EXPECT_EQ(stdin_run.out, inline_run.out);
}

TEST(InputFiles, ControlAndWeightsFromFiles) {
  const TempFile control("[[1,0],\n [1,1],\n [0,1]]\n");
  const TempFile weights("[1, 1, 2]");
  const RunResult inline_run = run_uniparam({"bezier", "--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,1,2]"});
  const RunResult file_run =
      run_uniparam({"bezier", "--control", "@" + control.path(), "--weights", "@" + weights.path()});
  ASSERT_EQ(inline_run.exit_code, 0) << inline_run.err;
  EXPECT_EQ(file_run.exit_code, 0) << file_run.err;
  EXPECT_EQ(file_run.out, inline_run.out);
  // --control from standard input, through read_curve (uniformity) as well.
  const RunResult a = run_uniparam({"uniformity", "--control", "[[1,0],[1,1],[0,1]]", "--speed", "parametric"});
  const RunResult b = run_with_stdin({"uniformity", "--control", "-", "--speed", "parametric"}, control.path());
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(b.out, a.out);
}

TEST(InputFiles, MissingFileNamesThePath) {
  const std::string missing = "/tmp/uniparam_no_such_input_file_36.txt";
  std::remove(missing.c_str());
  RunResult r = run_uniparam({"uniformity", "@" + missing});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("CURVE: cannot open '" + missing + "': No such file or directory"), std::string::npos) << r.err;
  r = run_uniparam({"bezier", "--control", "@" + missing});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--control: cannot open '" + missing + "'"), std::string::npos) << r.err;
  const TempFile control("[[0,0],[1,1]]");
  r = run_uniparam({"bezier", "--control", "@" + control.path(), "--weights", "@" + missing});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--weights: cannot open '" + missing + "'"), std::string::npos) << r.err;
}

TEST(InputFiles, OtherErrors) {
  RunResult r = run_uniparam({"uniformity", "@/tmp"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("cannot read the file '/tmp'"), std::string::npos) << r.err;
  r = run_uniparam({"uniformity", "@"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("'@' must be followed by a file name"), std::string::npos) << r.err;
  const TempFile f("[[0,0],[1,1]]");
  r = run_with_stdin({"uniformity", "--control", "-", "--weights", "-"}, f.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("at most one of CURVE, --control, --weights, --svg and --nurbs may be '-'"), std::string::npos) << r.err;
  // A file longer than --max-length: the budget error of the parser's limit.
  const TempFile curve(kCurve);
  r = run_uniparam({"uniformity", "@" + curve.path(), "--max-length", "10"});
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("more than 10 bytes"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--max-length"), std::string::npos) << r.err;
  // The same through standard input.
  r = run_with_stdin({"uniformity", "-", "--max-length", "10"}, curve.path());
  EXPECT_EQ(r.exit_code, 4);
  EXPECT_NE(r.err.find("standard input holds more than 10 bytes"), std::string::npos) << r.err;
  // A file's parse error is reported as for the inline text.
  const TempFile bad("(t, t^)");
  r = run_uniparam({"uniformity", "@" + bad.path()});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("parse error"), std::string::npos) << r.err;
}

}  // namespace
