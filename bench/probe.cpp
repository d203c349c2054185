// bench/probe.cpp -- runs one certified operation on one benchmark curve and
// prints the result and the wall time (for profiling with perf / callgrind):
//   uniparam_probe FAMILY DEGREE uniformity|radical|piecesN|target99|phases [DIGITS]
// `phases` times radical's steps one after the other, each alone: the speed's
// construction, mu, the critical points, the piece integrals. PROBE_RUNS=N
// runs the operation N times in one process (cold first run, then warm).
#include "bench_curves.hpp"
#include "uniparam/reparam/pieces.hpp"
#include <chrono>
#include <iostream>
int main(int argc, char** argv) {
  std::string fam = argv[1]; long d = atol(argv[2]); std::string op = argv[3]; long digits = argc > 4 ? atol(argv[4]) : 15;
  auto c = uniparam::bench::make_curve(fam, d);
  if (getenv("SHOW")) std::cout << c.str() << "\n";
  uniparam::Options o; o.digits = digits;
  const int runs = getenv("PROBE_RUNS") ? atoi(getenv("PROBE_RUNS")) : 1;
  for (int run = 0; run < runs; ++run) {
  auto t0 = std::chrono::steady_clock::now();
  if (op == "uniformity") { auto r = uniparam::uniformity(c, uniparam::SpeedKind::Angular, o); std::cout << r.u.str(20) << " zeros " << r.zeros.size() << "\n"; }
  else if (op == "radical") { auto r = uniparam::radical(c, uniparam::SpeedKind::Angular, o); std::cout << r.u_after.str(20) << " pieces " << r.pieces() << "\n"; }
  else if (op == "phases") {
    auto t = [&] { return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(); };
    const uniparam::Speed s(c, uniparam::SpeedKind::Angular);
    std::cout << "speed " << t() << " s\n";
    const double a = t();
    auto mu = uniparam::mean_speed(s, uniparam::digits_to_bits(digits), o);
    std::cout << "mu " << t() - a << " s " << mu.str(20) << "\n";
    const double b = t();
    auto T = uniparam::critical_breakpoints(s);
    std::cout << "critical " << t() - b << " s " << T.size() << " breakpoints\n";
    const double e = t();
    auto I = uniparam::all_piece_integrals(s, T, uniparam::digits_to_bits(digits) + 8, o.max_prec);
    std::cout << "pieces " << t() - e << " s\n";
  }
  else if (op.rfind("pieces", 0) == 0) { auto r = uniparam::reparam_c0(c, uniparam::SpeedKind::Angular, atol(op.c_str() + 6), o); std::cout << r.u_after.str(20) << "\n"; }
  else { auto r = uniparam::reparam_c1(c, uniparam::SpeedKind::Angular, uniparam::Rational(99, 100), o); std::cout << r.u_after.str(20) << " pieces " << r.pieces() << (r.target->reached ? "" : " (target not reached)") << "\n"; }
  std::cout << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
  }
}
