// `uniparam plot` under hostile conditions: the rsvg-convert child and any
// temporary file do not outlive the command (timeout, SIGTERM, SIGINT,
// SIGKILL), and an unwritable output is refused before computing. The
// layout at extreme scales is tested in test_plot_layout.cpp, the trace in
// test_plot_trace.cpp.
#include <gtest/gtest.h>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run.hpp"
#include "support/svg.hpp"
#include "uniparam/reparam/all.hpp"

extern char** environ;

using uniparam::test_support::group;
using uniparam::test_support::run_uniparam;

namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool exists(const std::string& path) {
  struct stat st;
  return lstat(path.c_str(), &st) == 0;
}

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> v;
  if (DIR* d = opendir(dir.c_str())) {
    while (const dirent* e = readdir(d))
      if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) v.push_back(e->d_name);
    closedir(d);
  }
  return v;
}

// A private directory, removed with its contents at the end of the scope.
struct ScratchDir {
  std::string path;
  ScratchDir() {
    char name[] = "/tmp/uniparam_plot_robust_XXXXXX";
    path = mkdtemp(name) ? name : "";
  }
  ~ScratchDir() {
    if (!path.empty()) std::system(("rm -rf " + uniparam::test_support::shell_quote(path)).c_str());
  }
};

// True while process `pid` exists and is not a zombie.
bool running(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(f, line)) return false;
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

// A stand-in for rsvg-convert in `dir`/bin: records its arguments and pid,
// then blocks on the FIFO `dir`/go until released, then writes its output
// like rsvg-convert does (to --output FILE, else to stdout).
void install_fake_rsvg(const std::string& dir) {
  mkdir((dir + "/bin").c_str(), 0755);
  mkfifo((dir + "/go").c_str(), 0600);
  const std::string script = dir + "/bin/rsvg-convert";
  std::ofstream f(script);
  f << "#!/bin/sh\n"
    << "for a in \"$@\"; do printf '%s\\n' \"$a\"; done > '" << dir << "/args'\n"
    << "echo $$ > '" << dir << "/pid.tmp' && mv '" << dir << "/pid.tmp' '" << dir << "/pid'\n"
    << "read line < '" << dir << "/go'\n"
    << "out=; prev=\n"
    << "for a in \"$@\"; do [ \"$prev\" = --output ] && out=\"$a\"; prev=\"$a\"; done\n"
    << "if [ -n \"$out\" ]; then printf 'PNG' > \"$out\"; else cat > /dev/null; printf 'PNG'; fi\n";
  f.close();
  chmod(script.c_str(), 0755);
}

