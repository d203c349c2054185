// uniparam/core/cdisk.hpp -- complex discs in IEEE double: a rigorous,
// low-accuracy (~2^-50 relative) complex ball arithmetic for bounding
// functions on wide balls (the quadrature's ellipses), where Arb's
// per-operation cost (~1 K instructions an acb_mul at 64 bits) dominates
// and the bounds need only a few correct bits.
//
// The proofs (u = 2^-53, IEEE double, round to nearest; every bound below
// also holds when the compiler fuses a product and a sum into one FMA,
// which only removes roundings):
//   * up(x) = x (1 + 2^-48) + 2^-1000 is an upper bound of the exact value
//     E of any expression of at most 30 sums and products of nonnegative
//     doubles computed as x: x >= E (1 - u)^30 (gradual underflow loses at
//     most 2^-1075 an operation, covered by 2^-1000), and up's own
//     rounding costs one more factor 1 - u; (1 - 31u)(1 + 32u) > 1;
//   * a complex sum's parts are each rounded once: |error| <= u (|re| +
//     |im|) of the computed sum (RN: |fl(s) - s| <= u |fl(s)| / (1 - u));
//   * a complex product by the textbook formula errs by at most sqrt(5) u
//     |a||b| (Brent, Percival and Zimmermann, 2007), 2u |a||b| with FMAs
//     (Jeannerod, Kornerup, Louvet and Muller, 2017): 3u |a||b| covers
//     both; underflow adds at most 2^-1074 a part;
//   * |c| = sqrt(x^2 + y^2) computed errs by at most 2u + O(u^2) relative
//     when max(|x|, |y|) is within 2^+-400 (the smaller square's underflow
//     is below 2^-275 relative there); abs_lo takes 1 - 2^-50 off it;
//   * 1 / c = (x - iy) / |c|^2 computed errs by at most 3u + O(u^2)
//     relative in each part, so 4u |1/c| in modulus; for w in the disc
//     |w - c| <= r < |c|, |1/w - 1/c| = |w - c| / (|w||c|) <= r / ((|c| -
//     r) |c|);
//   * the principal square root: when the disc avoids (-inf, 0] (r < |c|
//     and Re c > 0, or r < |Im c|: a point w of (-inf, 0] has |w - c| >=
//     |c| when Re c >= 0), the angle at 0 between c and any w of the disc
//     is at most arcsin(r / |c|) < pi/2 and arg is continuous on the disc,
//     so |arg sqrt(w) - arg sqrt(c)| < pi/4, Re(sqrt(w) conj(sqrt(c))) > 0
//     and |sqrt(w) + sqrt(c)|^2 >= |w| + |c| >= |c|: |sqrt(w) - sqrt(c)| =
//     |w - c| / |sqrt(w) + sqrt(c)| <= r / sqrt|c|. sqrt(c) is computed as
//     t = sqrt((|c| + |x|) / 2) (no cancellation) and y / (2t): each part
//     within 3.5u + O(u^2) relative, so 8u |sqrt(c)| covers the modulus.
#pragma once

#include <acb.h>

#include <algorithm>
#include <cmath>

