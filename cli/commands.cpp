// cli/commands.cpp -- the table of subcommands and their shared options.
#include "commands.hpp"

#include "composite.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <thread>

#include "input.hpp"
#include "uniparam/core/parallel.hpp"

namespace uniparam::cli {

namespace {

constexpr const char* kDefaultTimeout = "600";

/// The range of --threads and UNIPARAM_THREADS.
constexpr long kMaxThreads = 64;

/// The backstop of --timeout. The engine checks its TimeBudget cooperatively
/// in every long loop, but a single Arb or FLINT call (one product or gcd of
/// huge polynomials, say) runs to its end without looking at the clock. If
/// the command is still running watchdog_grace() after its deadline, this
/// thread reports the budget error and ends the process with exit code 4
/// (stdout stays empty: main() writes the answer only after the command has
/// returned, cli/output.hpp).
/// The grace: max(0.4 s, 8% of the budget), inside the promise of
/// docs/robustness.md that --timeout T stops within max(0.5 s, 10% of T).
double watchdog_grace(double seconds) { return std::max(0.4, 0.08 * seconds); }

class Watchdog {
 public:
  Watchdog(double seconds, std::string command) {
    const auto grace = std::chrono::duration<double>(seconds + watchdog_grace(seconds));
    thread_ = std::thread([this, grace, seconds, command = std::move(command)] {
      std::unique_lock<std::mutex> lock(mutex_);
      if (done_cv_.wait_for(lock, grace, [this] { return done_; })) return;
      std::fprintf(stderr,
                   "uniparam %s: time limit exceeded: the computation did not finish within %g s "
                   "(raise it with --timeout SECONDS)\n",
                   command.c_str(), seconds);
      std::fflush(stderr);
      std::_Exit(4);
    });
  }
  ~Watchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    done_cv_.notify_one();
    thread_.join();
  }
  Watchdog(const Watchdog&) = delete;
  Watchdog& operator=(const Watchdog&) = delete;

 private:
  std::mutex mutex_;
  std::condition_variable done_cv_;
  bool done_ = false;
  std::thread thread_;
};

}  // namespace

std::vector<OptionSpec> common_options() {
  return {
      {"speed", "KIND", "speed to make uniform: angular or parametric (arc length; also 'arclength')", "angular"},
      {"digits", "D", "correct decimal digits, 1 to 2000: every ball has radius <= 10^-D * max(1, |mid|)", "15"},
      {"json", "", "print JSON: certified reals as {\"mid\", \"rad\"}", ""},
      {"max-prec", "BITS", "largest working precision before giving up", "16384"},
      {"max-degree", "N", "largest degree of the curve and of any polynomial or exponent read in CURVE", "1000"},
      {"max-bits", "BITS", "largest size of a number or polynomial read in CURVE, (degree + 1) * coefficient bits",
       "268435456"},
      {"max-length", "N", "largest length of CURVE in characters", "1048576"},
      {"max-depth", "N", "deepest nesting of parentheses, signs and powers in CURVE", "500"},
      {"timeout", "SECONDS", "wall-clock time limit of the whole command", kDefaultTimeout},
      {"threads", "N", "worker threads for independent pieces (default: UNIPARAM_THREADS, else the cores, at most 8)",
       ""},
      {"control", "POINTS", "the curve as Bezier control points \"[[x0,y0],[x1,y1],...]\" (instead of CURVE; @FILE reads a file, - standard input, as for CURVE)", ""},
      {"weights", "LIST", "weights \"[w0,w1,...]\" of a rational Bezier curve (with --control; positive; or @FILE, -)", ""},
      {"svg", "PATH", "the curve as SVG path data \"M 0 0 Q 1 2 3 1 ...\" (one subpath; docs/inputs.md)", ""},
      {"subpath", "K", "with --svg: the subpath to use, 0-based (needed when the path has several)", ""},
      {"nurbs", "JSON", "the curve as a NURBS/B-spline {\"degree\", \"knots\", \"control\", \"weights\"}", ""},
  };
}

Options read_options(const Args& a) {
  static_assert(kMaxDigits == 2000, "the --digits help names the range");
  Options o;
  o.digits = a.get_long("digits", o.digits, 1, kMaxDigits);
  o.max_prec = a.get_long("max-prec", default_max_prec(o.digits), 64, 1L << 24);
  o.max_degree = a.get_long("max-degree", o.max_degree, 1, 20000);  // root isolation refuses degrees above 20000
  return o;
}

namespace {
// BezierCurve::parse reads at most 2^20 characters of each list.
constexpr std::size_t kMaxListBytes = std::size_t(1) << 20;

// At most one of CURVE, --control, --weights, --svg, --nurbs may read standard input.
void check_one_stdin(const Args& a) {
  int n = !a.positional.empty() && reads_stdin(a.positional.front());
  for (const char* o : {"control", "weights", "svg", "nurbs"}) n += a.has(o) && reads_stdin(a.get(o, ""));
  if (n > 1)
    throw InvalidArgument("at most one of CURVE, --control, --weights, --svg and --nurbs may be '-' (standard input)");
}
}  // namespace

