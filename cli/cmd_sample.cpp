// cli/cmd_sample.cpp -- `uniparam sample CURVE`: K certified points of p o r
// at equally spaced parameters, as CSV (decimals) or JSON (balls); and the
// --method options shared with `uniparam plot`.
#include <algorithm>
#include <memory>
#include <iostream>
#include <string>

#include "commands.hpp"
#include "composite.hpp"
#include "output.hpp"
#include "json_reports.hpp"
#include "moebius_report.hpp"
#include "report.hpp"
#include "uniparam/reparam/locate.hpp"
#include "uniparam/reparam/sample.hpp"

namespace uniparam::cli {

std::vector<OptionSpec> method_options(bool with_none) {
  return {
      {"method", "M",
       std::string("reparameterization: radical (lifts zeros of the speed), c0 (C0 piecewise Moebius, "
                   "--pieces), c1 (C1 piecewise Moebius, --target)") +
           (with_none ? ", none (the original p)" : ""),
       "radical"},
      {"pieces", "N", "number of pieces for --method c0", "3"},
      {"target", "U", "target uniformity in (0, 1) for --method c1, e.g. 0.99", "0.99"},
      {"max-pieces", "N", "largest number of pieces --method c1 tries", "64"},
  };
}

void check_method_name(const std::string& m, bool pieces, bool target, bool max_pieces, bool with_none,
                       const std::string& flag) {
  if (m != "radical" && m != "c0" && m != "c1" && !(with_none && m == "none"))
    throw InvalidArgument("unknown method '" + m + "' (expected radical, c0, c1" +
                          std::string(with_none ? " or none)" : ")"));
  const std::string max_pieces_name = flag == "--" ? "max-pieces" : "max_pieces";
  if (pieces && m != "c0") throw InvalidArgument(flag + "pieces applies to " + flag + "method c0 only");
  if (target && m != "c1") throw InvalidArgument(flag + "target applies to " + flag + "method c1 only");
  if (max_pieces && m != "c1")
    throw InvalidArgument(flag + max_pieces_name + " applies to " + flag + "method c1 only");
}

std::string read_method_name(const Args& a, bool with_none) {
  const std::string m = a.get("method", "radical");
  check_method_name(m, a.has("pieces"), a.has("target"), a.has("max-pieces"), with_none, "--");
  return m;
}

Reparameterization read_method(const Args& a, const Curve& c, SpeedKind kind, const Options& opt, bool with_none) {
  const std::string m = read_method_name(a, with_none);
  if (m == "radical") return Reparameterization(radical(c, kind, opt));
  if (m == "c0") return Reparameterization(reparam_c0(c, kind, a.get_long("pieces", 3, 1, 1000), opt));
  if (m == "c1") {
    const Rational target = read_rational("target", a.get("target", "0.99"));
    if (target <= Rational(0) || target >= Rational(1))
      throw InvalidArgument("--target must lie strictly between 0 and 1, got " + target.str());
    return Reparameterization(reparam_c1(c, kind, target, opt, a.get_long("max-pieces", 64, 1, 1000)));
  }
  const UniformityResult u = uniformity(c, kind, opt);
  return Reparameterization::identity(u.mu, u.u);
}

int target_status(const Reparameterization& r, const std::string& command, const Args& a, long digits) {
  const auto* m = r.moebius_result();
  if (!m || !m->target.has_value() || m->target->reached) return 0;
  warn() << "uniparam " << command << ": "
         << target_missed_message(*m, a.get_long("max-pieces", 64, 1, 1000), digits, "used") << "\n";
  return 4;
}

std::string coordinate_name(std::size_t i, std::size_t n) {
  if (n <= 3) return std::string(1, "xyz"[i]);
  return "x" + std::to_string(i + 1);
}

CommandSpec sample_spec() {
  auto opts = common_options();
  for (auto o : method_options(true)) {
    if (o.name == "method")
      o.help += ", exact (points at exactly equal steps of arc length with --speed arclength, "
                "of turning angle with --speed angular; not a rational map)";
    opts.push_back(o);
  }
  opts.push_back({"points", "K", "number of points, at s = 0, 1/(K-1), ..., 1", "40"});
  opts.push_back({"format", "F", "csv (decimals) or json (certified balls; same as --json)", "csv"});
  opts.push_back({"deviation", "",
                  "add each row's distance from the exact equal step, |G(r(s))/mu - s| with G(t) = int_0^t sigma "
                  "(CSV: a certified upper bound; JSON: a ball, and the largest as \"max_deviation\")",
                  ""});
  return {"sample",
          "K points of the reparameterized curve p o r at equally spaced parameters.",
          "Points at equal arc length:  uniparam sample CURVE --method exact --speed arclength --points K\n"
          "\n"
          "Row k is s = k/(K-1) (first 0, last 1), t = r(s), the point p(r(s)) and the\n"
          "speed of p o r at s. Every value is certified to --digits digits: JSON gives\n"
          "balls {\"mid\", \"rad\"}, CSV the midpoints (decimals with D significant digits).\n"
          "Where s falls on a joint of r whose side cannot be decided, the speed is\n"
          "two-sided: CSV leaves it empty, JSON gives the union and \"at_joint\": true.\n"
          "--method none samples the original p (s = t). When --method c1 misses its\n"
          "target, the best map is sampled and the exit status is 4.\n"
          "--method exact: t is the parameter where int_0^t sigma = s mu exactly (equal\n"
          "steps of arc length for the parametric speed, of turning angle for the\n"
          "angular one); it is not rational, so there is no map to print, and the\n"
          "speed column is mu (the uniform speed). --deviation tells, for the other\n"
          "methods, how far their rows are from these (in fraction of mu).\n"
          "The map is certified before the first row; the rows then stream out as they\n"
          "are certified (r's data refined where a row needs it). A row that cannot be\n"
          "certified within --max-prec or --timeout ends the output with an error\n"
          "naming the rows written (exit 4).",
          {"CURVE"},
          opts};
}

Json sample_header_json(const Curve& c, SpeedKind kind, const Reparameterization& r, long digits, long K) {
  const long pd = printed_digits(digits);
  Json head = Json::object();
  head.set("curve", Json::string(c.str()));
  head.set("speed", Json::string(to_string(kind)));
  head.set("method", Json::string(r.method()));
  head.set("digits", Json::number(digits));
  head.set("points", Json::number(K));
  head.set("mu", json_ball(r.mu(), pd));
  head.set("u_before", json_ball(r.u_before(), pd));
  head.set("u_after", json_ball(r.u_after(), pd));
  Json js = json_balls(r.joints_s(), pd), jt = Json::array();
  for (const auto& t : r.joints_t()) jt.push(json_algebraic(t, digits));
  Json joints = Json::object();
  joints.set("s", js);
  joints.set("t", jt);
  head.set("joints", joints);
  return head;
}

Json sample_row_json(const SamplePoint& p, long digits) {
  const long pd = printed_digits(digits);
  Json row = Json::object();
  row.set("s", json_rational(p.s, pd));
  row.set("t", json_ball(p.t, pd));
  row.set("point", json_balls(p.point, pd));
  row.set("speed", json_ball(p.speed, pd));
  row.set("at_joint", Json::boolean(p.at_joint));
  return row;
}

Json sample_exact_header_json(const Curve& c, SpeedKind kind, long digits, long K) {
  Json head = Json::object();
  head.set("curve", Json::string(c.str()));
  head.set("speed", Json::string(to_string(kind)));
  head.set("method", Json::string("exact"));
  head.set("digits", Json::number(digits));
  head.set("points", Json::number(K));
  return head;
}

SamplePoint exact_sample_row(long k, long K, const LocatedPoint& p, const Ball& mu) {
  SamplePoint row;
  row.s = Rational(k, K - 1);
  row.t = p.t;
  row.point = p.point;
  row.speed = mu;
  return row;
}

Ball row_deviation(ArcFraction& frac, const SamplePoint& p, long digits, Ball& worst) {
  const long prec = 2 * digits_to_bits(digits) + 128;
  Ball d = frac.at(p.t), s(p.s, prec);
  arb_sub(d.get(), d.get(), s.get(), prec);
  arb_abs(d.get(), d.get());
  arb_max(worst.get(), worst.get(), d.get(), prec);
  return d;
}

namespace {

/// The bookkeeping of rows streamed to answer() (after stream_stdout()): a
/// failed write ends the command with status 1, a budget exceeded after the
/// first row with status 4, both saying how many rows went out.
struct RowStream {
  explicit RowStream(long k) : K(k) {}
  const long K;
  long written = 0;
  struct WriteFailed {};
  std::ostream& out = answer();

