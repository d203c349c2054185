// python/src/module.cpp -- uniparam._uniparam, the compiled half of the
// Python package `uniparam` (python/uniparam/ holds the other half).
//
// Every function takes the curve and the options as plain values, runs the
// library (reparam/, the same calls as the CLI's commands) and returns the
// command's JSON document as text (cli/json_reports.hpp and, for composite
// curves, cli/composite.hpp: the very code the CLI prints with --json), which
// uniparam/__init__.py turns into Python objects. Computations run on a thread of their own with the GIL released;
// the calling thread waits, looking for signals every 50 ms, and on Ctrl-C
// (KeyboardInterrupt) cancels the computation through the library's
// ScopedCancellation (core/budget.hpp), which stops it at its next budget
// check. C++ exceptions become the classes of uniparam._errors.
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
using namespace uniparam;

namespace {

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

long in_range(const char* name, long v, long lo, long hi) {
  if (v < lo || v > hi)
    throw InvalidArgument(std::string(name) + " must be an integer from " + std::to_string(lo) + " to " +
                          std::to_string(hi) + ", got " + std::to_string(v));
  return v;
}

/// The options of c, in the CLI's ranges (read_options).
Options options_of(const Common& c) {
  Options o;
  o.digits = in_range("digits", c.digits, 1, 10000);
  o.max_prec = c.max_prec == 0 ? default_max_prec(o.digits) : in_range("max_prec", c.max_prec, 64, 1L << 24);
  o.max_degree = in_range("max_degree", c.max_degree, 1, 20000);
  return o;
}

/// The curve of c: the Bezier curve of control (and weights), else the text
/// read with the CLI's parse limits (read_curve, read_parse_limits).
Curve curve_of(const Common& c) {
  const Options o = options_of(c);
  if (!c.control.empty()) {
    BezierCurve b = BezierCurve::parse(c.control, c.weights, static_cast<std::size_t>(o.max_degree) + 1);
    if (!c.weights.empty() && !b.is_rational()) throw InvalidArgument("weights: empty list");
    return b.to_curve();
  }
  if (!c.weights.empty()) throw InvalidArgument("weights need control points (a rational Bezier curve)");
  ParseLimits lim;
  lim.max_degree = o.max_degree;
  lim.max_exponent = lim.max_degree;
  lim.max_bits = in_range("max_bits", c.max_bits, 64, 1L << 40);
  lim.max_length = static_cast<std::size_t>(in_range("max_length", c.max_length, 1, 1L << 30));
  lim.max_depth = static_cast<int>(in_range("max_depth", c.max_depth, 1, 1L << 30));
  return Curve::parse(c.curve, lim);
}

/// How the composite readers' messages name the Python parameters.
cli::CompositeNames python_names() {
  cli::CompositeNames n;
  n.svg = "svg";
  n.subpath = "subpath=K";
  n.max_degree = "max_degree";
  n.subpaths_hint = "";
  return n;
}

/// The composite curve of c's svg or nurbs, or nullopt for a curve given as
/// text or control points (the CLI's read_composite, with the text given
/// directly; a NURBS text longer than max_length is refused as the CLI
/// refuses such a file).
std::optional<CompositeCurve> composite_of(const Common& c) {
  if (c.subpath && !c.svg) throw InvalidArgument("subpath needs an SVG path (Curve.svg)");
  if (!c.svg && !c.nurbs) return std::nullopt;
  const Options o = options_of(c);
  const std::size_t max_length = static_cast<std::size_t>(in_range("max_length", c.max_length, 1, 1L << 30));
  if (c.svg) {
    const std::vector<PathInput> paths = cli::read_svg_subpaths(*c.svg, max_length, python_names());
    std::optional<std::size_t> k;
    if (c.subpath) k = static_cast<std::size_t>(in_range("subpath", *c.subpath, 0, static_cast<long>(paths.size()) - 1));
    return cli::svg_composite(paths, k, o, python_names());
  }
  if (c.nurbs->size() > max_length)
    throw BudgetExceeded("nurbs: the text holds more than " + std::to_string(max_length) +
                         " characters (the limit for nurbs; raise it with max_length)");
  return cli::read_nurbs_composite(*c.nurbs, o, python_names());
}

/// The input of a command: a composite curve of several segments (with its
/// description, as the CLI's), or one curve (a path or spline of one segment
/// is that segment, as in the CLI).
struct Input {
  std::optional<CompositeCurve> composite;
  std::optional<Curve> curve;
  std::string description;
};

Input input_of(const Common& c) {
  Input in;
  if (std::optional<CompositeCurve> cc = composite_of(c)) {
    if (cc->size() == 1) {
      in.curve = cc->segment(0);
      return in;
    }
    in.description =
        cli::composite_description(c.svg ? cli::CompositeSource::Svg : cli::CompositeSource::Nurbs, *cc);
    in.composite = std::move(cc);
    return in;
  }
  in.curve = curve_of(c);
  return in;
}

/// An exact rational given as text to parameter `name` (as the CLI's
/// read_rational, naming the Python parameter).
Rational rational_arg(const std::string& name, const std::string& text) {
  const auto e = text.find_first_of("eE");
  if (text.size() > 100000 || (e != std::string::npos && text.size() - e > 5))
    throw InvalidArgument(name + ": the number '" + text.substr(0, 20) + (text.size() > 20 ? "..." : "") +
                          "' is too large (at most 100000 characters and a decimal exponent below 1000)");
  try {
    return Rational::parse(text);
  } catch (const Error& ex) {
    throw InvalidArgument(name + ": '" + text.substr(0, 40) + (text.size() > 40 ? "..." : "") +
                          "' is not a rational number such as 1/3, 0.25 or 1e-3 (" + ex.what() + ")");
  }
}

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

std::string dump(const Json& j) { return j.dump(-1); }

/// The reparameterization `method` (radical, c0, c1, none) of cli's
/// read_method, with its checks.
Reparameterization method_of(const std::string& method, const Curve& cv, SpeedKind kind, const Options& opt,
                             std::optional<long> pieces, const std::optional<std::string>& target,
                             std::optional<long> max_pieces, bool with_none) {
  const std::string& m = method;
  if (m != "radical" && m != "c0" && m != "c1" && !(with_none && m == "none"))
    throw InvalidArgument("unknown method '" + m + "' (expected radical, c0, c1" +
                          std::string(with_none ? " or none)" : ")"));
  if (pieces && m != "c0") throw InvalidArgument("pieces applies to method c0 only");
  if (target && m != "c1") throw InvalidArgument("target applies to method c1 only");
  if (max_pieces && m != "c1") throw InvalidArgument("max_pieces applies to method c1 only");
  if (m == "radical") return Reparameterization(radical(cv, kind, opt));
  if (m == "c0") return Reparameterization(reparam_c0(cv, kind, in_range("pieces", pieces.value_or(3), 1, 1000), opt));
  if (m == "c1") {
    const Rational t = rational_arg("target", target.value_or("0.99"));
    if (t <= Rational(0) || t >= Rational(1))
      throw InvalidArgument("target must lie strictly between 0 and 1, got " + t.str());
    return Reparameterization(reparam_c1(cv, kind, t, opt, in_range("max_pieces", max_pieces.value_or(64), 1, 1000)));
  }
  const UniformityResult u = uniformity(cv, kind, opt);
  return Reparameterization::identity(u.mu, u.u);
}

MoebiusResult finish(const Curve& cv, const MoebiusResult& r, bool rational, std::optional<long> rational_digits,
                     const Options& opt) {
  if (rational_digits && !rational) throw InvalidArgument("rational_digits needs rational=True");
  const long rd = in_range("rational_digits", rational_digits.value_or(8), 1, 100);
  return rational ? make_rational(cv, r, rd, opt) : r;
}

std::vector<RealAlgebraic> breakpoints_of(const std::vector<std::string>& list) {
  std::vector<RealAlgebraic> T;
  for (const auto& s : list) T.emplace_back(rational_arg("breakpoints", s));
  return T;
}

/// The answer of a command with --output: ("report", its JSON document),
/// ("nurbs", the NURBS JSON) or ("step", the STEP text), and the C1 map's
/// missed-target message.
using Answer = std::tuple<std::string, std::string, std::string>;

/// The output form `output` names ("" none; "nurbs", "step" or a .stp/.step
/// file, checked writable before computing: cli::parse_nurbs_output).
cli::NurbsOutput output_of(const std::string& output) {
  if (output.empty()) return cli::NurbsOutput{};
  try {
    return cli::parse_nurbs_output(output);
  } catch (const InvalidArgument& e) {
    const std::string m = e.what();
    throw InvalidArgument(m.rfind("--output", 0) == 0 ? "output" + m.substr(8) : m);
  }
}

/// The NURBS n as `o` asks, as the CLI's write_nurbs: the NURBS JSON or the
/// STEP text in place of `report`, or the STEP file written and `report`.
Answer nurbs_answer(const Nurbs& n, const cli::NurbsOutput& o, long digits, const std::function<Json()>& report,
                    const std::string& missed) {
  if (o.form == cli::NurbsOutput::Form::Json) return Answer("nurbs", dump(cli::nurbs_json(n, digits)), missed);
  if (o.form == cli::NurbsOutput::Form::Step && o.file.empty())
    return Answer("step", cli::nurbs_step(n, "uniparam.stp"), missed);
  Json doc = report();  // the report first, then the file (as the CLI)
  if (o.form == cli::NurbsOutput::Form::Step) {
    try {
      cli::write_nurbs(n, o, digits);
    } catch (const Error&) {
      throw;
    } catch (const std::runtime_error& e) {
      throw InvalidArgument(e.what());
    }
  }
  return Answer("report", dump(doc), missed);
}

/// The C1 map's message when it missed its target ("" otherwise).
std::string missed(const MoebiusResult& r, long max_pieces, long digits) {
  if (!r.target.used || r.target.reached) return "";
  return cli::target_missed_message(r, max_pieces, digits);
}

/// The map of `method` (radical, c0, c1, none) for a composite curve, as
/// the CLI's read_composite_method: pieces (c0; default max(3, segments)),
/// target (c1; default 0.99), max_pieces (c1, per segment).
CompositeMethod composite_method_of(const std::string& m, const CompositeCurve& cc, std::optional<long> pieces,
                                    const std::optional<std::string>& target, std::optional<long> max_pieces,
                                    bool with_none) {
  if (m != "radical" && m != "c0" && m != "c1" && !(with_none && m == "none"))
    throw InvalidArgument("unknown method '" + m + "' (expected radical, c0, c1" +
                          std::string(with_none ? " or none)" : ")"));
  if (pieces && m != "c0") throw InvalidArgument("pieces applies to method c0 only");
  if (target && m != "c1") throw InvalidArgument("target applies to method c1 only");
  if (max_pieces && m != "c1") throw InvalidArgument("max_pieces applies to method c1 only");
  CompositeMethod cm;
  if (m == "radical") cm.kind = CompositeMethod::Kind::Radical;
  if (m == "c0") {
    cm.kind = CompositeMethod::Kind::Pieces;
    cm.pieces = in_range("pieces", pieces.value_or(std::max<long>(3, static_cast<long>(cc.size()))), 1, 1000);
  }
  if (m == "c1") {
    cm.kind = CompositeMethod::Kind::Target;
    cm.target = rational_arg("target", target.value_or("0.99"));
    if (cm.target <= Rational(0) || cm.target >= Rational(1))
      throw InvalidArgument("target must lie strictly between 0 and 1, got " + cm.target.str());
    cm.max_pieces = in_range("max_pieces", max_pieces.value_or(64), 1, 1000);
  }
  return cm;
}

/// `m` with rational (and rational_digits) as the CLI's with_rational.
CompositeMethod with_rational(CompositeMethod m, bool rational, std::optional<long> rational_digits) {
  if (rational_digits && !rational) throw InvalidArgument("rational_digits needs rational=True");
  m.rational = rational;
  m.rational_digits = in_range("rational_digits", rational_digits.value_or(8), 1, 100);
  return m;
}

/// radical, moebius and reparam on a composite curve (the CLI's
/// run_map_composite): the report, or the NURBS of p o r as `no` asks.
Answer composite_answer(const Input& in, SpeedKind kind, const Options& opt, const CompositeMethod& m, Format fmt,
                        const cli::NurbsOutput& no) {
  const CompositeCurve& cc = *in.composite;
  const std::vector<Speed> sp = cc.speeds(kind);
  const CompositeMap r = composite_map(cc, sp, m, opt);
  const bool missed = m.kind == CompositeMethod::Kind::Target && !r.target_reached();
  const std::string message = missed ? cli::composite_target_missed_message(m) : "";
  auto report = [&] {
    return cli::composite_map_json(in.description, cc, kind, opt.digits, m, r, joints(cc, 128), fmt);
  };
  if (no.form == cli::NurbsOutput::Form::None) return Answer("report", dump(report()), message);
  return nurbs_answer(composite_nurbs(cc, r, cli::nurbs_prec(opt)), no, opt.digits, report, message);
}

/// sample on a composite curve (the CLI's run_sample_composite): the
/// document and the missed-target message.
std::pair<std::string, std::string> sample_composite(const Input& in, SpeedKind kind, const Options& opt,
                                                     const std::string& method, std::optional<long> pieces,
                                                     const std::optional<std::string>& target,
                                                     std::optional<long> max_pieces, long K, bool deviation) {
  const CompositeCurve& cc = *in.composite;
  if (method == "exact" && (pieces || target || max_pieces))
    throw InvalidArgument("pieces, target and max_pieces do not apply to method exact");
  if (method == "exact" && deviation)
    throw InvalidArgument("deviation measures a map's rows against method exact's; it does not apply to "
                          "method exact itself");
  const std::vector<Speed> sp = cc.speeds(kind);
  Json rows = Json::array();
  if (method == "exact") {
    Json j = cli::composite_sample_header_json(in.description, cc, kind, "exact", nullptr, opt.digits, K);
    Ball mu;
    exact_samples_each(cc, sp, K, opt, mu, [&](long k, const LocatedPoint& p) {
      rows.push(cli::sample_row_json(cli::exact_sample_row(k, K, p, mu), opt.digits));
    });
    j.set("mu", json_ball(mu, cli::printed_digits(opt.digits)));
    j.set("samples", rows);
    return std::make_pair(dump(j), std::string());
  }
  const CompositeMethod cm = composite_method_of(method, cc, pieces, target, max_pieces, true);
  Options ropt = opt;
  ropt.digits = opt.digits + 3;
  const CompositeMap r = composite_map(cc, sp, cm, ropt);
  Json j = cli::composite_sample_header_json(in.description, cc, kind, method == "none" ? "none" : r.method(), &r,
                                             opt.digits, K);
  CompositeSampler smp(cc, sp, r, opt.digits, opt.max_prec);
  std::unique_ptr<ArcFraction> frac;
  if (deviation) frac = std::make_unique<ArcFraction>(cc, sp, digits_to_bits(opt.digits) + 8, opt);
  Ball worst(0);
  const long pd = cli::printed_digits(opt.digits);
  for (long k = 0; k < K; ++k) {
    check_time_budget();
    const SamplePoint p = smp.at(Rational(k, K - 1));
    Json row = cli::sample_row_json(p, opt.digits);
    if (deviation) row.set("deviation", json_ball(cli::row_deviation(*frac, p, opt.digits, worst), pd));
    rows.push(row);
  }
  j.set("samples", rows);
  if (deviation) j.set("max_deviation", json_ball(worst, pd));
  std::string message;
  if (cm.kind == CompositeMethod::Kind::Target && !r.target_reached())
    message = "the target u >= " + cm.target.str() + " was not reached on every segment; the best map was sampled";
  return std::make_pair(dump(j), message);
}

}  // namespace

