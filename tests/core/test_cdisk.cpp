// Tests of the complex discs in double (core/cdisk.hpp): every result must
// contain the exact result at exact points of the input discs (Arb at 600
// bits), including points on their boundary circles; results of point
// discs must be accurate to a few units of 2^-53 (which fails if a
// rounding term is dropped or a bound grossly inflated); the operations
// refuse discs that reach a pole or a branch cut.
#include <gtest/gtest.h>

#include <acb.h>

#include <cmath>
#include <random>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/cdisk.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

constexpr long kRefPrec = 600;

// A random disc: centre of magnitude ~2^e (e in [-30, 30]), sometimes real,
// sometimes 0; radius 0, tiny, comparable to the centre, or larger.
CDisk random_disk(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1), mant(0.5, 1);
  std::uniform_int_distribution<int> ex(-30, 30), kind(0, 9);
  const int e = ex(rng);
  CDisk d{std::ldexp(u(rng), e), std::ldexp(u(rng), e), 0};
  const int k = kind(rng);
  if (k == 0) d.im = 0;
  if (k == 1) d.re = d.im = 0;
  const int r = kind(rng);
  if (r <= 2) d.rad = 0;
  else if (r <= 5) d.rad = std::ldexp(mant(rng), e - 40);
  else if (r <= 8) d.rad = std::ldexp(mant(rng), e - 3);
  else d.rad = std::ldexp(mant(rng), e + 1);
  return d;
}

// |t - centre| <= rad, rigorously (t exact or a tiny ball).
bool holds(const CDisk& d, const acb_t t) {
  if (!cdisk_is_finite(d)) return false;
  acb_t w;
  arb_t m, r;
  acb_init(w);
  arb_init(m);
  arb_init(r);
  acb_set_d_d(w, d.re, d.im);
  acb_sub(w, t, w, kRefPrec);
  acb_abs(m, w, kRefPrec);
  arb_set_d(r, d.rad);
  const bool ok = arb_le(m, r);
  acb_clear(w);
  arb_clear(m);
  arb_clear(r);
  return ok;
}

// Exact points of a disc: its centre, four points of its circle, random
// interior points (each rounded to doubles, and kept only if exactly in).
std::vector<std::pair<double, double>> points(const CDisk& d, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> ang(0, 2 * M_PI), frac(0, 1);
  std::vector<std::pair<double, double>> out{{d.re, d.im}};
  if (d.rad == 0) return out;
  for (int i = 0; i < 8; ++i) {
    const double a = ang(rng), f = i < 4 ? 1 - 0x1p-40 : frac(rng);
    double x = d.re + f * d.rad * std::cos(a), y = d.im + f * d.rad * std::sin(a);
    acb_t t;
    acb_init(t);
    acb_set_d_d(t, x, y);
    if (holds(d, t)) out.emplace_back(x, y);
    acb_clear(t);
  }
  return out;
}

TEST(CDisk, ArithmeticContainsEveryExactResult) {
  std::mt19937_64 rng(21);
  acb_t x, y, e;
  acb_init(x);
  acb_init(y);
  acb_init(e);
  long divisions = 0;
  for (long it = 0; it < iterations(600); ++it) {
    const CDisk a = random_disk(rng), b = random_disk(rng);
    const CDisk s = cdisk_add(a, b), p = cdisk_mul(a, b), q = cdisk_div(a, b), i = cdisk_inv(b);
    ASSERT_TRUE(cdisk_is_finite(s) && cdisk_is_finite(p)) << it;
    divisions += cdisk_is_finite(q);
    for (const auto& pa : points(a, rng))
      for (const auto& pb : points(b, rng)) {
        acb_set_d_d(x, pa.first, pa.second);
        acb_set_d_d(y, pb.first, pb.second);
        acb_add(e, x, y, kRefPrec);
        ASSERT_TRUE(holds(s, e)) << it;
        acb_mul(e, x, y, kRefPrec);
        ASSERT_TRUE(holds(p, e)) << it;
        if (cdisk_is_finite(q)) {
          acb_div(e, x, y, kRefPrec);
          ASSERT_TRUE(holds(q, e)) << it;
          acb_inv(e, y, kRefPrec);
          ASSERT_TRUE(holds(i, e)) << it;
        }
      }
  }
  EXPECT_GT(divisions, iterations(600) / 2);  // most divisors exclude 0
  acb_clear(x);
  acb_clear(y);
  acb_clear(e);
}

TEST(CDisk, SquareRootContainsEveryPointsPrincipalRoot) {
  std::mt19937_64 rng(22);
  acb_t x, e;
  acb_init(x);
  acb_init(e);
  long taken = 0;
  for (long it = 0; it < iterations(800); ++it) {
    const CDisk a = random_disk(rng);
    const CDisk r = cdisk_sqrt_analytic(a);
    // refused exactly when the disc may reach (-inf, 0] (up to the
    // margins of the lower bound of |c|)
    const double m = std::hypot(a.re, a.im);
    const bool clear = a.re > 0 ? a.rad < m * (1 - 1e-12) : a.rad < std::fabs(a.im) * (1 - 1e-12);
    const bool reaches = a.re > 0 ? a.rad >= m : a.rad >= std::fabs(a.im);
    if (clear) ASSERT_TRUE(cdisk_is_finite(r)) << it;
    if (reaches) ASSERT_FALSE(cdisk_is_finite(r)) << it;
    if (!cdisk_is_finite(r)) continue;
    ++taken;
    for (const auto& pa : points(a, rng)) {
      acb_set_d_d(x, pa.first, pa.second);
      acb_sqrt(e, x, kRefPrec);
      ASSERT_TRUE(holds(r, e)) << it;
    }
  }
  EXPECT_GT(taken, iterations(800) / 4);
  acb_clear(x);
  acb_clear(e);
}