  /// Throws WriteFailed when the stream has failed; else counts the row.
  void row_done() {
    if (!out) throw WriteFailed{};
    ++written;
  }
  /// Writes row k of the "samples" array, as Json::dump(2) indents it two
  /// levels down (the header was written without its closing brace).
  void json_row(long k, const Json& row) {
    std::string line = k ? ",\n    " : "\n    ";
    for (char ch : row.dump(2)) {
      line += ch;
      if (ch == '\n') line += "    ";
    }
    out << line;
  }
  /// The message of a failed write, with the system's reason; returns 1.
  int write_failed() const {
    const std::string why = stdout_stream_error();
    warn() << "uniparam sample: cannot write the output to stdout" << (why.empty() ? "" : ": " + why) << " ("
              << written << " of " << K << " rows handed over; the output is incomplete)\n";
    return 1;
  }
  /// The budget error e, saying the output is incomplete.
  BudgetExceeded incomplete(const BudgetExceeded& e) const {
    return BudgetExceeded("the output is incomplete (" + std::to_string(written) + " of " + std::to_string(K) +
                          " rows written): " + e.what());
  }
};

// CSV's deviation column: a certified upper bound of |d|, rounded up to 3
// significant digits.
std::string upper_bound_text(const Ball& d) {
  arf_t u;
  arf_init(u);
  arb_get_abs_ubound_arf(u, d.get(), 64);
  Ball b(0);
  arb_add_error_arf(b.get(), u);
  arf_clear(u);
  return b.rad_decimal();
}

// Streams the rows `each` hands over: the header (JSON: `head` with the
// rows as "samples" last; CSV: the column line) goes out before the first
// row -- at once, or, with `late_mu`, at the first row with "mu" from there
// (certified by then). With `deviation`, each row gets its deviation and
// JSON ends with "max_deviation" = *worst. A failed write gives status 1; a
// budget exceeded after the header, the error saying how many rows went out.
int stream_samples(Json head, std::size_t n, long K, const std::string& format, const Options& opt,
                   const std::function<void(const SampleSink&)>& each,
                   const std::function<Ball(const SamplePoint&)>& deviation = {}, const Ball* worst = nullptr,
                   const Ball* late_mu = nullptr) {
  const long pd = printed_digits(opt.digits);
  RowStream rows(K);
  std::ostream& out = rows.out;
  bool started = false;
  auto start = [&]() {
    started = true;
    stream_stdout();
    if (format == "json") {
      if (late_mu) head.set("mu", json_ball(*late_mu, pd));
      // The document as Json::dump(2) would print it with "samples" last:
      // the header without its closing brace, then each row indented.
      std::string text = head.dump(2);
      text.resize(text.size() - 2);  // "\n}"
      out << text << ",\n  \"samples\": [";
    } else {
      out << "s,t";
      for (std::size_t i = 0; i < n; ++i) out << "," << coordinate_name(i, n);
      out << ",speed" << (deviation ? ",deviation" : "") << "\n";
    }
  };
  if (!late_mu) start();
  try {
    each([&](long k, const SamplePoint& p) {
      if (!started) start();
      if (format == "json") {
        Json row = sample_row_json(p, opt.digits);
        if (deviation) row.set("deviation", json_ball(deviation(p), pd));
        rows.json_row(k, row);
      } else {
        std::string line = decimal_string(p.s, opt.digits) + "," + p.t.mid_decimal(opt.digits);
        for (const auto& b : p.point) line += "," + b.mid_decimal(opt.digits);
        line += ",";
        if (!p.at_joint) line += p.speed.mid_decimal(opt.digits);
        if (deviation) line += "," + upper_bound_text(deviation(p));
        out << line << "\n";
      }
      rows.row_done();
    });
  } catch (const BudgetExceeded& e) {
    if (!started) throw;
    out.flush();
    throw rows.incomplete(e);
  } catch (const RowStream::WriteFailed&) {
    return rows.write_failed();
  }
  if (format == "json") {
    out << "\n  ]";
    if (deviation && worst) {
      std::string m = json_ball(*worst, pd).dump(2), indented;
      for (char ch : m) {
        indented += ch;
        if (ch == '\n') indented += "  ";
      }
      out << ",\n  \"max_deviation\": " << indented;
    }
    out << "\n}\n";
  }
  out.flush();
  if (!out) return rows.write_failed();
  return 0;
}

// sample --method exact: the rows of exact_samples_each, streamed as the
// other methods' rows (same columns; the speed of the exactly uniform
// parameterization is mu at every s). mu is certified before the first
// row; the header goes out with it.
int run_sample_exact(const Args& a, const Curve& c, SpeedKind kind, const Options& opt, long K,
                     const std::string& format) {
  for (const char* o : {"pieces", "target", "max-pieces"})
    if (a.has(o)) throw InvalidArgument(std::string("--") + o + " does not apply to --method exact");
  if (a.flag("deviation"))
    throw InvalidArgument("--deviation measures a map's rows against --method exact's; it does not apply to "
                          "--method exact itself");
  check_degree(c, opt);
  const Speed sp(c, kind);
  Json head = sample_exact_header_json(c, kind, opt.digits, K);
  Ball mu;
  return stream_samples(head, c.dimension(), K, format, opt, [&](const SampleSink& sink) {
    exact_samples_each(c, sp, K, opt, mu, [&](long k, const LocatedPoint& p) {
      sink(k, exact_sample_row(k, K, p, mu));
    });
  }, {}, nullptr, &mu);
}

int run_sample_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt, long K,
                         const std::string& format);

}  // namespace

