// The library examples of docs/library.md, built against the installed
// package by the test suite: piecewise Moebius (C0, C1, exact rational
// output), Bezier curves and sampling.
#include <iostream>

#include <uniparam/uniparam.hpp>

int main() {
  uniparam::Curve c = uniparam::parse_curve("(t, t^3)");
  uniparam::Options o;
  auto c0 = uniparam::reparam_c0(c, uniparam::SpeedKind::Angular, 3, o);        // C0, optimised T
  auto c1 = uniparam::reparam_c1(c, uniparam::SpeedKind::Angular, uniparam::Rational(99, 100), o);
  auto q  = uniparam::make_rational(c, c1, 8, o);   // q.T_exact, q.S_exact, q.alpha_exact; exactly C1
  auto f  = uniparam::moebius_formulas(c, q, uniparam::Format::Latex, o.digits);  // r and p o r per piece

  auto bz = uniparam::BezierCurve::parse("[[0,0],[0,1],[3,1]]", "");
  auto br = uniparam::bezier_optimal(bz, o);        // br.alpha_exact: (-3 + sqrt(33))/8

  uniparam::Reparameterization rp(c0);              // or a RadicalResult
  auto smp = uniparam::sample(c, uniparam::Speed(c, uniparam::SpeedKind::Angular), rp, 40, 15, o.max_prec);

  std::cout << "C0, 3 pieces: u = " << c0.u_after.str(20) << "\n"
            << "C1, rational: u = " << q.u_after.str(20) << ", " << f.size() << " pieces, t = " << f[0].r << "\n"
            << "Bezier alpha = " << br.alpha.str(20) << "\n"
            << "samples: " << smp.after.size() << "\n";
  return 0;
}