PYBIND11_MODULE(_uniparam, m) {
  m.doc() = "The compiled part of uniparam (see the package uniparam).";

  py::class_<Common>(m, "Common")
      .def(py::init<>())
      .def_readwrite("curve", &Common::curve)
      .def_readwrite("control", &Common::control)
      .def_readwrite("weights", &Common::weights)
      .def_readwrite("svg", &Common::svg)
      .def_readwrite("subpath", &Common::subpath)
      .def_readwrite("nurbs", &Common::nurbs)
      .def_readwrite("speed", &Common::speed)
      .def_readwrite("digits", &Common::digits)
      .def_readwrite("max_prec", &Common::max_prec)
      .def_readwrite("max_degree", &Common::max_degree)
      .def_readwrite("max_bits", &Common::max_bits)
      .def_readwrite("max_length", &Common::max_length)
      .def_readwrite("max_depth", &Common::max_depth)
      .def_readwrite("timeout", &Common::timeout)
      .def_readwrite("threads", &Common::threads);

  // Exceptions: the classes of uniparam._errors, most derived first. The
  // references are kept for the process's lifetime (never released: a static
  // py::object would be destroyed after the interpreter has finalized).
  py::module_ errors = py::module_::import("uniparam._errors");
  auto keep = [&](const char* name) { return py::object(errors.attr(name)).release(); };
  static const py::handle parse_error = keep("ParseError");
  static const py::handle domain_error = keep("DomainError");
  static const py::handle invalid_argument = keep("InvalidArgument");
  static const py::handle time_limit = keep("TimeLimitExceeded");
  static const py::handle budget_exceeded = keep("BudgetExceeded");
  static const py::handle base_error = keep("Error");
  py::register_exception_translator([](std::exception_ptr p) {
    auto raise = [](py::handle cls, py::object value) { PyErr_SetObject(cls.ptr(), value.ptr()); };
    try {
      std::rethrow_exception(p);
    } catch (const ParseError& e) {
      raise(parse_error, parse_error(e.what(), e.column(), e.expected()));
    } catch (const Interrupted& e) {
      PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
    } catch (const TimeLimitExceeded& e) {
      raise(time_limit, time_limit(e.what()));
    } catch (const BudgetExceeded& e) {
      raise(budget_exceeded, budget_exceeded(e.what()));
    } catch (const DomainError& e) {
      raise(domain_error, domain_error(e.what()));
    } catch (const InvalidArgument& e) {
      raise(invalid_argument, invalid_argument(e.what()));
    } catch (const Error& e) {
      raise(base_error, base_error(e.what()));
    }
  });

  m.def(
      "curve_text",
      [](const Common& c) {
        return guarded(c, [&] {
          const Input in = input_of(c);
          return in.composite ? in.description : in.curve->str();
        });
      },
      "The canonical text of the curve of c (Curve::str()), or the CLI's description of a composite curve.");

  m.def(
      "curve_parts",
      [](const Common& c) {
        return guarded(c, [&] {
          Input in = input_of(c);
          const CompositeCurve cc = in.composite ? std::move(*in.composite) : CompositeCurve(*in.curve);
          std::vector<std::string> segments, knots, labels;
          for (std::size_t j = 0; j < cc.size(); ++j) {
            segments.push_back(cc.segment(j).str());
            labels.push_back(cc.label(j));
          }
          for (const Rational& k : cc.knots()) knots.push_back(k.str());
          return std::make_tuple(segments, knots, labels);
        });
      },
      "The segments' texts, the knots (exact rationals as text) and the labels of the curve of c.");

  m.def(
      "uniformity",
      [](const Common& c) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          const Input in = input_of(c);
          if (in.composite)
            return dump(cli::composite_uniformity_json(in.description, *in.composite, kind, opt.digits,
                                                       uniformity(*in.composite, kind, opt)));
          const Curve& cv = *in.curve;
          return dump(cli::uniformity_json(cv, kind, opt.digits, uniformity(cv, kind, opt)));
        });
      },
      py::arg("common"));

  m.def(
      "radical",
      [](const Common& c, const std::string& format, const std::optional<std::string>& at) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          const Format fmt = cli::parse_format(format);
          const Input in = input_of(c);
          if (in.composite) {
            if (at) throw InvalidArgument("at on a composite curve: use sample() (its rows are r(s))");
            CompositeMethod m;
            m.kind = CompositeMethod::Kind::Radical;
            return std::get<1>(composite_answer(in, kind, opt, m, fmt, cli::NurbsOutput{}));
          }
          const Curve& cv = *in.curve;
          std::optional<Rational> z;
          if (at) {
            z = rational_arg("at", *at);
            if (*z < Rational(0) || *z > Rational(1)) throw InvalidArgument("at must lie in [0, 1], got " + z->str());
          }
          const RadicalResult r = radical(cv, kind, opt);
          std::optional<SamplePoint> atv;
          if (z) {
            const Speed s(cv, kind);
            Sampler ev(cv, s, Reparameterization(r), opt.digits + 1, opt.max_prec);
            atv = ev.at(*z);
          }
          Json j = cli::radical_json(cv, r, opt.digits, fmt);
          if (atv) j.set("at", cli::radical_at_json(*z, *atv, opt.digits));
          return dump(j);
        });
      },
      py::arg("common"), py::arg("format"), py::arg("at"));

  m.def(
      "moebius",
      [](const Common& c, const std::optional<std::vector<std::string>>& breakpoints, const std::string& format,
         bool rational, std::optional<long> rational_digits, const std::string& output) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          cli::MoebiusPrint how;
          how.json = true;
          how.format = cli::parse_format(format);
          const auto T = breakpoints_of(breakpoints.value_or(std::vector<std::string>{"0", "1"}));
          const cli::NurbsOutput no = output_of(output);
          const Input in = input_of(c);
          if (in.composite) {
            CompositeMethod m;
            m.kind = breakpoints ? CompositeMethod::Kind::Breakpoints : CompositeMethod::Kind::Moebius;
            for (const RealAlgebraic& t : T) m.breakpoints.push_back(t.rational());
            return composite_answer(in, kind, opt, with_rational(m, rational, rational_digits), how.format, no);
          }
          const Curve& cv = *in.curve;
          const MoebiusResult r = finish(cv, moebius_c0(cv, kind, T, opt), rational, rational_digits, opt);
          auto report = [&] { return cli::moebius_json(cv, r, opt.digits, how); };
          if (no.form == cli::NurbsOutput::Form::None) return Answer("report", dump(report()), "");
          return nurbs_answer(moebius_nurbs(cv, r, cli::nurbs_prec(opt)), no, opt.digits, report, "");
        });
      },
      py::arg("common"), py::arg("breakpoints"), py::arg("format"), py::arg("rational"), py::arg("rational_digits"),
      py::arg("output"));

  m.def(
      "reparam",
      [](const Common& c, std::optional<long> pieces, const std::vector<std::string>& breakpoints,
         const std::optional<std::string>& target, std::optional<long> max_pieces, const std::string& format,
         bool rational, std::optional<long> rational_digits, const std::string& output) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          cli::MoebiusPrint how;
          how.json = true;
          how.format = cli::parse_format(format);
          const int given = static_cast<int>(pieces.has_value()) + static_cast<int>(!breakpoints.empty()) +
                            static_cast<int>(target.has_value());
          if (given != 1) throw InvalidArgument("give exactly one of pieces, breakpoints, target");
          if (max_pieces && !target) throw InvalidArgument("max_pieces needs target");
          const long mp = in_range("max_pieces", max_pieces.value_or(64), 1, cli::kMaxPiecesLimit);
          Rational t;
          if (pieces) in_range("pieces", *pieces, 1, 1000);
          const auto T = breakpoints_of(breakpoints);
          if (target) {
            t = rational_arg("target", *target);
            if (!(t.sign() > 0 && t < Rational(1)))
              throw InvalidArgument("target must lie strictly between 0 and 1, got " + *target);
          }
          const cli::NurbsOutput no = output_of(output);
          const Input in = input_of(c);
          if (in.composite) {
            CompositeMethod m;
            m.kind = pieces       ? CompositeMethod::Kind::Pieces
                     : !T.empty() ? CompositeMethod::Kind::Breakpoints
                                  : CompositeMethod::Kind::Target;
            m.pieces = pieces.value_or(0);
            for (const RealAlgebraic& x : T) m.breakpoints.push_back(x.rational());
            m.target = t;
            m.max_pieces = mp;
            return composite_answer(in, kind, opt, with_rational(m, rational, rational_digits), how.format, no);
          }
          const Curve& cv = *in.curve;
          MoebiusResult r = pieces       ? reparam_c0(cv, kind, *pieces, opt)
                            : !T.empty() ? moebius_c0(cv, kind, T, opt)
                                         : reparam_c1(cv, kind, t, opt, mp);
          r = finish(cv, r, rational, rational_digits, opt);
          auto report = [&] { return cli::moebius_json(cv, r, opt.digits, how); };
          if (no.form == cli::NurbsOutput::Form::None) return Answer("report", dump(report()), missed(r, mp, opt.digits));
          return nurbs_answer(moebius_nurbs(cv, r, cli::nurbs_prec(opt)), no, opt.digits, report,
                              missed(r, mp, opt.digits));
        });
      },
      py::arg("common"), py::arg("pieces"), py::arg("breakpoints"), py::arg("target"), py::arg("max_pieces"),
      py::arg("format"), py::arg("rational"), py::arg("rational_digits"), py::arg("output"));

  m.def(
      "bezier",
      [](const Common& c, const std::string& exact_weights, const std::string& output) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const cli::NurbsOutput no = output_of(output);
          if (c.svg || c.nurbs)
            throw InvalidArgument("bezier takes one Bezier curve, given by its control points; for a path or a "
                                  "spline, moebius(curve, speed=\"parametric\") gives each segment its optimal "
                                  "Moebius map");
          if (c.control.empty()) throw InvalidArgument("bezier needs control points");
          BezierCurve bz = BezierCurve::parse(c.control, c.weights, static_cast<std::size_t>(opt.max_degree) + 1);
          if (!c.weights.empty() && !bz.is_rational()) throw InvalidArgument("weights: empty list");
          const BezierResult r = bezier_optimal(bz, opt);
          const bool expanded = cli::expand_weights(exact_weights, r, bz.degree());
          auto report = [&] { return cli::bezier_json(bz, r, opt.digits, expanded); };
          if (no.form == cli::NurbsOutput::Form::None) return Answer("report", dump(report()), "");
          Nurbs n = bezier_nurbs(bz, r, cli::nurbs_prec(opt));
          if (!expanded && n.kind == Nurbs::Kind::Surd) {  // surds too long to print: the balls (as the CLI)
            n.kind = Nurbs::Kind::Balls;
            n.weights_surd.clear();
          }
          return nurbs_answer(n, no, opt.digits, report, "");
        });
      },
      py::arg("common"), py::arg("exact_weights"), py::arg("output"));

  m.def(
      "locate",
      [](const Common& c, const std::string& option, const std::string& value) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          const Rational v = rational_arg(option, value);
          const LocateTarget target = option == "fraction" ? LocateTarget::Fraction : LocateTarget::Integral;
          const Input in = input_of(c);
          if (in.composite) {
            const std::vector<Speed> sp = in.composite->speeds(kind);
            LocateResult r;
            try {
              r = locate(*in.composite, sp, v, target, opt);
            } catch (const InvalidArgument& e) {
              throw InvalidArgument(option + ": " + e.what());
            }
            return dump(cli::composite_locate_json(in.description, kind, opt.digits, option, v, r));
          }
          const Curve& cv = *in.curve;
          check_degree(cv, opt);
          const Speed s(cv, kind);
          LocateResult r;
          try {
            r = locate(cv, s, v, target, opt);
          } catch (const InvalidArgument& e) {
            throw InvalidArgument(option + ": " + e.what());
          }
          return dump(cli::locate_json(cv, kind, opt.digits, option, v, r));
        });
      },
      py::arg("common"), py::arg("option"), py::arg("value"));

  m.def(
      "sample",
      [](const Common& c, const std::string& method, std::optional<long> pieces,
         const std::optional<std::string>& target, std::optional<long> max_pieces, long K, bool deviation) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          in_range("points", K, 2, 1000000);
          const Input in = input_of(c);
          if (in.composite) return sample_composite(in, kind, opt, method, pieces, target, max_pieces, K, deviation);
          const Curve& cv = *in.curve;
          const long pd = cli::printed_digits(opt.digits);
          if (method == "exact") {
            if (pieces || target || max_pieces)
              throw InvalidArgument("pieces, target and max_pieces do not apply to method exact");
            if (deviation)
              throw InvalidArgument("deviation measures a map's rows against method exact's; it does not apply to "
                                    "method exact itself");
            check_degree(cv, opt);
            const Speed sp(cv, kind);
            Ball mu;
            Json rows = Json::array();
            exact_samples_each(cv, sp, K, opt, mu, [&](long k, const LocatedPoint& p) {
              rows.push(cli::sample_row_json(cli::exact_sample_row(k, K, p, mu), opt.digits));
            });
            Json j = cli::sample_exact_header_json(cv, kind, opt.digits, K);
            j.set("mu", json_ball(mu, pd));
            j.set("samples", rows);
            return std::make_pair(dump(j), std::string());
          }
          Options ropt = opt;
          ropt.digits = opt.digits + 3;
          const Reparameterization r = method_of(method, cv, kind, ropt, pieces, target, max_pieces, true);
          const Speed sp(cv, kind);
          std::unique_ptr<ArcFraction> frac;
          if (deviation) frac = std::make_unique<ArcFraction>(sp, digits_to_bits(opt.digits) + 8, opt);
          Ball worst(0);
          Json rows = Json::array();
          sample_each(cv, sp, r, K, opt.digits, opt.max_prec, [&](long, const SamplePoint& p) {
            Json row = cli::sample_row_json(p, opt.digits);
            if (deviation) row.set("deviation", json_ball(cli::row_deviation(*frac, p, opt.digits, worst), pd));
            rows.push(row);
          });
          Json j = cli::sample_header_json(cv, kind, r, opt.digits, K);
          j.set("samples", rows);
          if (deviation) j.set("max_deviation", json_ball(worst, pd));
          const auto* mr = r.moebius_result();
          return std::make_pair(dump(j), mr ? missed(*mr, max_pieces.value_or(64), opt.digits) : std::string());
        });
      },
      py::arg("common"), py::arg("method"), py::arg("pieces"), py::arg("target"), py::arg("max_pieces"),
      py::arg("points"), py::arg("deviation"));

  m.def(
      "plot",
      [](const Common& c, const std::string& method, std::optional<long> pieces,
         const std::optional<std::string>& target, std::optional<long> max_pieces, long K,
         const std::string& projection) {
        return guarded(c, [&] {
          const Options opt = options_of(c);
          const SpeedKind kind = parse_speed_kind(c.speed);
          in_range("points", K, 2, 100000);
          const Input in = input_of(c);
          if (in.composite) {
            const CompositeMethod m = composite_method_of(method, *in.composite, pieces, target, max_pieces, false);
            std::string message;
            const std::string svg =
                cli::composite_plot_svg(in.description, *in.composite, kind, m, K, projection, opt, [&] {
                  message = "the target u >= " + m.target.str() +
                            " was not reached on every segment; the best map is drawn";
                });
            return std::make_pair(svg, message);
          }
          const Curve& cv = *in.curve;
          const Reparameterization r = method_of(method, cv, kind, opt, pieces, target, max_pieces, false);
          const std::string svg = cli::plot_svg(cv, kind, r, K, projection, target.value_or("0.99"), opt);
          const auto* mr = r.moebius_result();
          return std::make_pair(svg, mr ? missed(*mr, max_pieces.value_or(64), opt.digits) : std::string());
        });
      },
      py::arg("common"), py::arg("method"), py::arg("pieces"), py::arg("target"), py::arg("max_pieces"),
      py::arg("points"), py::arg("projection"));

  m.def(
      "write_png",
      [](const std::string& svg, const std::string& path) {
        Common c;
        guarded(c, [&] {
          try {
            cli::svg::write_png(svg, path, 2);
          } catch (const Error&) {
            throw;
          } catch (const std::runtime_error& e) {
            throw InvalidArgument(e.what());
          }
          return 0;
        });
      },
      py::arg("svg"), py::arg("path"), "Renders svg to PNG at path with rsvg-convert (as uniparam plot -o F.png).");
}
