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
// check. C++ exceptions become the classes of uniparam._errors.//
// The readers of the arguments, the guarded run and the composite-curve
// commands are in module_support.cpp; this file binds the functions.
#include "module_support.hpp"

using namespace uniparam;
using namespace uniparam::python_support;

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
          if (at) z = cli::unit_at("at", rational_arg("at", *at));
          const RadicalResult r = radical(cv, kind, opt);
          std::optional<SamplePoint> atv;
          if (z) atv = cli::radical_at(cv, kind, r, *z, opt);
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
          const cli::MoebiusPrint how = json_print(format);
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
          const cli::MoebiusPrint how = json_print(format);
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
