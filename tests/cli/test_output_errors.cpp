// The uniparam command's output path and budgets: a failed write to stdout is
// an error, an error leaves stdout empty, --timeout and UNIPARAM_THREADS are
// enforced, and a missed --target says what can still be changed.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::test_support::run_uniparam;
using uniparam::test_support::shell_quote;

namespace {

std::string binary() {
  const char* bin = std::getenv("UNIPARAM_BIN");
  return bin ? bin : "uniparam";
}

/// Where the child's stdout goes.
enum class Stdout { DevFull, ClosedPipe, Closed };

struct Outcome {
  int exit_code = -1;  ///< -1 when the child died of a signal
  int signal = 0;
  std::string err;
};

/// Runs the binary with stdout set up as `how` and stderr captured.
Outcome run_with_stdout(Stdout how, const std::vector<std::string>& args) {
  char errname[] = "/tmp/uniparam_test_outerr_XXXXXX";
  const int errfd = mkstemp(errname);
  Outcome o;
  if (errfd < 0) return o;
  int pipefd[2] = {-1, -1};
  if (how == Stdout::ClosedPipe) {
    if (pipe(pipefd) != 0) return o;
    close(pipefd[0]);  // nobody will ever read: a write fails with EPIPE
  }
  const std::string bin = binary();
  std::vector<std::string> argv_s{bin};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    signal(SIGPIPE, SIG_DFL);  // as from a shell
    dup2(errfd, 2);
    if (how == Stdout::DevFull) {
      const int fd = open("/dev/full", O_WRONLY);
      dup2(fd, 1);
    } else if (how == Stdout::ClosedPipe) {
      dup2(pipefd[1], 1);
    } else {
      close(1);
    }
    execv(bin.c_str(), argv.data());
    _exit(127);
  }
  if (pipefd[1] >= 0) close(pipefd[1]);
  int status = 0;
  waitpid(pid, &status, 0);
  if (WIFEXITED(status)) o.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) o.signal = WTERMSIG(status);
  close(errfd);
  std::ifstream f(errname);
  std::stringstream ss;
  ss << f.rdbuf();
  o.err = ss.str();
  std::remove(errname);
  return o;
}

/// Commands that print an answer on success, one of each kind of output.
std::vector<std::vector<std::string>> printing_commands() {
  return {
      {"uniformity", "(t, t^3)"},
      {"uniformity", "(t, t^3)", "--json"},
      {"radical", "(t^2, t^3)"},
      {"reparam", "(t, t^3)", "--pieces", "2"},
      {"sample", "(t, t^3)", "--points", "5"},
      {"uniformity", "--help"},
      {"--help"},
      {"--version"},
  };
}

