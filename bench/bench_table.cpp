// Google Benchmark: the table of docs/benchmarks.md. For every curve family of
// bench_curves.hpp at degrees 6, 12, 50, 100, 150, 300 and every operation
// (uniformity, radical, reparam --pieces 3 = reparam_c0 with N = 3 and its
// breakpoint optimiser, reparam --target 0.99 = reparam_c1), registers
//   cert/<family>/<degree>/<op>/<digits>   certified, digits 15 and 50
//   float/<family>/<degree>/<op>           the UNCERTIFIED double baseline
//                                          (none for target99: no double C1)
// The double pieces3 runs the library's breakpoint search on its own double
// quadrature (fp::reparam_c0); its digits are measured against the certified
// map on the breakpoints it chose (moebius_c0 on those doubles, exactly).
// The float benchmark also reports, as counters, how many digits of its
// results are correct (measured against a certified run at 20 digits, outside
// the timed loop): `correct_digits` (minimum over the numbers it reports),
// `structure_ok` (0 when it found different breakpoints than the certified
// run), `converged` (its quadrature's own verdict). Every benchmark reports
// `maxrss_MB`, the peak resident memory of the process (scripts/bench.sh runs
// one process per benchmark, so this is that benchmark's peak).
// Angular speed throughout. Targets are read from the table, never asserted.
#include <benchmark/benchmark.h>
#include <flint/fmpq.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench_curves.hpp"
#include "float_baseline.hpp"
#include "uniparam/core/parallel.hpp"

namespace ub = uniparam::bench;
namespace fp = uniparam::fp;
using uniparam::Ball;
using uniparam::SpeedKind;

namespace {

const long kDegrees[] = {6, 12, 50, 100, 150, 300};
const char* kOps[] = {"uniformity", "radical", "pieces3", "target99"};
constexpr SpeedKind kKind = SpeedKind::Angular;

double maxrss_mb() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return static_cast<double>(ru.ru_maxrss) / 1024.0;
}

using fp::correct_digits;

struct Check {
  double digits = 17;
  bool structure = true;
  void add(double x, const Ball& ref) { digits = std::min(digits, correct_digits(x, ref)); }
};

Check check_uniformity(const uniparam::Curve& c) {
  uniparam::Options o;
  o.digits = 20;
  const auto ref = uniparam::uniformity(c, kKind, o);
  const auto f = fp::uniformity(fp::to_float(c), kKind);
  Check k;
  k.add(f.mu, ref.mu);
  k.add(f.mean_square, ref.mean_square);
  k.add(f.u, ref.u);
  return k;
}

Check check_radical(const uniparam::Curve& c) {
  uniparam::Options o;
  o.digits = 20;
  const auto ref = uniparam::radical(c, kKind, o);
  const auto f = fp::radical(fp::to_float(c), kKind);
  Check k;
  k.add(f.mu, ref.mu);
  k.add(f.u_radical, ref.u_radical);
  k.add(f.u_after, ref.u_after);
  if (f.T.size() != ref.T.size()) {
    k.structure = false;
    k.digits = 0;
    return k;
  }
  for (std::size_t i = 0; i < f.T.size(); ++i) {
    k.structure = k.structure && f.mult[i] == ref.T[i].multiplicity;
    k.add(f.T[i] == 0 ? 1e-300 : f.T[i], ref.T[i].t.to_ball(128));
    if (i + 1 < f.T.size()) k.add(f.pieces[i].alpha, ref.integrals[i].alpha);
    if (i > 0 && i + 1 < f.T.size()) {
      k.add(f.S[i], ref.S[i]);
      k.add(f.Z[i], ref.Z[i]);
    }
  }
  if (!k.structure) k.digits = 0;
  return k;
}

// The double x as an exact rational.
uniparam::Rational exact(double x) {
  int e = 0;
  const double m = std::frexp(x, &e);  // x = m 2^e, m 2^53 an integer
  fmpq_t q;
  fmpq_init(q);
  fmpz_set_d(fmpq_numref(q), std::ldexp(m, 53));
  if (e >= 53) fmpq_mul_2exp(q, q, static_cast<ulong>(e - 53));
  else fmpq_div_2exp(q, q, static_cast<ulong>(53 - e));
  uniparam::Rational r(q);
  fmpq_clear(q);
  return r;
}

