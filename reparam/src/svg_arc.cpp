// SVG elliptical arcs as exact rational quadratic Bezier pieces (svg_arc.hpp).
//
// The center follows SVG implementation notes F.6.5 (with F.6.6's radius
// scale-up, where the center is the chord's midpoint). The ellipse through
// p1 with that center is {c + cos(t) u + sin(t) J u}: u = p1 - c and J u
// its conjugate semi-diameter, so p2 - c = cos(Delta) u + sin(Delta) J u
// with rational cos(Delta), sin(Delta) (a 2x2 rational system). In these
// coordinates the arc is the unit circle's arc from angle 0 to Delta; it is
// split at the axis points (rational) into pieces of at most 90 degrees,
// each the exact rational quadratic of a circular arc, mapped affinely.
#include "svg_arc.hpp"

#include <stdexcept>

#include "uniparam/core/error.hpp"

namespace uniparam::detail {

bool rational_sqrt(const Rational& q, Rational& root) {
  if (q.sign() < 0) return false;
  const Integer n = q.num(), d = q.den();
  if (!fmpz_is_square(n.get()) || !fmpz_is_square(d.get())) return false;
  Integer rn, rd;
  fmpz_sqrt(rn.get(), n.get());
  fmpz_sqrt(rd.get(), d.get());
  root = Rational(rn, rd);
  return true;
}

namespace {

struct Vec {
  Rational x, y;
};

Rational abs_value(const Rational& q) { return q.sign() < 0 ? -q : q; }

}  // namespace

std::vector<BezierCurve> svg_arc(const Rational& x1, const Rational& y1, const Rational& rx_in,
                                 const Rational& ry_in, const Rational& phi, bool large_arc, bool sweep,
                                 const Rational& x2, const Rational& y2, const std::string& name) {
  if (x1 == x2 && y1 == y2) return {};
  const Rational rx = abs_value(rx_in), ry = abs_value(ry_in);
  if (rx.is_zero() || ry.is_zero()) return {BezierCurve({{x1, y1}, {x2, y2}})};

  // cos(phi), sin(phi) for phi a multiple of 90 degrees.
  const Rational quarter_turns = phi / Rational(90);
  if (!quarter_turns.is_integer())
    throw InvalidArgument(name + ": its x-axis rotation " + phi.str() +
                          " degrees is not a multiple of 90, so its cosine and sine are irrational; "
                          "uniparam does not approximate");
  Integer r4;
  {
    Integer four(4);
    fmpz_fdiv_r(r4.get(), fmpq_numref(quarter_turns.get()), four.get());
  }
  const long k = fmpz_get_si(r4.get());
  const Rational cs = k == 0 ? Rational(1) : k == 2 ? Rational(-1) : Rational(0);
  const Rational sn = k == 1 ? Rational(1) : k == 3 ? Rational(-1) : Rational(0);

  // F.6.5.1: the half chord in the ellipse's frame.
  const Rational dx = (x1 - x2) / Rational(2), dy = (y1 - y2) / Rational(2);
  const Rational x1p = cs * dx + sn * dy, y1p = -sn * dx + cs * dy;
  const Rational rx2 = rx * rx, ry2 = ry * ry;
  const Rational lambda = x1p * x1p / rx2 + y1p * y1p / ry2;
  // F.6.5.2 (F.6.6: lambda >= 1 scales the radii up; the center is then the midpoint).
  Rational cxp(0), cyp(0);
  if (lambda < Rational(1)) {
    const Rational den = rx2 * y1p * y1p + ry2 * x1p * x1p;
    const Rational radicand = (rx2 * ry2 - rx2 * y1p * y1p - ry2 * x1p * x1p) / den;
    Rational root;
    if (!rational_sqrt(radicand, root))
      throw InvalidArgument(name + ": its center is irrational (the radicand " + radicand.str() +
                            " of SVG implementation notes F.6.5.2 is not the square of a rational); "
                            "uniparam does not approximate");
    if (large_arc == sweep) root = -root;
    cxp = root * rx * y1p / ry;
    cyp = -(root * ry * x1p / rx);
  }
  const Vec c{cs * cxp - sn * cyp + (x1 + x2) / Rational(2), sn * cxp + cs * cyp + (y1 + y2) / Rational(2)};

  // J = R A R^T, A = [[0, -rx/ry], [ry/rx, 0]], R = [[cs, -sn], [sn, cs]];
  // negated for a negative-angle sweep.
  const Rational a12 = -(rx / ry), a21 = ry / rx;
  // R A = [[-sn a21, cs a12], [cs a21, sn a12]]; (R A) R^T with R^T = [[cs, sn], [-sn, cs]].
  const Rational ra11 = -(sn * a21), ra12 = cs * a12, ra21 = cs * a21, ra22 = sn * a12;
  Rational j11 = ra11 * cs - ra12 * sn, j12 = ra11 * sn + ra12 * cs;
  Rational j21 = ra21 * cs - ra22 * sn, j22 = ra21 * sn + ra22 * cs;
  if (!sweep) { j11 = -j11; j12 = -j12; j21 = -j21; j22 = -j22; }

  const Vec u{x1 - c.x, y1 - c.y};
  const Vec v{j11 * u.x + j12 * u.y, j21 * u.x + j22 * u.y};
  const Vec w{x2 - c.x, y2 - c.y};
  const Rational det = u.x * v.y - u.y * v.x;  // nonzero: u, J u independent (u != 0)
  const Rational C = (w.x * v.y - w.y * v.x) / det, S = (u.x * w.y - u.y * w.x) / det;
  if (C * C + S * S != Rational(1))
    throw std::logic_error("svg_arc: the end point is not on the ellipse (" + name + ")");

  // Quadrant of Delta in (0, 360): the axis points strictly inside the arc.
  int quadrant;
  if (S.sign() > 0 && C.sign() >= 0) quadrant = 1;
  else if (C.sign() < 0 && S.sign() >= 0) quadrant = 2;
  else if (S.sign() < 0 && C.sign() <= 0) quadrant = 3;
  else quadrant = 4;
  const Vec axis[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  std::vector<Vec> on_circle(axis, axis + quadrant);
  on_circle.push_back({C, S});

  auto map = [&](const Vec& p) -> std::vector<Rational> {
    return {c.x + p.x * u.x + p.y * v.x, c.y + p.x * u.y + p.y * v.y};
  };
  std::vector<BezierCurve> pieces;
  for (std::size_t i = 0; i + 1 < on_circle.size(); ++i) {
    const Vec& a = on_circle[i];
    const Vec& b = on_circle[i + 1];
    const Rational sin_delta = a.x * b.y - a.y * b.x;  // > 0: sweep in (0, 90]
    const Vec t{(b.y - a.y) / sin_delta, (a.x - b.x) / sin_delta};
    const Rational cos_half_sq = (Rational(1) + a.x * b.x + a.y * b.y) / Rational(2);
    pieces.emplace_back(std::vector<std::vector<Rational>>{map(a), map(t), map(b)},
                        std::vector<Rational>{Rational(1), Rational(1), Rational(1) / cos_half_sq});
  }
  return pieces;
}

}  // namespace uniparam::detail
