// tests/support/run.hpp -- running the uniparam binary from tests.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace uniparam::test_support {

struct RunResult {
  int exit_code = -1;
  std::string out, err;
};

/// Single-quotes an argument for /bin/sh.
inline std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += (c == '\'') ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// Runs the shell command `cmd` (stderr is redirected here); captures
/// stdout, stderr and the exit code.
inline RunResult run_shell(std::string cmd) {
  char errname[] = "/tmp/uniparam_test_err_XXXXXX";
  int fd = mkstemp(errname);
  if (fd >= 0) close(fd);
  cmd += " 2>" + std::string(errname);
  RunResult r;
  FILE* p = popen(cmd.c_str(), "r");
  if (p) {
    std::array<char, 4096> buf{};
    std::size_t n;
    while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
    int status = pclose(p);
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
  std::ifstream f(errname);
  std::stringstream ss;
  ss << f.rdbuf();
  r.err = ss.str();
  std::remove(errname);
  return r;
}

/// The shell command line of $UNIPARAM_BIN with the arguments.
inline std::string uniparam_command(const std::vector<std::string>& args) {
  const char* bin = std::getenv("UNIPARAM_BIN");
  std::string cmd = shell_quote(bin ? bin : "uniparam");
  for (const auto& a : args) cmd += " " + shell_quote(a);
  return cmd;
}

/// Runs $UNIPARAM_BIN with the arguments; captures stdout, stderr, exit code.
inline RunResult run_uniparam(const std::vector<std::string>& args) { return run_shell(uniparam_command(args)); }

/// run_uniparam with `input` on standard input (through a temporary file).
inline RunResult run_uniparam_stdin(const std::vector<std::string>& args, const std::string& input) {
  char inname[] = "/tmp/uniparam_test_in_XXXXXX";
  int fd = mkstemp(inname);
  if (fd < 0) return RunResult{};
  close(fd);
  {
    std::ofstream f(inname, std::ios::binary);
    f << input;
  }
  RunResult r = run_shell(uniparam_command(args) + " <" + shell_quote(inname));
  std::remove(inname);
  return r;
}

}  // namespace uniparam::test_support