int run_sample(int argc, char** argv) {
  const CommandSpec spec = sample_spec();
  Args a = parse_args(spec, argc, argv, 2);
  if (a.help) { answer() << help_text(spec); return 0; }
  const Options opt = read_options(a);
  const SpeedKind kind = parse_speed_kind(a.get("speed", "angular"));
  const long K = a.get_long("points", 40, 2, 1000000);
  std::string format = a.get("format", a.flag("json") ? "json" : "csv");
  if (format != "csv" && format != "json")
    throw InvalidArgument("unknown format '" + format + "' (expected csv or json)");
  if (a.flag("json") && format != "json") throw InvalidArgument("--json conflicts with --format " + format);
  if (auto cc = read_composite(a); cc && cc->size() > 1) return run_sample_composite(a, *cc, kind, opt, K, format);
  const Curve c = read_curve(a);
  if (a.get("method", "radical") == "exact") return run_sample_exact(a, c, kind, opt, K, format);
  // The map is certified completely (u, joints, data to 3 more digits than
  // the samples) before the first byte; the samples then stream out one row
  // at a time (memory independent of K). A sample refines r's data when it
  // needs more (Sampler): that can fail only at the --max-prec or --timeout
  // budget, and then the rows written so far are followed by an error and
  // exit status 4 (see incomplete()).
  Options ropt = opt;
  ropt.digits = opt.digits + 3;
  const Reparameterization r = read_method(a, c, kind, ropt, true);
  const Speed sp(c, kind);
  const std::size_t n = c.dimension();
  // --deviation: G(r(s)) / mu for the rows in increasing s, one short
  // integral per row; mu (and the straight line's refusal) before any row.
  const bool deviation = a.flag("deviation");
  std::unique_ptr<ArcFraction> frac;
  if (deviation) frac = std::make_unique<ArcFraction>(sp, digits_to_bits(opt.digits) + 8, opt);
  Ball worst(0);
  auto deviation_of = [&](const SamplePoint& p) { return row_deviation(*frac, p, opt.digits, worst); };
  const Json head = sample_header_json(c, kind, r, opt.digits, K);
  const int rc = stream_samples(head, n, K, format, opt, [&](const SampleSink& sink) {
    sample_each(c, sp, r, K, opt.digits, opt.max_prec, sink);
  }, deviation ? std::function<Ball(const SamplePoint&)>(deviation_of) : std::function<Ball(const SamplePoint&)>(),
     &worst);
  return rc ? rc : target_status(r, "sample", a, opt.digits);
}

