// bench/bench_occt_abscissa.cpp -- uniparam's exact samples at equal arc
// length (exact_samples_each, 15 digits) against OpenCASCADE's
// GCPnts_UniformAbscissa on the same Bezier curves: the font quadratics of
// tests/data/font_quadratics.jsonl and a few hard cases (scaled, cusped,
// degenerate control polygon, long and thin). Prints a Markdown table
// (docs/locate.md, "Against OpenCASCADE").
//
//   uniparam_bench_occt [--every N] [--runs R] [--points K1,K2,...] [--font-only | --hard-only]
//
// --every N: every N-th font segment (default 10; 1 = all 3746).
// --runs R: timed runs per hard case and method, the median reported (default 5;
//           the font segments are timed once each, after a warm-up, and the
//           table gives the median over the segments).
//
// The error of a point with parameter u is |G(u) / mu - k / (K - 1)|, G the
// arc length from t = 0 and mu = G(1), from uniparam's ArcFraction at about
// 30 digits (certified balls: the reported error is their upper end). For
// uniparam the point is the midpoint of its certified t ball ("digits") and
// the whole ball ("certified digits": the largest error of any parameter in
// the ball). Each 15-digit ball is also checked to contain the reference
// parameter computed by exact_samples at 30 digits. OCCT's parameters are
// doubles, read exactly. Every control point is exact in double (the scaled
// cases use powers of two), so both libraries see the same curve.
// Time per point = wall time of the whole call (from the control points:
// curve, speed, mu and all K points for uniparam; Geom2d_BezierCurve, its
// adaptor and the abscissa computation for OCCT) / K, and the process's CPU
// time over the same call / K (all threads; less sensitive than the wall
// time to other work on a shared machine).
#include <Geom2dAdaptor_Curve.hxx>
#include <Geom2d_BezierCurve.hxx>
#include <GCPnts_UniformAbscissa.hxx>
#include <Standard_Failure.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "uniparam/core/json.hpp"
#include "uniparam/reparam/all.hpp"

