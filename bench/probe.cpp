// bench/probe.cpp -- runs one certified operation on one benchmark curve and
// prints the result and the wall time (for profiling with perf / callgrind):
//   uniparam_probe FAMILY DEGREE uniformity|radical|piecesN|target99 [DIGITS]
#include "bench_curves.hpp"
#include <chrono>
#include <iostream>
int main(int argc, char** argv) {
  std::string fam = argv[1]; long d = atol(argv[2]); std::string op = argv[3]; long digits = argc > 4 ? atol(argv[4]) : 15;
  auto c = uniparam::bench::make_curve(fam, d);
  if (getenv("SHOW")) std::cout << c.str() << "\n";
  uniparam::Options o; o.digits = digits;
  auto t0 = std::chrono::steady_clock::now();
  if (op == "uniformity") { auto r = uniparam::uniformity(c, uniparam::SpeedKind::Angular, o); std::cout << r.u.str(20) << " zeros " << r.zeros.size() << "\n"; }
  else if (op == "radical") { auto r = uniparam::radical(c, uniparam::SpeedKind::Angular, o); std::cout << r.u_after.str(20) << " pieces " << r.pieces() << "\n"; }
  else if (op.rfind("pieces", 0) == 0) { auto r = uniparam::reparam_c0(c, uniparam::SpeedKind::Angular, atol(op.c_str() + 6), o); std::cout << r.u_after.str(20) << "\n"; }
  else { auto r = uniparam::reparam_c1(c, uniparam::SpeedKind::Angular, uniparam::Rational(99, 100), o); std::cout << r.u_after.str(20) << " pieces " << r.pieces() << (r.target.reached ? "" : " (target not reached)") << "\n"; }
  std::cout << std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() << " s\n";
}