namespace uniparam {

/// The closed disc {re + i im + w : |w| <= rad} of C. A disc with a field
/// that is NaN or infinite means "nothing is known": the operations
/// propagate it (or answer it where their precondition fails), so callers
/// check cdisk_is_finite once at the end. Each operation's result contains
/// the exact result of the operation for every choice of points in its
/// input discs.
struct CDisk {
  double re = 0, im = 0, rad = 0;
};

namespace cdisk_detail {
constexpr double kU = 0x1p-53;
// See the file comment: an upper bound of an expression of <= 30 sums and
// products of nonnegative doubles computed as x.
inline double up(double x) { return x * (1 + 0x1p-48) + 0x1p-1000; }
// Upper bound of |x + iy|: |x| + |y| outside 2^+-500 (where the squares
// could underflow or overflow), sqrt(x^2 + y^2) (2u + O(u^2) relative,
// the smaller square's underflow below 2^-73 relative) inside.
inline double abs_up(double x, double y) {
  const double s = std::fabs(x) + std::fabs(y);
  if (s < 0x1p-500 || s > 0x1p500) return up(s);
  return up(std::sqrt(x * x + y * y));
}
// Lower bound of |x + iy|; \pre in_range(x, y).
inline double abs_lo(double x, double y) { return std::sqrt(x * x + y * y) * (1 - 0x1p-50); }
// 2^-400 <= max(|x|, |y|) <= 2^400 (false for NaN): no overflow and no
// harmful underflow in |c|^2.
inline bool in_range(double x, double y) {
  const double m = std::max(std::fabs(x), std::fabs(y));
  return m >= 0x1p-400 && m <= 0x1p400;
}
// The disc that means "nothing is known" (every field NaN).
inline CDisk unknown() { return CDisk{NAN, NAN, NAN}; }
}  // namespace cdisk_detail

/// True if re, im and rad are finite.
inline bool cdisk_is_finite(const CDisk& a) {
  return std::isfinite(a.re) && std::isfinite(a.im) && std::isfinite(a.rad);
}

/// -a, exactly.
inline CDisk cdisk_neg(const CDisk& a) { return CDisk{-a.re, -a.im, a.rad}; }

/// A disc containing u + v for every u in a and v in b (see the file
/// comment for the rounding bound); not finite when an input is not, or on
/// overflow.
inline CDisk cdisk_add(const CDisk& a, const CDisk& b) {
  using namespace cdisk_detail;
  CDisk s{a.re + b.re, a.im + b.im, 0};
  s.rad = up(a.rad + b.rad + 2 * kU * (std::fabs(s.re) + std::fabs(s.im)));
  return s;
}

/// A disc containing u v for every u in a and v in b (textbook product, its
/// rounding bounded as in the file comment); not finite when an input is
/// not, or on overflow.
inline CDisk cdisk_mul(const CDisk& a, const CDisk& b) {
  using namespace cdisk_detail;
  CDisk p{a.re * b.re - a.im * b.im, a.re * b.im + a.im * b.re, 0};
  const double A = abs_up(a.re, a.im), B = abs_up(b.re, b.im);
  p.rad = up(A * b.rad + B * a.rad + a.rad * b.rad + 3 * kU * A * B);
  return p;
}

/// 1 / b. Not finite unless b's disc excludes 0 (and 2^-400 <= max(|Re|,
/// |Im|) of its centre <= 2^400).
inline CDisk cdisk_inv(const CDisk& b) {
  using namespace cdisk_detail;
  if (!in_range(b.re, b.im) || !std::isfinite(b.rad)) return unknown();
  const double L = abs_lo(b.re, b.im);
  if (!(L > b.rad)) return unknown();
  const double n = b.re * b.re + b.im * b.im;
  const double dl = (L - b.rad) * (1 - 0x1p-50);  // <= L - rad
  if (!(dl > 0)) return unknown();
  return CDisk{b.re / n, -b.im / n, up(b.rad / (dl * L) + 4 * kU / L)};
}

/// a / b (see cdisk_inv).
inline CDisk cdisk_div(const CDisk& a, const CDisk& b) { return cdisk_mul(a, cdisk_inv(b)); }

/// The principal square root, holomorphic on a's disc: not finite unless
/// the disc avoids (-inf, 0] (the branch cut and the branch point), and
/// 2^-400 <= max(|Re|, |Im|) of its centre <= 2^400.
inline CDisk cdisk_sqrt_analytic(const CDisk& a) {
  using namespace cdisk_detail;
  if (!in_range(a.re, a.im) || !std::isfinite(a.rad)) return unknown();
  const double L = abs_lo(a.re, a.im);
  if (!(a.re > 0 ? a.rad < L : a.rad < std::fabs(a.im))) return unknown();
  const double m = std::sqrt(a.re * a.re + a.im * a.im);
  const double t = std::sqrt(0.5 * (m + std::fabs(a.re)));
  const double o = a.im / (2 * t);
  CDisk s = a.re > 0 ? CDisk{t, o, 0} : CDisk{std::fabs(o), std::copysign(t, a.im), 0};
  s.rad = up(a.rad / (std::sqrt(L) * (1 - 0x1p-50)) + 8 * kU * std::sqrt(abs_up(a.re, a.im)));
  return s;
}

/// a's disc as an Arb box that holds it (midpoint exact, both radii a.rad
/// rounded upward); indeterminate if a is not finite.
inline void cdisk_get_acb(acb_t out, const CDisk& a) {
  if (!cdisk_is_finite(a)) {
    acb_indeterminate(out);
    return;
  }
  arf_set_d(arb_midref(acb_realref(out)), a.re);
  arf_set_d(arb_midref(acb_imagref(out)), a.im);
  mag_set_d(arb_radref(acb_realref(out)), a.rad);
  mag_set_d(arb_radref(acb_imagref(out)), a.rad);
}

/// A disc holding the Arb box z: its midpoint rounded to doubles (the
/// rounding added to the radius) and an upper bound of the hypot of its
/// radii. Not finite
/// if z is not, or its midpoint or radii overflow a double.
inline CDisk cdisk_set_acb(const acb_t z) {
  using namespace cdisk_detail;
  if (!acb_is_finite(z)) return unknown();
  CDisk d{arf_get_d(arb_midref(acb_realref(z)), ARF_RND_NEAR), arf_get_d(arb_midref(acb_imagref(z)), ARF_RND_NEAR), 0};
  const double rx = mag_get_d(arb_radref(acb_realref(z))), ry = mag_get_d(arb_radref(acb_imagref(z)));  // upper bounds
  d.rad = up(abs_up(rx, ry) + 2 * kU * (std::fabs(d.re) + std::fabs(d.im)));
  return d;
}

}  // namespace uniparam