namespace {

using namespace uniparam;
using Points = std::vector<std::vector<Rational>>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// CPU time of the whole process (all threads), in seconds.
double cpu_seconds() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// q as a double (every control point here is exact in double).
double to_double(const Rational& q) {
  const Ball b(q, 128);
  return arf_get_d(arb_midref(b.get()), ARF_RND_NEAR);
}

// Upper bound of |b| as a double (rounded up).
double abs_upper(const Ball& b) {
  arf_t u;
  arf_init(u);
  arb_get_abs_ubound_arf(u, b.get(), 64);
  const double d = arf_get_d(u, ARF_RND_UP);
  arf_clear(u);
  return d;
}

// Digits of an error e: -log10 e (capped at 30, the reference's accuracy).
double digits_of(double e) { return std::isnan(e) ? NAN : e <= 1e-30 ? 30.0 : std::min(30.0, -std::log10(e)); }

// One run of OCCT on the curve: the parameters (empty and *failed set when
// OCCT reports failure or throws).
std::vector<double> occt_params(const Points& pts, long K, double tol, std::string* failed) {
  TColgp_Array1OfPnt2d poles(1, static_cast<int>(pts.size()));
  for (std::size_t i = 0; i < pts.size(); ++i)
    poles.SetValue(static_cast<int>(i) + 1, gp_Pnt2d(to_double(pts[i][0]), to_double(pts[i][1])));
  std::vector<double> u;
  try {
    Handle(Geom2d_BezierCurve) bez = new Geom2d_BezierCurve(poles);
    Geom2dAdaptor_Curve ad(bez);
    GCPnts_UniformAbscissa ua(ad, static_cast<int>(K), tol);
    if (!ua.IsDone()) {
      *failed = "not done";
      return u;
    }
    for (int i = 1; i <= ua.NbPoints(); ++i) u.push_back(ua.Parameter(i));
  } catch (const Standard_Failure& e) {
    *failed = std::string("exception ") + e.GetMessageString();
    u.clear();
  }
  return u;
}

struct Outcome {
  long points = 0;         // number of points returned (0: failed)
  std::string note;        // failure, or wrong count
  double worst_err = NAN;  // largest fraction error (NAN when not comparable)
  double cert_err = NAN;   // uniparam only: largest over its balls
  bool contains_ref = true;
  double us_per_point = NAN;
  double cpu_us_per_point = NAN;  // process CPU time (all threads)
};

struct Method {
  std::string name;
  double tol = -1;  // OCCT's Toler
};

// The fraction error of each parameter u_k (doubles), by the certified G.
double worst_fraction_error(ArcFraction& frac, const std::vector<Ball>& params, long K) {
  double worst = 0;
  for (long k = 0; k < K; ++k) {
    Ball d = frac.at(params[static_cast<std::size_t>(k)]);
    Ball sk(Rational(k, K - 1), 256);
    arb_sub(d.get(), d.get(), sk.get(), 256);
    worst = std::max(worst, abs_upper(d));
  }
  return worst;
}

struct CaseResult {
  Outcome uni;
  std::vector<Outcome> occt;  // one per OCCT tolerance
};

// Everything for one curve and one K. `timed_runs` runs per method.
CaseResult run_case(const Points& pts, long K, const std::vector<double>& tols, int timed_runs) {
  CaseResult r;
  const Curve c = BezierCurve(pts).to_curve();
  const Speed s(c, SpeedKind::Parametric);
  Options ref_opt;
  ref_opt.digits = 30;
  ArcFraction frac(s, digits_to_bits(32), ref_opt);

  // uniparam at 15 digits.
  Options opt;
  opt.digits = 15;
  std::vector<LocatedPoint> pts15;
  std::vector<double> times, cpu;
  for (int run = 0; run < timed_runs; ++run) {
    pts15.clear();
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    const Curve cc = BezierCurve(pts).to_curve();
    const Speed ss(cc, SpeedKind::Parametric);
    Ball mu;
    exact_samples_each(cc, ss, K, opt, mu, [&](long, const LocatedPoint& p) { pts15.push_back(p); });
    times.push_back(seconds_since(t0) / static_cast<double>(K));
    cpu.push_back((cpu_seconds() - c0) / static_cast<double>(K));
  }
  r.uni.us_per_point = median(times) * 1e6;
  r.uni.cpu_us_per_point = median(cpu) * 1e6;
  r.uni.points = static_cast<long>(pts15.size());
  std::vector<Ball> mids, balls;
  for (const auto& p : pts15) {
    Ball m;
    arb_set_arf(m.get(), arb_midref(p.t.get()));
    mids.push_back(m);
    balls.push_back(p.t);
  }
  r.uni.worst_err = worst_fraction_error(frac, mids, K);
  r.uni.cert_err = worst_fraction_error(frac, balls, K);
  const ExactSamples ref = exact_samples(c, s, K, ref_opt);
  for (long k = 0; k < K; ++k)
    if (!arb_contains(pts15[static_cast<std::size_t>(k)].t.get(), ref.points[static_cast<std::size_t>(k)].t.get()))
      r.uni.contains_ref = false;

  // OCCT, one outcome per tolerance.
  for (double tol : tols) {
    Outcome o;
    std::vector<double> u;
    std::string failed;
    times.clear();
    cpu.clear();
    for (int run = 0; run < timed_runs; ++run) {
      failed.clear();
      const auto t0 = Clock::now();
      const double c0 = cpu_seconds();
      u = occt_params(pts, K, tol, &failed);
      times.push_back(seconds_since(t0) / static_cast<double>(K));
      cpu.push_back((cpu_seconds() - c0) / static_cast<double>(K));
    }
    o.us_per_point = median(times) * 1e6;
    o.cpu_us_per_point = median(cpu) * 1e6;
    o.points = static_cast<long>(u.size());
    if (!failed.empty()) {
      o.note = "fails (" + failed + ")";
    } else if (o.points != K) {
      o.note = std::to_string(o.points) + " points";
    } else {
      std::vector<Ball> ub(u.size());
      bool in_range = true;
      for (std::size_t i = 0; i < u.size(); ++i) {
        arb_set_d(ub[i].get(), u[i]);
        if (u[i] < 0 || u[i] > 1) in_range = false;
      }
      o.worst_err = worst_fraction_error(frac, ub, K);
      if (!in_range) o.note = "parameter outside [0, 1]";
    }
    r.occt.push_back(o);
  }
  return r;
}

std::string fmt(double v, const char* f) {
  if (std::isnan(v)) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

std::string tol_name(double tol) { return tol < 0 ? "default tol" : "tol " + fmt(tol, "%.0e"); }

std::vector<Points> read_fonts(const std::string& path) {
  std::ifstream f(path);
  if (!f) {
    std::cerr << "cannot open " << path << "\n";
    std::exit(2);
  }
  std::vector<Points> out;
  for (std::string line; std::getline(f, line);) {
    if (line.empty()) continue;
    const JsonValue v = parse_json(line);
    Points p;
    for (const auto& q : v.find("control")->as_array("control")) {
      const auto& xy = q.as_array("point");
      p.push_back({xy[0].as_rational("x"), xy[1].as_rational("y")});
    }
    out.push_back(p);
  }
  return out;
}

Points scaled(const Points& p, const Rational& f) {
  Points out = p;
  for (auto& pt : out)
    for (auto& x : pt) x = x * f;
  return out;
}

struct HardCase {
  std::string name;
  Points pts;
};

}  // namespace

int main(int argc, char** argv) {
  long every = 10;
  int runs = 5;
  std::vector<long> Ks = {11, 101};
  bool fonts = true, hard = true;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--every" && i + 1 < argc) every = std::max(1L, std::atol(argv[++i]));
    else if (a == "--runs" && i + 1 < argc) runs = std::max(1, std::atoi(argv[++i]));
    else if (a == "--points" && i + 1 < argc) {
      Ks.clear();
      std::stringstream ss(argv[++i]);
      for (std::string k; std::getline(ss, k, ',');) Ks.push_back(std::atol(k.c_str()));
    } else if (a == "--font-only") hard = false;
    else if (a == "--hard-only") fonts = false;
    else {
      std::cerr << "usage: uniparam_bench_occt [--every N] [--runs R] [--points K1,K2] [--font-only | --hard-only]\n";
      return 2;
    }
  }
  const std::vector<double> tols = {-1, 1e-15};
  const auto R = [](long a, long b = 1) { return Rational(a, b); };