// Starts `uniparam plot ...` with PATH led by the fake rsvg-convert and
// TMPDIR private; stdin from /dev/null, stdout and stderr into files.
pid_t start_plot(const std::string& dir, const std::vector<std::string>& args) {
  const char* bin = std::getenv("UNIPARAM_BIN");
  std::vector<std::string> argv_s = {bin ? bin : "uniparam", "plot"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (kv.rfind("PATH=", 0) == 0 || kv.rfind("TMPDIR=", 0) == 0) continue;
    env_s.push_back(kv);
  }
  const char* path = std::getenv("PATH");
  env_s.push_back("PATH=" + dir + "/bin:" + (path ? path : "/usr/bin:/bin"));
  env_s.push_back("TMPDIR=" + dir + "/tmp");
  mkdir((dir + "/tmp").c_str(), 0700);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, (dir + "/stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 2, (dir + "/stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

// The pid the fake rsvg-convert recorded, waiting for it while `plot` runs
// (0 if `plot` ended first: it never started the child).
pid_t wait_for_fake(const std::string& dir, pid_t plot, int& plot_status, bool& plot_ended) {
  plot_ended = false;
  for (int i = 0; i < 240 * 50; ++i) {  // a generous bound, not a speed test
    if (exists(dir + "/pid")) return static_cast<pid_t>(std::atol(read_all(dir + "/pid").c_str()));
    if (waitpid(plot, &plot_status, WNOHANG) == plot) {
      plot_ended = true;
      return exists(dir + "/pid") ? static_cast<pid_t>(std::atol(read_all(dir + "/pid").c_str())) : 0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return 0;
}

// After `plot` has ended: lets a surviving fake child go on (as a surviving
// rsvg-convert would) and waits for it to finish, so that nothing is left
// running and a late output file shows.
void release_survivor(const std::string& dir, pid_t fake) {
  if (fake <= 0 || !running(fake)) return;
  const int fd = open((dir + "/go").c_str(), O_WRONLY | O_NONBLOCK);
  if (fd >= 0) {
    const ssize_t n = write(fd, "go\n", 3);
    (void)n;
    close(fd);
  }
  for (int i = 0; i < 60 * 50 && running(fake); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

// The SVG files a fake rsvg-convert was handed as arguments (temporary files).
std::vector<std::string> svg_arguments(const std::string& dir) {
  std::vector<std::string> v;
  std::istringstream in(read_all(dir + "/args"));
  for (std::string a; std::getline(in, a);)
    if (a.size() > 4 && a.compare(a.size() - 4, 4, ".svg") == 0) v.push_back(a);
  return v;
}

enum class Ending { Timeout, Sigterm, Sigint, Sigkill };

void check_plot_ends_cleanly(Ending how) {
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  install_fake_rsvg(d.path);
  const std::string png = d.path + "/x.png";
  std::vector<std::string> args = {"(t, t^2)", "--points", "10", "-o", png};
  if (how == Ending::Timeout) args.insert(args.end(), {"--timeout", "4"});
  const pid_t plot = start_plot(d.path, args);
  ASSERT_GT(plot, 0);
  int status = 0;
  bool ended = false;
  const pid_t fake = wait_for_fake(d.path, plot, status, ended);
  if (how != Ending::Timeout && !ended) {
    const int sig = how == Ending::Sigterm ? SIGTERM : how == Ending::Sigint ? SIGINT : SIGKILL;
    kill(plot, sig);
  }
  if (!ended) waitpid(plot, &status, 0);
  const std::vector<std::string> temps = svg_arguments(d.path);
  // After SIGKILL the child gets its parent-death signal asynchronously: give
  // it a bounded moment to go (a survivor blocks on its FIFO and never does).
  if (how == Ending::Sigkill)
    for (int i = 0; i < 5 * 50 && fake > 0 && running(fake); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool survived = fake > 0 && running(fake);
  release_survivor(d.path, fake);
  std::vector<std::string> left;
  for (const auto& t : temps)
    if (exists(t)) left.push_back(t);
  for (const auto& t : left) std::remove(t.c_str());  // tidy up after a failing binary
  ASSERT_GT(fake, 0) << "rsvg-convert was never started: " << read_all(d.path + "/stderr");
  if (how == Ending::Timeout) {
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status;
    EXPECT_NE(read_all(d.path + "/stderr").find("--timeout"), std::string::npos) << read_all(d.path + "/stderr");
  } else {
    const int sig = how == Ending::Sigterm ? SIGTERM : how == Ending::Sigint ? SIGINT : SIGKILL;
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
  }
  EXPECT_FALSE(survived) << "rsvg-convert (pid " << fake << ") outlived the command";
  EXPECT_TRUE(entries(d.path + "/tmp").empty()) << "files left in TMPDIR";
  for (const auto& t : left) ADD_FAILURE() << "temporary file left: " << t;
  EXPECT_FALSE(exists(png)) << "the output was written after the command ended";
}

}  // namespace

// ---- The rsvg-convert child and temporary files ---------------------------

TEST(PlotRobust, TimeoutKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Timeout); }
TEST(PlotRobust, SigtermKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Sigterm); }
TEST(PlotRobust, SigintKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Sigint); }
TEST(PlotRobust, SigkillTakesRsvgConvertAlong) { check_plot_ends_cleanly(Ending::Sigkill); }

TEST(PlotRobust, PngWithoutTemporaryFilesWhenRsvgConvertWorks) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) GTEST_SKIP() << "no rsvg-convert";
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  mkdir((d.path + "/tmp").c_str(), 0700);
  const std::string png = d.path + "/x.png";
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  setenv("TMPDIR", (d.path + "/tmp").c_str(), 1);
  const auto r = run_uniparam({"plot", "(t, t^3)", "-o", png});
  if (old) setenv("TMPDIR", saved.c_str(), 1);
  else unsetenv("TMPDIR");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = read_all(png);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_TRUE(entries(d.path + "/tmp").empty());
}

// ---- The output file: checked before computing ----------------------------

TEST(PlotRobust, UnwritableOutputIsRefusedBeforeComputingWithTheReason) {
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  std::ofstream(d.path + "/file") << "x";
  mkdir((d.path + "/dir.svg").c_str(), 0755);
  struct Case {
    std::string path;
    int err;
  };
  const Case cases[] = {
      {d.path + "/missing/x.svg", ENOENT},
      {d.path + "/missing/x.png", ENOENT},
      {d.path + "/file/x.svg", ENOTDIR},
      {d.path + "/dir.svg", EISDIR},
  };
  // The curve has a pole in [0, 1] (exit 3 once the curve is read): the
  // output must be refused before that.
  for (const auto& c : cases) {
    const auto r = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", c.path});
    EXPECT_EQ(r.exit_code, 2) << c.path << ": " << r.err;
    const std::string want = "cannot write " + c.path + ": " + std::strerror(c.err);
    EXPECT_NE(r.err.find(want), std::string::npos) << "want '" << want << "', got: " << r.err;
  }
  // A writable new path: not created by the check (the command then fails
  // on the curve).
  const std::string fresh = d.path + "/fresh.svg";
  const auto r = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", fresh});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_FALSE(exists(fresh));
  // An existing file is left as it is when the command fails.
  std::ofstream(d.path + "/old.svg") << "keep";
  const auto r2 = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", d.path + "/old.svg"});
  EXPECT_EQ(r2.exit_code, 3) << r2.err;
  EXPECT_EQ(read_all(d.path + "/old.svg"), "keep");
}