/// (t, y(t)) with y of degree `n` and coefficients in [-9, 9] from a fixed
/// linear congruential sequence: a dense curve whose radical output (many
/// breakpoints, each printed with a short isolating interval) takes seconds.
std::string dense_curve(int n) {
  std::uint64_t state = 12345;
  std::string y;
  for (int k = 0; k <= n; ++k) {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    const int c = static_cast<int>((state >> 33) % 19) - 9;
    y += (k ? "+(" : "(") + std::to_string(c) + ")*t^" + std::to_string(k);
  }
  return "(t, " + y + ")";
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST(OutputErrors, AFullDiskIsAnErrorWithTheSystemsReason) {
  if (access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  for (const auto& args : printing_commands()) {
    const Outcome o = run_with_stdout(Stdout::DevFull, args);
    EXPECT_EQ(o.exit_code, 1) << args[0] << ": " << o.err;
    EXPECT_NE(o.err.find("cannot write the output"), std::string::npos) << o.err;
    EXPECT_NE(o.err.find(std::strerror(ENOSPC)), std::string::npos) << o.err;
  }
}

TEST(OutputErrors, AClosedPipeIsAnErrorNotADeathBySignal) {
  for (const auto& args : printing_commands()) {
    const Outcome o = run_with_stdout(Stdout::ClosedPipe, args);
    EXPECT_EQ(o.signal, 0) << args[0];
    EXPECT_EQ(o.exit_code, 1) << args[0] << ": " << o.err;
    EXPECT_NE(o.err.find(std::strerror(EPIPE)), std::string::npos) << o.err;
  }
}

TEST(OutputErrors, AClosedStdoutIsAnError) {
  for (const auto& args : printing_commands()) {
    const Outcome o = run_with_stdout(Stdout::Closed, args);
    EXPECT_EQ(o.exit_code, 1) << args[0] << ": " << o.err;
    EXPECT_NE(o.err.find(std::strerror(EBADF)), std::string::npos) << o.err;
  }
}

TEST(OutputErrors, AnErrorWithoutOutputNeedsNoStdout) {
  // An invalid option prints nothing: its exit code stays 2 with stdout unusable.
  const Outcome o = run_with_stdout(Stdout::Closed, {"uniformity", "(t, t^3)", "--digits", "0"});
  EXPECT_EQ(o.exit_code, 2) << o.err;
  EXPECT_EQ(o.err.find("cannot write"), std::string::npos) << o.err;
}

TEST(OutputErrors, NothingIsPrintedWhenTheTimeRunsOutWhilePrinting) {
  // Whatever phase the deadline falls in (computing, or formatting the
  // breakpoints' isolating intervals, which takes most of the run here),
  // exit 4 comes with an empty stdout and exit 0 with the whole answer.
  const std::string curve = dense_curve(600);
  for (const char* timeout : {"1", "2", "3"})
    for (const bool json : {false, true}) {
      std::vector<std::string> args{"radical", curve, "--timeout", timeout};
      if (json) args.push_back("--json");
      const auto r = run_uniparam(args);
      if (r.exit_code == 4) {
        EXPECT_NE(r.err.find("time limit"), std::string::npos) << r.err;
        EXPECT_EQ(r.out.size(), 0u) << "--timeout " << timeout << (json ? " --json" : "") << " printed "
                                    << r.out.size() << " bytes before failing";
      } else {
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(r.out.find(json ? "\"u_after\"" : "u(p o r)"), std::string::npos);
      }
    }
}

TEST(Timeout, StopsSoonAfterItsDeadline) {
  // The Gauss-Legendre nodes at 2000 digits take longer than the budget;
  // the command must stop within max(0.5 s, 10%) of --timeout 1, which this
  // bound leaves room for on a loaded machine (the old backstop fired at 3.05 s).
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = run_uniparam({"moebius", "(t, t^3)", "--digits", "2000", "--timeout", "1"});
  const double wall = seconds_since(t0);
  ASSERT_EQ(r.exit_code, 4) << r.err;
  EXPECT_NE(r.err.find("time limit exceeded"), std::string::npos) << r.err;
  EXPECT_EQ(r.out.size(), 0u);
  EXPECT_LT(wall, 2.5);
}

TEST(Timeout, TheBudgetIsPolledWhileGaussLegendreNodesAreComputed) {
  // In the library, without the CLI's watchdog: the quadrature at 2000
  // digits starts by computing Gauss-Legendre rules of hundreds of nodes at
  // 8192 bits (about a second per rule); the budget must be noticed between
  // two nodes, not after the rule.
  using namespace uniparam;
  Options opt;
  opt.digits = 2000;
  const Curve c = Curve::parse("(t, t^3)");
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const TimeBudget budget(0.3);
    (void)uniformity(c, SpeedKind::Angular, opt);
    FAIL() << "finished within 0.3 s";
  } catch (const BudgetExceeded& e) {
    EXPECT_NE(std::string(e.what()).find("time limit exceeded"), std::string::npos) << e.what();
  }
  EXPECT_LT(seconds_since(t0), 2.0);
}

TEST(Threads, AnInvalidEnvironmentValueIsRefusedLikeTheOption) {
  for (const char* bad : {"abc", "0", "65", "2x", "-1", "99999999999999999999"}) {
    const std::string env = "UNIPARAM_THREADS=" + shell_quote(bad) + " ";
    const std::string cmd = env + shell_quote(binary()) + " uniformity '(t, t^3)' 2>&1";
    std::string out;
    FILE* p = popen(cmd.c_str(), "r");
    ASSERT_NE(p, nullptr);
    char buf[4096];
    std::size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int status = pclose(p);
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 2) << bad << ": " << out;
    EXPECT_NE(out.find("UNIPARAM_THREADS"), std::string::npos) << out;
    // the same validator as --threads: the same message with the option's name
    const auto opt = run_uniparam({"uniformity", "(t, t^3)", "--threads", bad});
    EXPECT_EQ(opt.exit_code, 2);
    std::string expected = opt.err;
    const auto at = expected.find("--threads");
    ASSERT_NE(at, std::string::npos) << expected;
    expected.replace(at, 9, "UNIPARAM_THREADS");
    EXPECT_EQ(out, expected);
  }
  setenv("UNIPARAM_THREADS", "2", 1);
  const auto ok = run_uniparam({"uniformity", "(t, t^3)"});
  unsetenv("UNIPARAM_THREADS");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(ReparamTarget, AMissedTargetShowsAUBelowItAndAdviceThatCanBeFollowed) {
  // u_after of one piece is 1 - 6e-14 here: 8 digits would print "1".
  const auto one = run_uniparam({"reparam", "(t, t^2/1000)", "--target", "0.99999999999999", "--max-pieces", "1"});
  ASSERT_EQ(one.exit_code, 4) << one.err;
  const auto u_at = one.err.find("u = ");
  ASSERT_NE(u_at, std::string::npos) << one.err;
  const std::string u = one.err.substr(u_at + 4, one.err.find(')', u_at) - u_at - 4);
  EXPECT_LT(uniparam::Rational::parse(u), uniparam::Rational::parse("0.99999999999999")) << one.err;
  EXPECT_NE(one.err.find("raise --max-pieces"), std::string::npos) << one.err;

  // At the cap of --max-pieces, raising it is impossible.
  EXPECT_EQ(run_uniparam({"reparam", "(t, t^3)", "--target", "0.9", "--max-pieces", "1001"}).exit_code, 2);
  const auto cap = run_uniparam(
      {"reparam", "(t, t^3)", "--target", "0.999999999999999999999", "--max-pieces", "1000", "--timeout", "120"});
  ASSERT_EQ(cap.exit_code, 4) << cap.err;
  EXPECT_EQ(cap.err.find("raise --max-pieces"), std::string::npos) << cap.err;
  EXPECT_NE(cap.err.find("lower --target"), std::string::npos) << cap.err;
}

TEST(Timeout, ADeadlineAnywhereInTheEngineIsReportedAsTime) {
  // Budgets that end in different phases (root isolation, quadrature,
  // precision loops, the C1 refinement): whatever stops the computation is
  // the time limit, never a precision or other budget message.
  using namespace uniparam;
  const Curve dense = Curve::parse(dense_curve(200));
  const Curve cusp = Curve::parse("((t-1)^2, (t-1)^3)");
  Options opt;
  opt.digits = 40;
  int stopped = 0;
  for (const double seconds : {0.01, 0.05, 0.15, 0.4}) {
    for (int job = 0; job < 3; ++job) {
      try {
        const TimeBudget budget(seconds);
        if (job == 0) (void)radical(dense, SpeedKind::Angular, opt);
        if (job == 1) (void)reparam_c1(cusp, SpeedKind::Angular, Rational(999, 1000), opt, 64);
        if (job == 2) (void)uniformity(dense, SpeedKind::Parametric, opt);
      } catch (const BudgetExceeded& e) {
        ++stopped;
        EXPECT_NE(dynamic_cast<const TimeLimitExceeded*>(&e), nullptr) << "job " << job << ": " << e.what();
        EXPECT_NE(std::string(e.what()).find("time limit exceeded"), std::string::npos) << e.what();
      }
    }
  }
  EXPECT_GT(stopped, 0);
}