Check check_pieces(const uniparam::Curve& c, int N) {
  uniparam::Options o;
  o.digits = 20;
  const auto f = fp::reparam_c0(fp::to_float(c), kKind, N);
  std::vector<uniparam::RealAlgebraic> T;
  for (double t : f.T) T.emplace_back(exact(t));
  const auto ref = uniparam::moebius_c0(c, kKind, T, o);
  Check k;
  k.add(f.mu, ref.mu);
  k.add(f.u_after, ref.u_after);
  for (std::size_t i = 0; i < f.alpha.size(); ++i) k.add(f.alpha[i], ref.alpha[i]);
  for (std::size_t i = 1; i + 1 < f.S.size(); ++i) k.add(f.S[i], ref.S[i]);
  return k;
}

void run_cert(benchmark::State& st, const std::string& fam, long deg, const std::string& op, long digits) {
  const uniparam::Curve c = ub::make_curve(fam, deg);
  uniparam::Options o;
  o.digits = digits;
  const std::uint64_t dispatched_before = uniparam::parallel_dispatches();
  for (auto _ : st) {
    if (op == "uniformity") benchmark::DoNotOptimize(uniparam::uniformity(c, kKind, o));
    else if (op == "radical") benchmark::DoNotOptimize(uniparam::radical(c, kKind, o));
    else if (op == "pieces3") benchmark::DoNotOptimize(uniparam::reparam_c0(c, kKind, 3, o));
    else {
      const auto r = uniparam::reparam_c1(c, kKind, uniparam::Rational(99, 100), o);
      st.counters["pieces"] = static_cast<double>(r.pieces());
      st.counters["reached"] = r.target->reached ? 1 : 0;
      benchmark::DoNotOptimize(r);
    }
  }
  st.counters["maxrss_MB"] = maxrss_mb();
  st.counters["degree"] = static_cast<double>(deg);
  // Whether the default thread count woke other threads in this process, and
  // how often per iteration (0 with UNIPARAM_THREADS=1).
  st.counters["threads"] = uniparam::parallel_threads_started() ? 1 : 0;
  st.counters["dispatches"] = benchmark::Counter(static_cast<double>(uniparam::parallel_dispatches() - dispatched_before),
                                                 benchmark::Counter::kAvgIterations);
}

void run_float(benchmark::State& st, const std::string& fam, long deg, const std::string& op) {
  const uniparam::Curve c = ub::make_curve(fam, deg);
  for (auto _ : st) {
    const fp::FloatCurve f = fp::to_float(c);
    if (op == "uniformity") benchmark::DoNotOptimize(fp::uniformity(f, kKind));
    else if (op == "radical") benchmark::DoNotOptimize(fp::radical(f, kKind));
    else benchmark::DoNotOptimize(fp::reparam_c0(f, kKind, 3));
  }
  st.counters["maxrss_MB"] = maxrss_mb();
  st.counters["degree"] = static_cast<double>(deg);
  const fp::FloatCurve f = fp::to_float(c);
  bool conv = true;
  if (op == "uniformity") conv = fp::uniformity(f, kKind).converged;
  else if (op == "radical") conv = fp::radical(f, kKind).converged;
  else conv = fp::reparam_c0(f, kKind, 3).converged;
  st.counters["converged"] = conv ? 1 : 0;
  if (std::getenv("UNIPARAM_BENCH_NO_REF")) {  // timing only (the reference run was too slow)
    st.counters["correct_digits"] = -1;
    return;
  }
  try {
    const Check k = op == "uniformity" ? check_uniformity(c) : op == "radical" ? check_radical(c) : check_pieces(c, 3);
    st.counters["correct_digits"] = k.digits;
    st.counters["structure_ok"] = k.structure ? 1 : 0;
  } catch (const std::exception& e) {
    st.counters["correct_digits"] = -1;  // no certified reference (budget)
  }
}

struct Registrar {
  Registrar() {
    for (const auto& fam : ub::families())
      for (long d : kDegrees)
        for (const char* op : kOps) {
          const std::string base = fam + "/" + std::to_string(d) + "/" + op;
          for (long digits : {15L, 50L})
            benchmark::RegisterBenchmark(("cert/" + base + "/" + std::to_string(digits)).c_str(),
                                         [fam, d, op = std::string(op), digits](benchmark::State& st) {
                                           run_cert(st, fam, d, op, digits);
                                         })
                ->Unit(benchmark::kMillisecond);
          if (std::string(op) == "target99") continue;  // no double C1 baseline
          benchmark::RegisterBenchmark(("float/" + base).c_str(),
                                       [fam, d, op = std::string(op)](benchmark::State& st) { run_float(st, fam, d, op); })
              ->Unit(benchmark::kMillisecond);
        }
  }
} registrar;

}  // namespace
