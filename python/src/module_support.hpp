// python/src/module_support.hpp -- internal to the Python module (not
// installed): the plain values every function of uniparam._uniparam takes,
// their reading with the CLI's checks and ranges, the guarded run of a
// computation (its own thread, the GIL released, Ctrl-C cancelling it), and
// the composite-curve commands. module.cpp binds them; module_support.cpp
// defines them.
#pragma once

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <flint/flint.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <functional>
#include <tuple>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "commands.hpp"
#include "composite.hpp"
#include "json_reports.hpp"
#include "moebius_report.hpp"
#include "nurbs_out.hpp"
#include "report.hpp"
#include "svg.hpp"
#include "uniparam/core/parallel.hpp"
#include "uniparam/reparam/all.hpp"

namespace py = pybind11;

namespace uniparam::python_support {

/// The curve and the options every function shares (the CLI's
/// common_options). Built by uniparam/__init__.py.
struct Common {
  std::string curve;    ///< the curve's text (when control is empty)
  std::string control;  ///< Bezier control points "[[x0,y0],...]" (else "")
  std::string weights;  ///< their weights "[w0,...]" (else "")
  std::optional<std::string> svg;    ///< SVG path data (a composite curve)
  std::optional<long> subpath;       ///< with svg: the subpath to use, 0-based
  std::optional<std::string> nurbs;  ///< NURBS/B-spline JSON (a composite curve)
  std::string speed = "angular";
  long digits = 15;
  long max_prec = 0;  ///< 0: default_max_prec(digits)
  long max_degree = 1000;
  long max_bits = ParseLimits{}.max_bits;
  long max_length = static_cast<long>(ParseLimits{}.max_length);
  long max_depth = ParseLimits{}.max_depth;
  double timeout = 0;  ///< seconds; 0: no time limit
  long threads = 0;    ///< 0: UNIPARAM_THREADS, else the cores (at most 8)
};

/// The input of a command: a composite curve of several segments (with its
/// description, as the CLI's), or one curve (a path or spline of one segment
/// is that segment, as in the CLI).
struct Input {
  std::optional<CompositeCurve> composite;
  std::optional<Curve> curve;
  std::string description;
};

/// The answer of a command with --output: ("report", its JSON document),
/// ("nurbs", the NURBS JSON) or ("step", the STEP text), and the C1 map's
/// missed-target message.
using Answer = std::tuple<std::string, std::string, std::string>;

/// v when lo <= v <= hi; else InvalidArgument naming the parameter `name`.
long in_range(const char* name, long v, long lo, long hi);

/// The options of c, in the CLI's ranges (read_options).
Options options_of(const Common& c);

/// The curve of c: the Bezier curve of control (and weights), else the text
/// read with the CLI's parse limits (read_curve, read_parse_limits).
Curve curve_of(const Common& c);

/// How the composite readers' messages name the Python parameters.
cli::CompositeNames python_names();

/// The composite curve of c's svg or nurbs, or nullopt for a curve given as
/// text or control points (the CLI's read_composite, with the text given
/// directly; a NURBS text longer than max_length is refused as the CLI
/// refuses such a file).
std::optional<CompositeCurve> composite_of(const Common& c);

/// The input of c: its composite curve (of more than one segment) with its
/// description, else its one curve.
Input input_of(const Common& c);

/// An exact rational given as text to parameter `name` (as the CLI's
/// read_rational, naming the Python parameter).
Rational rational_arg(const std::string& name, const std::string& text);

/// j as compact JSON text.
std::string dump(const Json& j);

/// The reparameterization `method` (radical, c0, c1, none) of cli's
/// read_method, with its checks.
Reparameterization method_of(const std::string& method, const Curve& cv, SpeedKind kind, const Options& opt,
                             std::optional<long> pieces, const std::optional<std::string>& target,
                             std::optional<long> max_pieces, bool with_none);

/// r, or its rational form (make_rational, rational_digits digits) when
/// `rational`; InvalidArgument for rational_digits without rational.
MoebiusResult finish(const Curve& cv, const MoebiusResult& r, bool rational, std::optional<long> rational_digits,
                     const Options& opt);

/// The exact rationals of `list` (parameter "breakpoints").
std::vector<RealAlgebraic> breakpoints_of(const std::vector<std::string>& list);

/// The output form `output` names ("" none; "nurbs", "step" or a .stp/.step
/// file, checked writable before computing: cli::parse_nurbs_output).
cli::NurbsOutput output_of(const std::string& output);

/// How moebius() and reparam() print their report: JSON, formulas in
/// `format` (text, latex, maple; InvalidArgument otherwise:
/// cli::parse_format).
cli::MoebiusPrint json_print(const std::string& format);

/// The NURBS n as `o` asks, as the CLI's write_nurbs: the NURBS JSON or the
/// STEP text in place of `report`, or the STEP file written and `report`.
Answer nurbs_answer(const Nurbs& n, const cli::NurbsOutput& o, long digits, const std::function<Json()>& report,
                    const std::string& missed);

/// The C1 map's message when it missed its target ("" otherwise).
std::string missed(const MoebiusResult& r, long max_pieces, long digits);

/// The map of `method` (radical, c0, c1, none) for a composite curve, as
/// the CLI's read_composite_method: pieces (c0; default max(3, segments)),
/// target (c1; default 0.99), max_pieces (c1, per segment).
CompositeMethod composite_method_of(const std::string& m, const CompositeCurve& cc, std::optional<long> pieces,
                                    const std::optional<std::string>& target, std::optional<long> max_pieces,
                                    bool with_none);

/// `m` with rational (and rational_digits) as the CLI's with_rational.
CompositeMethod with_rational(CompositeMethod m, bool rational, std::optional<long> rational_digits);

/// radical, moebius and reparam on a composite curve (the CLI's
/// run_map_composite): the report, or the NURBS of p o r as `no` asks.
Answer composite_answer(const Input& in, SpeedKind kind, const Options& opt, const CompositeMethod& m, Format fmt,
                        const cli::NurbsOutput& no);

/// sample on a composite curve (the CLI's run_sample_composite): the
/// document and the missed-target message.
std::pair<std::string, std::string> sample_composite(const Input& in, SpeedKind kind, const Options& opt,
                                                     const std::string& method, std::optional<long> pieces,
                                                     const std::optional<std::string>& target,
                                                     std::optional<long> max_pieces, long K, bool deviation);

/// Runs f() on a thread of its own under c's time budget and thread count,
/// the GIL released; the calling thread looks for signals every 50 ms and,
/// when a handler raises (Ctrl-C: KeyboardInterrupt), cancels f through
/// ScopedCancellation, waits for it to stop and re-raises the Python error.
/// \throws what f throws; py::error_already_set for a signal's exception.
template <class F>
auto guarded(const Common& c, F f) -> decltype(f()) {
  using R = decltype(f());
  if (c.timeout < 0) throw InvalidArgument("timeout must be positive seconds (or None)");
  if (c.threads != 0) in_range("threads", c.threads, 1, 64);
  std::atomic<bool> cancel{false};
  std::optional<R> result;
  std::exception_ptr error;
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  std::thread worker([&] {
    try {
      const ScopedCancellation cancellation(cancel);
      const ScopedWorkerCount workers(static_cast<std::size_t>(c.threads));
      std::optional<TimeBudget> budget;
      if (c.timeout > 0) budget.emplace(c.timeout);
      result.emplace(f());
    } catch (...) {
      error = std::current_exception();
    }
    flint_cleanup();  // this thread's FLINT/Arb caches
    {
      std::lock_guard<std::mutex> lock(m);
      done = true;
    }
    cv.notify_all();
  });
  bool interrupted = false;
  for (;;) {
    bool finished;
    {
      py::gil_scoped_release release;
      std::unique_lock<std::mutex> lock(m);
      finished = cv.wait_for(lock, std::chrono::milliseconds(interrupted ? 1000 : 50), [&] { return done; });
    }
    if (finished) break;
    if (!interrupted && PyErr_CheckSignals() != 0) {
      interrupted = true;
      cancel = true;
    }
  }
  worker.join();
  if (interrupted) throw py::error_already_set();
  if (error) std::rethrow_exception(error);
  return std::move(*result);
}

}  // namespace uniparam::python_support
