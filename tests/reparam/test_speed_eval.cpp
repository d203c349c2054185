// Speed evaluation on wide complex balls (the quadrature's ellipses): the
// enclosure of sigma^2 (and sigma, and sigma^2 over a zero) on a ball must
// contain the value at every point of the ball. Curves: Bezier curves of
// moderate degree converted to the power basis (large alternating
// coefficients, where the centred form replaces Horner), plane and space,
// polynomial and rational.
#include <acb_poly.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <memory>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "reparam/speed_eval_support.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/algebra/quadrature.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

using uniparam::speed_eval_test::random_bezier;

namespace {

// A random complex ball with midpoint near [0, 1] and radii up to `maxrad`.
void random_ball(acb_t z, std::mt19937_64& rng, double maxrad) {
  std::uniform_int_distribution<long> m(0, 1 << 20), r(1, 1 << 10);
  arb_set_si(acb_realref(z), m(rng));
  arb_mul_2exp_si(acb_realref(z), acb_realref(z), -20);
  arb_set_si(acb_imagref(z), m(rng) - (1 << 19));
  arb_mul_2exp_si(acb_imagref(z), acb_imagref(z), -24);
  mag_set_d(arb_radref(acb_realref(z)), maxrad * static_cast<double>(r(rng)) / 1024.0);
  mag_set_d(arb_radref(acb_imagref(z)), maxrad * static_cast<double>(r(rng)) / 1024.0);
}

// True when out overlaps v or -v: sigma evaluated with default piece signs
// is the analytic continuation from a piece where sign g (or the plane's
// sign of E) is +-1, so only |sigma| is compared.
bool overlaps_up_to_sign(const acb_t out, const acb_t v) {
  acb_t nv;
  acb_init(nv);
  acb_neg(nv, v);
  const bool ok = acb_overlaps(out, v) || acb_overlaps(out, nv);
  acb_clear(nv);
  return ok;
}

// An exact point of the ball z: mid + (a, b) * rad with a, b in [-1, 1].
void random_point(acb_t w, const acb_t z, std::mt19937_64& rng) {
  std::uniform_int_distribution<long> f(-1024, 1024);
  arb_t s;
  arb_init(s);
  for (int part = 0; part < 2; ++part) {
    arb_srcptr src = part ? acb_imagref(z) : acb_realref(z);
    arb_ptr dst = part ? acb_imagref(w) : acb_realref(w);
    arf_set_mag(arb_midref(s), arb_radref(src));
    mag_zero(arb_radref(s));
    arb_mul_si(s, s, f(rng), ARF_PREC_EXACT);
    arb_mul_2exp_si(s, s, -10);
    arb_set_arf(dst, arb_midref(src));
    arb_add(dst, dst, s, ARF_PREC_EXACT);
  }
  arb_clear(s);
}

}  // namespace

namespace {

// For `iters` random Bezier curves (make(it): degree, dimension, rational)
// and both speed kinds, 10 random balls each (ball(z, b) makes ball b):
// where wide(s, out, z) gives a finite enclosure, the values point(s, v, w)
// at 8 exact points w of the ball must overlap it (up to sign: see
// overlaps_up_to_sign). Returns {finite enclosures, balls}.
struct WideCase {
  long d;
  std::size_t dim;
  bool rational;
};
template <class Make, class Ball, class Wide, class Point>
std::pair<long, long> check_wide_balls(std::mt19937_64& rng, long iters, Make make, Ball ball, Wide wide,
                                       Point point, bool up_to_sign) {
  long finite = 0, total = 0;
  for (long it = 0; it < iters; ++it) {
    const WideCase k = make(it);
    const Curve c = random_bezier(rng, k.d, k.dim, k.rational);
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Speed s(c, kind);
      acb_t z, w, out, v;
      for (acb_ptr x : {z, w, out, v}) acb_init(x);
      for (int b = 0; b < 10; ++b) {
        ball(z, b);
        ++total;
        wide(s, out, z);
        if (!acb_is_finite(out)) continue;
        ++finite;
        for (int p = 0; p < 8; ++p) {
          random_point(w, z, rng);
          point(s, v, w);
          const bool ok = up_to_sign ? overlaps_up_to_sign(out, v) : acb_overlaps(out, v);
          if (!ok) {  // (ASSERT_* needs a void function)
            ADD_FAILURE() << c.str() << " degree " << k.d << " kind " << static_cast<int>(kind);
            for (acb_ptr x : {z, w, out, v}) acb_clear(x);
            return {finite, total};
          }
        }
      }
      for (acb_ptr x : {z, w, out, v}) acb_clear(x);
    }
  }
  return {finite, total};
}

}  // namespace

