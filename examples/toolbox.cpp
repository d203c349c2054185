// The library examples of docs/library.md, built against the installed
// package by the test suite: piecewise Moebius (C0, C1, exact rational
// output), Bezier curves, sampling and composite curves.
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

  std::vector<uniparam::PathInput> sub = uniparam::parse_svg_path("M 0 0 Q 1 2 2 0 A 5 5 0 0 1 10 0 Z");
  std::vector<uniparam::Curve> segs;
  for (const auto& b : sub[0].segments) segs.push_back(b.to_curve());
  uniparam::CompositeCurve cc(segs, sub[0].knots, sub[0].labels);
  auto cu = uniparam::uniformity(cc, uniparam::SpeedKind::Parametric, o);  // cu.mu, cu.u, cu.joints
  std::vector<uniparam::Speed> sp = cc.speeds(uniparam::SpeedKind::Parametric);
  uniparam::CompositeMethod m;
  m.kind = uniparam::CompositeMethod::Kind::Pieces;   // or Radical, Moebius, Breakpoints, Target
  m.pieces = 8;
  uniparam::CompositeMap map = uniparam::composite_map(cc, sp, m, o);   // map.S(), map.parts(), map.u_after()
  uniparam::CompositeSampler at(cc, sp, map, 15, o.max_prec);            // at.at(s): t, p(r(s)), speed
  auto half = uniparam::locate(cc, sp, uniparam::Rational(1, 2), uniparam::LocateTarget::Fraction, o);
  uniparam::Nurbs n = uniparam::composite_nurbs(cc, map, 128);           // p o r as one NURBS

  std::cout << "C0, 3 pieces: u = " << c0.u_after.str(20) << "\n"
            << "C1, rational: u = " << q.u_after.str(20) << ", " << f.size() << " pieces, t = " << f[0].r << "\n"
            << "Bezier alpha = " << br.alpha.str(20) << "\n"
            << "samples: " << smp.after.size() << "\n"
            << "path: length " << cu.mu.str(20) << ", " << map.pieces() << " pieces, u = " << map.u_after().str(20)
            << ", half way at t = " << half.at.t.str(20) << ", p(r(1/2)) = " << at.at(uniparam::Rational(1, 2)).point[0].str(10)
            << ", NURBS of " << n.segments << " segments\n";
  return 0;
}