// Point discs: the results' radii are rounding only, a few units of 2^-53
// of the result (and above the true rounding error, by the test above).
TEST(CDisk, PointDiscsGiveResultsAccurateToAFewUlps) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(-1, 1);
  for (long it = 0; it < iterations(400); ++it) {
    const CDisk a{u(rng), u(rng), 0}, b{u(rng), it % 2 ? u(rng) : 0.0, 0};
    auto rel = [](const CDisk& d) { return d.rad / std::hypot(d.re, d.im); };
    EXPECT_LE(rel(cdisk_mul(a, b)), 0x1p-50) << it;
    EXPECT_LE(rel(cdisk_inv(a)), 0x1p-50) << it;
    EXPECT_LE(rel(cdisk_div(a, b)), 0x1p-49) << it;
    if (a.re > 0 || a.im != 0) EXPECT_LE(rel(cdisk_sqrt_analytic(a)), 0x1p-49) << it;
    EXPECT_LE(cdisk_add(a, b).rad, 0x1p-50) << it;
  }
}

TEST(CDisk, PolesAndBranchCutsAreRefused) {
  // 0 in the divisor's disc
  EXPECT_FALSE(cdisk_is_finite(cdisk_inv(CDisk{1, 1, 1.5})));
  EXPECT_FALSE(cdisk_is_finite(cdisk_inv(CDisk{0, 0, 0})));
  EXPECT_TRUE(cdisk_is_finite(cdisk_inv(CDisk{1, 1, 1.4})));
  // the cut: centre left of 0 with the disc crossing the negative axis
  EXPECT_FALSE(cdisk_is_finite(cdisk_sqrt_analytic(CDisk{-1, 0.5, 0.6})));
  EXPECT_TRUE(cdisk_is_finite(cdisk_sqrt_analytic(CDisk{-1, 0.5, 0.4})));
  EXPECT_FALSE(cdisk_is_finite(cdisk_sqrt_analytic(CDisk{-1, 0, 0})));
  // right of 0: refused only when the disc holds 0
  EXPECT_TRUE(cdisk_is_finite(cdisk_sqrt_analytic(CDisk{1, 0, 0.99})));
  EXPECT_FALSE(cdisk_is_finite(cdisk_sqrt_analytic(CDisk{1, 0, 1.01})));
  // out of range, NaN propagate as unknown
  EXPECT_FALSE(cdisk_is_finite(cdisk_inv(CDisk{0x1p500, 0, 0})));
  EXPECT_FALSE(cdisk_is_finite(cdisk_mul(CDisk{NAN, 0, 0}, CDisk{1, 0, 0})));
}

TEST(CDisk, ArbBoxesRoundTrip) {
  std::mt19937_64 rng(24);
  acb_t z, t;
  acb_init(z);
  acb_init(t);
  for (long it = 0; it < iterations(300); ++it) {
    const CDisk a = random_disk(rng);
    // a box with a midpoint of more than 53 bits: set_acb rounds it
    acb_t third;
    acb_init(third);
    acb_set_d_d(third, a.re / 3 + 1e-3, a.im / 7);
    acb_div_ui(third, third, 3, 200);
    mag_set_d(arb_radref(acb_realref(third)), a.rad);
    mag_set_d(arb_radref(acb_imagref(third)), a.rad / 2);
    const CDisk d = cdisk_set_acb(third);
    ASSERT_TRUE(cdisk_is_finite(d));
    for (double fx : {-1.0, 0.0, 1.0})
      for (double fy : {-1.0, 0.0, 1.0}) {
        // the box's corners and edge midpoints, exactly
        acb_set(t, third);
        mag_zero(arb_radref(acb_realref(t)));
        mag_zero(arb_radref(acb_imagref(t)));
        arf_t o;
        arf_init(o);
        arf_set_mag(o, arb_radref(acb_realref(third)));
        arf_mul_si(o, o, static_cast<slong>(fx), ARF_PREC_EXACT, ARF_RND_DOWN);
        arb_add_arf(acb_realref(t), acb_realref(t), o, ARF_PREC_EXACT);
        arf_set_mag(o, arb_radref(acb_imagref(third)));
        arf_mul_si(o, o, static_cast<slong>(fy), ARF_PREC_EXACT, ARF_RND_DOWN);
        arb_add_arf(acb_imagref(t), acb_imagref(t), o, ARF_PREC_EXACT);
        arf_clear(o);
        ASSERT_TRUE(holds(d, t)) << it;
      }
    // and back: the box holds the disc's points
    cdisk_get_acb(z, d);
    for (const auto& p : points(d, rng)) {
      acb_set_d_d(t, p.first, p.second);
      ASSERT_TRUE(acb_contains(z, t)) << it;
    }
    acb_clear(third);
  }
  acb_clear(z);
  acb_clear(t);
}

}  // namespace
}  // namespace uniparam