TEST(SpeedEval, SquaredSpeedOnWideBallsContainsEveryPointValue) {
  std::mt19937_64 rng(7);
  const auto [finite, balls] = check_wide_balls(
      rng, test_support::iterations(6),
      [&](long it) { return WideCase{8 + static_cast<long>(rng() % 24), 2 + rng() % 2, it % 2 == 1}; },
      [&](acb_t z, int b) { random_ball(z, rng, b % 2 ? 0.05 : 0.002); },
      [](const Speed& s, acb_t out, const acb_t z) { s.eval_squared(out, z, 128); },
      [](const Speed& s, acb_t v, const acb_t w) { s.eval_squared(v, w, 256); }, false);
  (void)balls;
  EXPECT_GT(finite, 0);  // the check above ran
}

TEST(SpeedEval, AnalyticSpeedOnEllipsesInDiscsContainsEveryPointValue) {
  // Low degrees, where every factor has its centred form in double and the
  // ellipses are bounded in complex discs (Speed::eval_disk, the factored
  // form's discs for space curves): plane and space, polynomial and
  // rational, angular and parametric; boxes as the quadrature's (real and
  // complex midpoints). The enclosure must contain sigma at every point.
  std::mt19937_64 rng(31);
  const auto [finite, total] = check_wide_balls(
      rng, test_support::iterations(12),
      [&](long it) { return WideCase{3 + static_cast<long>(rng() % 8), 2 + static_cast<std::size_t>(it % 2), (it / 2) % 2 == 1}; },
      [&](acb_t z, int b) {
        random_ball(z, rng, b % 2 ? 0.1 : 0.01);
        if (b % 3 == 0) arb_zero(acb_imagref(z));  // the ellipses' bounding boxes: real midpoints
      },
      [](const Speed& s, acb_t out, const acb_t z) { s.eval(out, z, Speed::PieceSigns{}, true, 64); },
      [](const Speed& s, acb_t v, const acb_t w) { s.eval(v, w, Speed::PieceSigns{}, false, 256); }, true);
  EXPECT_GE(2 * finite, total);  // most boxes near [0, 1] are bounded
}

TEST(SpeedEval, SpeedAndSquaredOverIrrationalZeroOnWideBalls) {
  // (t, t^4 - 3 t^2): angular speed zero of multiplicity 1 at 1/sqrt(2).
  const Curve c = parse_curve("(t, t^4 - 3*t^2)");
  const Speed s(c, SpeedKind::Angular);
  ASSERT_EQ(s.zeros().size(), 1u);
  const SpeedZero& zero = s.zeros()[0];
  const Speed::PieceSigns right = s.piece_signs(zero.t, RealAlgebraic(1));
  std::mt19937_64 rng(11);
  acb_t z, w, out, v;
  acb_init(z);
  acb_init(w);
  acb_init(out);
  acb_init(v);
  long checked = 0;
  for (int b = 0; b < 40; ++b) {
    // balls around 1/sqrt(2) ~ 0.70710678 and to its right
    arb_set_d(acb_realref(z), 0.7071 + 0.002 * b);
    arb_zero(acb_imagref(z));
    mag_set_d(arb_radref(acb_realref(z)), 0.01);
    mag_set_d(arb_radref(acb_imagref(z)), 0.01);
    for (int power = 0; power <= 2; ++power) {
      s.eval_squared_over_zero(out, z, zero, 1, power, 128);
      if (!acb_is_finite(out)) continue;
      for (int p = 0; p < 6; ++p) {
        random_point(w, z, rng);
        s.eval_squared_over_zero(v, w, zero, 1, power, 256);
        ASSERT_TRUE(acb_overlaps(out, v)) << "power " << power << " ball " << b;
        ++checked;
      }
    }
    s.eval(out, z, right, false, 128);
    if (!acb_is_finite(out)) continue;
    for (int p = 0; p < 6; ++p) {
      random_point(w, z, rng);
      s.eval(v, w, right, false, 256);
      ASSERT_TRUE(acb_overlaps(out, v)) << "sigma, ball " << b;
      ++checked;
    }
  }
  EXPECT_GT(checked, 0);
  acb_clear(z);
  acb_clear(w);
  acb_clear(out);
  acb_clear(v);
}

