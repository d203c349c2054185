// The library examples of docs/library.md, built against the installed
// package by the test suite: the methods on one curve (radical, C0 and C1
// piecewise Moebius, exact rational output), a Bezier curve's bilinear map,
// samples, formulas, NURBS and STEP output, and a composite curve from SVG.
#include <iostream>

#include <uniparam/uniparam.hpp>

int main() {
  namespace up = uniparam::api;
  try {
    up::Options o;  // angular speed, 15 digits
    const up::Curve c = up::Curve::parse("(t, t^3)", o);
    up::Reparameterization rad = up::radical(c, o);
    up::Reparameterization c0 = up::moebius_pieces(c, 3, o);         // C0, optimised breakpoints
    up::Reparameterization c1 = up::moebius_target(c, up::Rational(99, 100), 64, o);
    up::Reparameterization q = c1.rational(8);                        // exact rational data, exactly C1
    auto f = q.formulas(up::Format::Latex);                           // r and p o r per piece
    auto smp = c0.samples(40);                                        // certified points of p o r
    up::Nurbs n = q.nurbs();                                          // p o r, exact NURBS

    up::Options po = o;
    po.speed = up::SpeedKind::Parametric;
    const up::Curve bz = up::Curve::bezier("[[0,0],[0,1],[3,1]]", "", po);
    up::Reparameterization br = up::bezier_bilinear(bz, po);          // alpha = (-3 + sqrt(33))/8

    const std::vector<up::Curve> path = up::Curve::svg_path("M 0 0 Q 1 2 2 0 A 5 5 0 0 1 10 0 Z", po);
    const up::Uniformity pu = up::uniformity(path[0], po);           // arc length, u
    up::Reparameterization pm = up::moebius_pieces(path[0], 8, po);
    const up::Located half = up::locate(path[0], up::Rational(1, 2), true, po);  // half the arc length
    const std::string step = pm.nurbs().step("path.stp");

    std::cout << "radical: u = " << rad.u_after().str(20) << ", r(1/2) = " << rad.eval_r(up::Rational(1, 2)).str(20)
              << "\n"
              << "C0, 3 pieces: u = " << c0.u_after().str(20) << ", " << smp.size() << " samples\n"
              << "C1, rational: u = " << q.u_after().str(20) << ", " << f.size() << " pieces, t = " << f[0].r
              << ", NURBS of degree " << n.degree() << (n.exact() ? " (exact)" : "") << "\n"
              << "Bezier: u = " << br.u_after().str(20) << ", weights " << br.nurbs().weights_text().at(1) << "\n"
              << "path: length " << pu.mu.str(20) << ", " << pm.pieces() << " pieces, u = " << pm.u_after().str(20)
              << ", half way at t = " << half.t.str(20) << ", p(r(1/2)) = "
              << pm.at(up::Rational(1, 2)).point[0].str(10) << ", STEP of " << step.size() << " bytes\n";
  } catch (const uniparam::Error& e) {
    std::cerr << "toolbox: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
