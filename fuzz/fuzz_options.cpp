// fuzz/fuzz_options.cpp -- libFuzzer target for the option handling of every
// command in cli/commands.cpp's commands() table (a command added there is
// fuzzed with its own options, with no change here).
//
// Input layout (any bytes are valid):
//   byte 0        the command: index modulo the table size
//   byte 1        the curve: one of kCurves, or (>= its size) a fuzzed token
//   then records  a selector byte s and, when needed, a token (bytes up to
//                 '\x01' or the end, at most 80):
//                   s % 4 == 0   "--NAME" [token] for option s/4 of the command
//                   s % 4 == 1   "--NAME=token"
//                   s % 4 == 2   a raw argument token
//                   s % 4 == 3   "--help" (s == 3) or a raw argument token
// The command runs through cli::run_command (its --timeout included) with
// stdout discarded. Only uniparam::Error may escape; any other exception, a
// crash, a sanitizer report, a leak or a hang is a bug.
//
// Each run is bounded: small budgets come first on the command line (a fuzzed
// later value overrides them), inputs raising them above kCaps are skipped,
// and an outer TimeBudget of 0.5 s caps the command's own --timeout.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "uniparam/reparam/all.hpp"

namespace {

using uniparam::cli::Command;

const char* const kCurves[] = {
    "(t, t^3)", "(t^2, t^3)", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "(t, 2t)", "(t, t^2, t^3)", "(t, 1/(t-1/2))",
    "(1, 2)",   "(t)",
};

struct Cap {
  const char* option;
  long max;
};
// Larger values are valid but make one run take seconds (Arb's quadrature
// nodes at thousands of bits cannot be interrupted): the options' parsing is
// still fuzzed below these.
const Cap kCaps[] = {{"max-prec", 2048}, {"max-degree", 60}, {"max-bits", 100000}, {"max-length", 4096}};
const char* const kBudgetDefaults[] = {"--max-prec=2048", "--max-degree=60", "--max-bits=100000"};

std::string token(const std::uint8_t* data, std::size_t size, std::size_t& i) {
  std::string t;
  while (i < size && data[i] != 1 && t.size() < 80) t += static_cast<char>(data[i++]);
  if (i < size && data[i] == 1) ++i;
  return t;
}

bool within_caps(const std::vector<std::string>& args) {
  for (std::size_t k = 0; k < args.size(); ++k) {
    for (const Cap& c : kCaps) {
      const std::string flag = std::string("--") + c.option;
      std::string value;
      if (args[k] == flag && k + 1 < args.size()) value = args[k + 1];
      else if (args[k].rfind(flag + "=", 0) == 0) value = args[k].substr(flag.size() + 1);
      else continue;
      char* end = nullptr;
      const long v = std::strtol(value.c_str(), &end, 10);
      if (end != value.c_str() && v > c.max) return false;
    }
  }
  return true;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto& table = uniparam::cli::commands();
  if (size < 2 || table.empty()) return 0;
  const Command& cmd = table[data[0] % table.size()];
  const auto& options = cmd.spec.options;

  std::vector<std::string> args{"uniparam", cmd.spec.name};
  std::size_t i = 2;
  const std::size_t ncurves = sizeof kCurves / sizeof kCurves[0];
  args.push_back(data[1] < ncurves ? std::string(kCurves[data[1]]) : token(data, size, i));
  for (const char* d : kBudgetDefaults) args.push_back(d);
  while (i < size && args.size() < 40) {
    const std::uint8_t s = data[i++];
    if (s == 3) { args.push_back("--help"); continue; }
    if (s % 4 >= 2 || options.empty()) { args.push_back(token(data, size, i)); continue; }
    const auto& o = options[(s / 4) % options.size()];
    if (s % 4 == 1) { args.push_back("--" + o.name + "=" + token(data, size, i)); continue; }
    args.push_back("--" + o.name);
    if (!o.value.empty()) args.push_back(token(data, size, i));
  }
  if (!within_caps(args)) return 0;

  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  std::ostringstream sink;
  std::streambuf* saved = std::cout.rdbuf(sink.rdbuf());
  try {
    const uniparam::TimeBudget outer(0.5);
    const int code = uniparam::cli::run_command(cmd, static_cast<int>(args.size()), argv.data(), false);
    if (code != 0) std::abort();  // commands return 0 or throw
  } catch (const uniparam::Error&) {
  }
  std::cout.rdbuf(saved);
  return 0;
}