namespace {

int run_sample_composite(const Args& a, const CompositeCurve& c, SpeedKind kind, const Options& opt, long K,
                         const std::string& format) {
  const std::string m = a.get("method", "radical");
  if (m == "exact") {
    for (const char* o : {"pieces", "target", "max-pieces"})
      if (a.has(o)) throw InvalidArgument(std::string("--") + o + " does not apply to --method exact");
    if (a.flag("deviation"))
      throw InvalidArgument("--deviation measures a map's rows against --method exact's; it does not apply to "
                            "--method exact itself");
  }
  const std::vector<Speed> sp = c.speeds(kind);
  const std::size_t n = c.dimension();
  const std::string description = composite_description(a, c);
  if (m == "exact") {
    const Json head = composite_sample_header_json(description, c, kind, "exact", nullptr, opt.digits, K);
    // mu comes with the first point (exact_samples_each certifies it first).
    Ball mu;
    return stream_samples(head, n, K, format, opt, [&](const SampleSink& sink) {
      exact_samples_each(c, sp, K, opt, mu, [&](long k, const LocatedPoint& p) {
        sink(k, exact_sample_row(k, K, p, mu));
      });
    }, {}, nullptr, &mu);
  }
  const CompositeMethod cm = read_composite_method(a, c, true);
  Options ropt = opt;
  ropt.digits = opt.digits + 3;
  const CompositeMap r = composite_map(c, sp, cm, ropt);
  const Json head =
      composite_sample_header_json(description, c, kind, m == "none" ? "none" : r.method(), &r, opt.digits, K);
  CompositeSampler smp(c, sp, r, opt.digits, opt.max_prec);
  // --deviation: as for one curve, G over the whole composite curve.
  std::unique_ptr<ArcFraction> frac;
  if (a.flag("deviation")) frac = std::make_unique<ArcFraction>(c, sp, digits_to_bits(opt.digits) + 8, opt);
  Ball worst(0);
  const auto deviation_of = [&](const SamplePoint& p) { return row_deviation(*frac, p, opt.digits, worst); };
  const int rc = stream_samples(head, n, K, format, opt, [&](const SampleSink& sink) {
    for (long k = 0; k < K; ++k) {
      check_time_budget();
      sink(k, smp.at(Rational(k, K - 1)));
    }
  }, frac ? std::function<Ball(const SamplePoint&)>(deviation_of) : std::function<Ball(const SamplePoint&)>(), &worst);
  if (rc) return rc;
  if (cm.kind == CompositeMethod::Kind::Target && !r.target_reached()) {
    warn() << "uniparam sample: the target u >= " << cm.target.str()
              << " was not reached on every segment; the best map was sampled\n";
    return 4;
  }
  return 0;
}

}  // namespace

}  // namespace uniparam::cli