BezierCurve read_bezier(const Args& a) {
  if (a.has("svg") || a.has("nurbs"))
    throw InvalidArgument("'uniparam " + a.command + "' takes one Bezier curve, given with --control; for a path "
                          "or a spline, 'uniparam moebius --speed parametric' gives each segment its optimal "
                          "Moebius map");
  if (!a.has("control")) throw InvalidArgument("give the control points with --control \"[[x0,y0],[x1,y1],...]\"");
  check_one_stdin(a);
  const long max_degree = read_options(a).max_degree;
  const std::string control = read_argument_text("--control", a.get("control", ""), kMaxListBytes);
  const std::string weights =
      a.has("weights") ? read_argument_text("--weights", a.get("weights", ""), kMaxListBytes) : std::string();
  BezierCurve b = BezierCurve::parse(control, weights, static_cast<std::size_t>(max_degree) + 1);
  if (a.has("weights") && !b.is_rational()) throw InvalidArgument("--weights: empty list");
  return b;
}

Curve read_curve(const Args& a) {
  check_one_stdin(a);
  if (a.has("svg") || a.has("nurbs")) {
    const CompositeCurve cc = *read_composite(a);
    if (cc.size() != 1)
      throw InvalidArgument("'uniparam " + a.command + "' takes one curve, and this " + composite_description(a, cc) +
                            " (use it with uniformity, radical, moebius, reparam, sample or locate)");
    return cc.segment(0);
  }
  if (a.has("control")) return read_bezier(a).to_curve();
  if (a.has("weights")) throw InvalidArgument("--weights needs --control (the weights of a rational Bezier curve)");
  const ParseLimits lim = read_parse_limits(a);
  return Curve::parse(read_argument_text("CURVE", a.positional.at(0), lim.max_length, "--max-length"), lim);
}

ParseLimits read_parse_limits(const Args& a) {
  ParseLimits lim;
  lim.max_degree = a.get_long("max-degree", Options{}.max_degree, 1, 20000);
  lim.max_exponent = lim.max_degree;
  lim.max_bits = a.get_long("max-bits", lim.max_bits, 64, 1L << 40);
  lim.max_length = static_cast<std::size_t>(a.get_long("max-length", static_cast<long>(lim.max_length), 1, 1L << 30));
  lim.max_depth = static_cast<int>(a.get_long("max-depth", lim.max_depth, 1, 1L << 30));
  return lim;
}

double read_timeout(const Args& a) {
  const std::string s = a.get("timeout", kDefaultTimeout);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw InvalidArgument("--timeout expects a number of seconds, got '" + s + "'");
  if (!(v > 0.0) || v > 1e9) throw InvalidArgument("--timeout must be above 0 and at most 1e9 seconds, got " + s);
  return v;
}

Rational read_rational(const std::string& option, const std::string& text) {
  // The OS already caps one argument at 128 KiB; this keeps 10^(10^6)-sized
  // numbers ("1e999999") out of the breakpoints and evaluation points.
  const auto e = text.find_first_of("eE");
  if (text.size() > 100000 || (e != std::string::npos && text.size() - e > 5))  // "e-999" at most
    throw InvalidArgument("--" + option + ": the number '" + text.substr(0, 20) + (text.size() > 20 ? "..." : "") +
                          "' is too large (at most 100000 characters and a decimal exponent below 1000)");
  try {
    return Rational::parse(text);
  } catch (const Error& e) {
    throw InvalidArgument("--" + option + ": '" + text.substr(0, 40) + (text.size() > 40 ? "..." : "") +
                          "' is not a rational number such as 1/3, 0.25 or 1e-3 (" + e.what() + ")");
  }
}


int run_command(const Command& c, int argc, char** argv, bool watchdog) {
  // Parse once here for --timeout (the command parses again, cheaply, and
  // reports every other option error itself); help needs no budget.
  const Args a = parse_args(c.spec, argc, argv, 2);
  if (a.help) return c.run(argc, argv);
  const double seconds = read_timeout(a);
  // --threads holds for this command's parallel loops (and their workers:
  // core/parallel.hpp), the process environment untouched; without it the
  // loops read UNIPARAM_THREADS, which passes the same check here.
  std::size_t threads = 0;
  if (a.has("threads")) {
    threads = static_cast<std::size_t>(a.get_long("threads", 1, 1, kMaxThreads));
  } else if (const char* e = std::getenv("UNIPARAM_THREADS"); e && *e) {
    parse_long("UNIPARAM_THREADS", e, 1, kMaxThreads);
  }
  const ScopedWorkerCount workers(threads);
  const TimeBudget budget(seconds);
  if (!watchdog) return c.run(argc, argv);
  const Watchdog backstop(seconds, c.spec.name);
  return c.run(argc, argv);
}

const std::vector<Command>& commands() {
  static const std::vector<Command> table = {
      {uniformity_spec(), &run_uniformity},
      {radical_spec(), &run_radical},
      {moebius_spec(), &run_moebius},
      {reparam_spec(), &run_reparam},
      {bezier_spec(), &run_bezier},
      {sample_spec(), &run_sample},
      {plot_spec(), &run_plot},
      {locate_spec(), &run_locate},
  };
  return table;
}

}  // namespace uniparam::cli