TEST(SpeedEval, SpaceSpeedOnWideBallsAtLowPrecision) {
  // Rational space Bezier curves of degree 40: the cofactors K of the
  // factored form have degree ~ 110 and power-basis coefficients some 200
  // bits above their values near t = 1. At a working precision of 64 bits the
  // enclosure of sigma on balls of radius ~1e-3 must still be finite (the
  // Taylor shift is redone above the bits lost to cancellation, and the
  // factored form is used instead of the components' |p' x p''|) and contain
  // sigma at every point of the ball.
  std::mt19937_64 rng(23);
  long finite = 0, total = 0;
  for (long it = 0; it < test_support::iterations(2); ++it) {
    const Curve c = random_bezier(rng, 40, 3, true);
    const Speed s(c, SpeedKind::Angular);
    const Speed::PieceSigns sign{};
    acb_t z, w, out, v;
    acb_init(z);
    acb_init(w);
    acb_init(out);
    acb_init(v);
    for (int b = 0; b < 12; ++b) {
      arb_set_d(acb_realref(z), 0.8 + 0.015 * b);
      arb_zero(acb_imagref(z));
      mag_set_d(arb_radref(acb_realref(z)), 1e-3);
      mag_set_d(arb_radref(acb_imagref(z)), 8e-4);
      ++total;
      s.eval(out, z, sign, true, 64);
      if (!acb_is_finite(out)) continue;
      ++finite;
      for (int p = 0; p < 6; ++p) {
        random_point(w, z, rng);
        s.eval(v, w, sign, false, 512);
        ASSERT_TRUE(overlaps_up_to_sign(out, v)) << c.str() << " ball " << b;
      }
    }
    acb_clear(z);
    acb_clear(w);
    acb_clear(out);
    acb_clear(v);
  }
  EXPECT_GE(2 * finite, total);
}

namespace uniparam {
namespace {

TEST(SpeedEval, SpeedOnRealSegmentsWithoutHolomorphyIsFiniteAndContainsPointValues) {
  // Arb's direct bound on a subinterval evaluates sigma on the real segment
  // itself with holomorphy not asked. sigma is real there, and |p' x p''|^2
  // and |p'|^2 are >= 0 at every real point: the enclosure must be real
  // (square roots of [max(0, lo), hi], no detour through the complex branch
  // cut), contain sigma at every point of the segment, and be finite on most
  // segments (a segment of radius 2^-6 near an end of a degree-30 curve may
  // still have |p'|^2's enclosure reach 0: at least half, as above).
  // Rational space Bezier curves of degree 30 and plane ones, segments of
  // radius 2^-6..2^-10.
  std::mt19937_64 rng(31);
  long finite = 0, total = 0;
  for (long it = 0; it < test_support::iterations(3); ++it) {
    const Curve c = random_bezier(rng, 30, it % 2 == 0 ? 3 : 2, true);
    const Speed s(c, SpeedKind::Angular);
    acb_t z, w, out, v;
    for (acb_ptr x : {z, w, out, v}) acb_init(x);
    for (int b = 0; b < 16; ++b) {
      acb_zero(z);
      arb_set_d(acb_realref(z), (b + 0.5) / 16);
      mag_set_ui_2exp_si(arb_radref(acb_realref(z)), 1, -6 - b % 5);
      const Speed::PieceSigns sign{};
      ++total;
      s.eval(out, z, sign, false, 64);
      ASSERT_TRUE(acb_is_real(out)) << c.str() << " segment " << b;
      if (!acb_is_finite(out)) continue;
      ++finite;
      for (int p = 0; p < 8; ++p) {
        random_point(w, z, rng);
        arb_zero(acb_imagref(w));
        s.eval(v, w, sign, false, 256);
        ASSERT_TRUE(overlaps_up_to_sign(out, v)) << c.str() << " segment " << b;
      }
    }
    for (acb_ptr x : {z, w, out, v}) acb_clear(x);
  }
  EXPECT_GE(2 * finite, total);
}

}  // namespace
}  // namespace uniparam