  std::cout << "| curve | K | OCCT " << tol_name(tols[0]) << ": points | digits | µs/point wall / CPU | OCCT "
            << tol_name(tols[1]) << ": points | digits | µs/point wall / CPU | uniparam 15 digits: points | digits | "
            << "certified digits | contains 30-digit ref | µs/point wall / CPU |\n";
  std::cout << "|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  auto row = [&](const std::string& name, long K, const CaseResult& r) {
    std::cout << "| " << name << " | " << K;
    for (const Outcome& o : r.occt)
      std::cout << " | " << (o.note.empty() ? std::to_string(o.points) : o.note) << " | "
                << fmt(digits_of(o.worst_err), "%.1f") << " | " << fmt(o.us_per_point, "%.3g") << " / "
                << fmt(o.cpu_us_per_point, "%.3g");
    std::cout << " | " << r.uni.points << " | " << fmt(digits_of(r.uni.worst_err), "%.1f") << " | "
              << fmt(digits_of(r.uni.cert_err), "%.1f") << " | " << (r.uni.contains_ref ? "yes" : "NO") << " | "
              << fmt(r.uni.us_per_point, "%.3g") << " / " << fmt(r.uni.cpu_us_per_point, "%.3g") << " |" << std::endl;
  };

  if (fonts) {
    const std::vector<Points> all = read_fonts(UNIPARAM_FONT_DATA);
    std::vector<Points> sel;
    for (std::size_t i = 0; i < all.size(); i += static_cast<std::size_t>(every)) sel.push_back(all[i]);
    run_case(sel.front(), Ks.front(), tols, 2);  // warm-up
    for (long K : Ks) {
      // Aggregated over the segments: counts of failures and wrong counts,
      // the worst digits, the median time per point.
      const std::size_t nt = tols.size();
      std::vector<long> bad(nt, 0);
      std::vector<double> worst(nt, 0), worst_uni{0, 0};
      std::vector<std::vector<double>> times(nt), cpus(nt);
      std::vector<double> uni_times, uni_cpus;
      long uni_bad = 0, uni_nocontain = 0;
      for (const Points& p : sel) {
        const CaseResult r = run_case(p, K, tols, 1);
        for (std::size_t j = 0; j < nt; ++j) {
          if (!r.occt[j].note.empty()) ++bad[j];
          else worst[j] = std::max(worst[j], r.occt[j].worst_err);
          times[j].push_back(r.occt[j].us_per_point);
          cpus[j].push_back(r.occt[j].cpu_us_per_point);
        }
        if (r.uni.points != K) ++uni_bad;
        if (!r.uni.contains_ref) ++uni_nocontain;
        worst_uni[0] = std::max(worst_uni[0], r.uni.worst_err);
        worst_uni[1] = std::max(worst_uni[1], r.uni.cert_err);
        uni_times.push_back(r.uni.us_per_point);
        uni_cpus.push_back(r.uni.cpu_us_per_point);
      }
      const std::string n = std::to_string(sel.size());
      std::cout << "| font quadratics (" << n << " of " << all.size() << ") | " << K;
      for (std::size_t j = 0; j < nt; ++j)
        std::cout << " | " << (bad[j] ? std::to_string(bad[j]) + " of " + n + " wrong or failed" : "all " + std::to_string(K))
                  << " | " << fmt(digits_of(worst[j]), "%.1f") << " | " << fmt(median(times[j]), "%.3g") << " / "
                  << fmt(median(cpus[j]), "%.3g");
      std::cout << " | " << (uni_bad ? std::to_string(uni_bad) + " wrong" : "all " + std::to_string(K)) << " | "
                << fmt(digits_of(worst_uni[0]), "%.1f") << " | " << fmt(digits_of(worst_uni[1]), "%.1f") << " | "
                << (uni_nocontain ? std::to_string(uni_nocontain) + " NO" : "yes") << " | "
                << fmt(median(uni_times), "%.3g") << " / " << fmt(median(uni_cpus), "%.3g") << " |" << std::endl;
    }
  }

  if (hard) {
    const Points seg = {{R(170), R(272)}, {R(272), R(208)}, {R(753, 2), R(351, 2)}};  // a DejaVu Sans "$" segment
    const std::vector<HardCase> cases = {
        {"font segment x 2^11 (coordinates ~1e6)", scaled(seg, pow2(11))},
        {"font segment x 2^-28 (coordinates ~1e-6)", scaled(seg, pow2(-28))},
        {"cusp (t^2, t^3), t in [-1, 1]", {{R(1), R(-1)}, {R(-1, 3), R(1)}, {R(-1, 3), R(-1)}, {R(1), R(1)}}},
        {"cubic, P0 = P1 (speed 0 at t = 0)", {{R(0), R(0)}, {R(0), R(0)}, {R(1), R(0)}, {R(1), R(1)}}},
        {"quadratic, P0 = P1 (a segment traced as t^2)", {{R(0), R(0)}, {R(0), R(0)}, {R(3), R(4)}}},
        {"long thin quadratic (hairpin 10000 x 2)", {{R(0), R(0)}, {R(10000), R(1)}, {R(0), R(2)}}},
        {"long flat quadratic (10000 x 1)", {{R(0), R(0)}, {R(5000), R(1)}, {R(10000), R(0)}}},
    };
    for (const HardCase& hc : cases) {
      run_case(hc.pts, Ks.front(), tols, 1);  // warm-up
      for (long K : Ks) row(hc.name, K, run_case(hc.pts, K, tols, runs));
    }
  }
  return 0;
}
