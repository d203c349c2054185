// cli/main.cpp -- the uniparam command: dispatch, error reporting, exit codes.
//
// Exit codes: 0 success; 2 usage error or invalid input (bad option, parse
// error); 3 domain error (the curve is not regular on [0, 1], ...);
// 4 budget exceeded (could not certify within the limits); 1 anything else,
// among it an answer that could not be written to stdout (cli/output.hpp).
#include <cstring>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "output.hpp"
#include "uniparam/reparam/all.hpp"

namespace {

const char* kMainHelp =
    "usage: uniparam COMMAND [ARGS] [options]\n"
    "\n"
    "Certified uniformity-improving reparameterization of rational curves.\n"
    "Every printed number is exact or a ball proven to contain the true value.\n"
    "\n"
    "commands:\n"
    "  uniformity CURVE   exact speed^2, zeros of the speed in [0,1], certified mu and u\n"
    "  radical CURVE      optimal piecewise radical reparameterization (lifts zeros)\n"
    "  moebius CURVE      optimal Moebius map, or C0 piecewise with --breakpoints\n"
    "  reparam CURVE      piecewise Moebius: C0 with --pieces N, C1 with --target U\n"
    "  bezier --control POINTS [--weights LIST]\n"
    "                     optimal bilinear reparameterization of a Bezier curve (arc length)\n"
    "  sample CURVE       K certified points of p o r at equal parameter steps (CSV, JSON)\n"
    "  plot CURVE -o F    SVG or PNG: p and p o r sampled at equal steps, and both speeds\n"
    "  locate CURVE (--length S | --fraction F | --angle A)\n"
    "                     the parameter t at arc length S (or turning angle A), certified\n"
    "  batch COMMAND      COMMAND on every JSON line of stdin, one JSON result per line\n"
    "\n"
    "CURVE is a tuple of rational functions of t, e.g. \"(t, t^3)\" or\n"
    "\"((1-t^2)/(1+t^2), 2t/(1+t^2), t)\"; decimals are read exactly (0.1 = 1/10).\n"
    "Every command also takes a Bezier curve instead of CURVE: --control\n"
    "\"[[x0,y0],[x1,y1],...]\" and, for a rational one, --weights \"[w0,w1,...]\";\n"
    "an SVG path (--svg \"M 0 0 Q 1 2 3 1\") or a NURBS curve (--nurbs JSON), whose\n"
    "segments are joined into one curve; any of them as - (stdin) or @FILE.\n"
    "\n"
    "Run 'uniparam COMMAND --help' for the options of a command.\n"
    "Exit codes: 0 ok, 2 invalid input or option, 3 curve not regular on [0,1],\n"
    "4 a budget exceeded (precision, degree, size, length, depth or time: the\n"
    "message names the option that raises it), 1 other error (among them an\n"
    "answer that could not be written: a full disk, a closed pipe).\n";

/// Runs the command of argv (or the main help); its answer goes to std::cout
/// (captured by main), errors to stderr. An exception discards what the
/// command printed so far, so a failed command prints nothing on stdout.
/// \returns the exit status; `cmd` is the command's name ("" for the help).
int dispatch(int argc, char** argv, uniparam::cli::StdoutCapture& out, std::string& cmd) {
  using namespace uniparam;
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h") || !std::strcmp(argv[1], "help")) {
    if (argc < 2) {  // a usage error: the help goes to stderr
      std::cerr << kMainHelp;
      return 2;
    }
    std::cout << kMainHelp;
    return 0;
  }
  if (!std::strcmp(argv[1], "--version")) {
    std::cout << "uniparam 0.1.0\n";
    return 0;
  }
  cmd = argv[1];
  auto fail = [&](const std::string& message, int status) {
    out.discard();
    std::cerr << "uniparam " << cmd << ": " << message << "\n";
    return status;
  };
  try {
    // batch runs other commands line by line, each under its own time limit.
    if (cmd == "batch") return cli::run_batch(argc, argv);
    for (const auto& c : cli::commands())
      if (c.spec.name == cmd) return cli::run_command(c, argc, argv);
    std::cerr << "uniparam: unknown command '" << cmd << "' (run 'uniparam --help' for the list)\n";
    return 2;
  } catch (const ParseError& e) {
    return fail(e.what(), 2);
  } catch (const InvalidArgument& e) {
    return fail(e.what(), 2);
  } catch (const DomainError& e) {
    return fail(e.what(), 3);
  } catch (const BudgetExceeded& e) {
    return fail(e.what(), 4);
  } catch (const std::bad_alloc&) {
    return fail("out of memory", 1);
  } catch (const std::exception& e) {
    return fail(std::string("internal error: ") + e.what(), 1);
  }
}

}  // namespace

int main(int argc, char** argv) {
  std::string cmd;
  int status = 0;
  std::string error;
  bool streamed = false;
  {
    uniparam::cli::StdoutCapture out;
    status = dispatch(argc, argv, out, cmd);
    // The answer is complete: write it at once (or flush what streamed), and
    // fail loudly if it cannot be.
    streamed = out.streaming();
    error = out.finish();
  }
  // A streaming command that failed has said why, a failed write included.
  if (!error.empty() && !(streamed && status != 0)) {
    std::cerr << "uniparam" << (cmd.empty() ? "" : " " + cmd) << ": cannot write the output to stdout: " << error
              << "\n";
    return status != 0 ? status : 1;
  }
  return status;
}
