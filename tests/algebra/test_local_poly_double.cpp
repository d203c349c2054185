// Tests of uniparam/algebra/local_poly.hpp's double-precision paths: the
// centred form in double on wide balls of low degree (certified), and the
// UNCERTIFIED values and Taylor coefficients in double against exact ones.
#include <acb_poly.h>
#include <arb_poly.h>
#include <flint/flint.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "support/balls.hpp"
#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/algebra/local_poly.hpp"
#include "uniparam/core/error.hpp"
#include "algebra/local_poly_support.hpp"

namespace uniparam {
namespace {

using local_poly_test::bernstein;
using local_poly_test::kRefPrec;
using local_poly_test::random_ball;
using local_poly_test::random_test_poly;
using local_poly_test::RefDerivatives;

using test_support::expect_encloses_at_points;
using test_support::iterations;
using test_support::offsets;
using test_support::point_of;
using test_support::random_poly;

// Wide balls with a real midpoint, of polynomials of degree <= 64 whose
// power basis loses few bits, are bounded by the centred form in double at
// their midpoint (DoubleCentredForm, tested on its own): on
// K (2^b t - a)^n around a 2^-b that bound is exact up to rounding, which
// the cells (a disc about twice the radius) are not. Balls where the form
// is refused (radius 2^-24 at the zero: rounding; radius up to 256:
// overflow) still get finite enclosures of the exact values.
TEST(LocalPoly, WideBallsOfLowDegreeGetTheCentredFormAtTheirMidpoint) {
  std::mt19937_64 rng(112327);
  std::uniform_real_distribution<double> unit(0, 1);
  for (long it = 0; it < iterations(60); ++it) {
    const test_support::PurePower c = test_support::random_pure_power(rng);
    const Poly& p = c.p;
    const LocalPoly lp(p);
    const double rx = c.m * (0.25 + 1.75 * unit(rng)), ry = rx * unit(rng);
    acb_t z, v, d1, d2;
    for (acb_ptr x : {z, v, d1, d2}) acb_init(x);
    acb_zero(z);
    arb_set_d(acb_realref(z), c.m);
    mag_set_d(arb_radref(acb_realref(z)), rx);
    mag_set_d(arb_radref(acb_imagref(z)), ry);
    const acb_struct* outs[3] = {v, d1, d2};
    lp.eval(v, d1, d2, z, 64);
    const std::string what = "of K (2^b t - a)^n, n = " + std::to_string(c.n);
    test_support::expect_pure_power_bounds(c, outs, z, rng, what);
    // refused: rounding near the zero, overflow at radius up to 256
    for (const double rr : {0x1p-24, 64 + 192 * unit(rng)}) {
      mag_set_d(arb_radref(acb_realref(z)), rr);
      mag_set_d(arb_radref(acb_imagref(z)), rr * unit(rng));
      lp.eval(v, d1, d2, z, 64);
      expect_encloses_at_points(p, outs, z, rng, "(refused) " + what);
      for (acb_srcptr o : {v, d1, d2}) EXPECT_TRUE(acb_is_finite(o)) << what;
    }
    for (acb_ptr x : {z, v, d1, d2}) acb_clear(x);
  }
}

}  // namespace
}  // namespace uniparam

namespace uniparam {
namespace {

/// The Taylor coefficients e_k of p at the double t (p(t + h) = sum e_k h^k),
/// exact (t is dyadic), then rounded to doubles.
std::vector<double> exact_taylor(const Poly& p, double t) {
  arb_poly_t e;
  arb_poly_init(e);
  arb_poly_set_fmpz_poly(e, p.get(), ARF_PREC_EXACT);
  arb_t tt;
  arb_init(tt);
  arb_set_d(tt, t);
  arb_poly_taylor_shift(e, e, tt, 4 * (p.degree() + 64) + p.max_bits());
  std::vector<double> out(static_cast<std::size_t>(arb_poly_length(e)));
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = arf_get_d(arb_midref(arb_poly_get_coeff_ptr(e, static_cast<slong>(k))), ARF_RND_NEAR);
  arb_clear(tt);
  arb_poly_clear(e);
  return out;
}

/// The scale of the j-th Taylor coefficient on a cell near t:
/// sum_{k >= j} C(k, j) |e_k| 2^-(k-j).
double local_scale(const std::vector<double>& e, int j) {
  double scale = 0, binom = 1;
  for (std::size_t k = static_cast<std::size_t>(j); k < e.size(); ++k) {
    scale += binom * std::fabs(e[k]) * std::ldexp(1.0, -static_cast<int>(k - static_cast<std::size_t>(j)));
    binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - static_cast<std::size_t>(j));
  }
  return scale;
}

/// eval_double_taylor against the exact Taylor coefficients p^(j)(t) / j!
/// (p shifted to the double t exactly, then rounded): random polynomials
/// (Bernstein ones up to degree 160, whose power basis is useless in
/// double), t inside [0, 1] (local expansions) and outside (power basis).
/// The tolerance is 2^-40 of the coefficient's scale (inside: sum_k C(k, j)
/// |e_k| 2^-(k-j), which double arithmetic on a level-6 cell meets by far;
/// outside, that of the power basis' terms);
/// fails with an off-by-one in the passes or the shift's sign.
TEST(LocalPoly, DoubleTaylorCoefficientsMatchTheExactShift) {
  std::mt19937_64 rng(777);
  std::uniform_real_distribution<double> in(0.0, 1.0), out(1.0, 1.25);
  for (long it = 0; it < iterations(30); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly lp(p);
    for (int k = 0; k < 6; ++k) {
      const double t = k < 5 ? in(rng) : out(rng);
      const int order = 1 + static_cast<int>(rng() % 8);
      std::vector<double> b(static_cast<std::size_t>(order + 1));
      lp.eval_double_taylor(t, order, b.data());
      // exact: p(t + h) = sum e_j h^j (t is a dyadic double)
      const std::vector<double> ex = exact_taylor(p, t);
      const long len = static_cast<long>(ex.size());
      auto ed = [&](long k) { return k < len ? ex[static_cast<std::size_t>(k)] : 0.0; };
      for (int j = 0; j <= order; ++j) {
        // Inside [0, 1]: the local expansion's scale near t. Outside: the
        // power basis is used (documented), so the scale of its terms,
        // sum_k C(k, j) |c_k| t^(k-j).
        double scale = 0, binom = 1;
        if (t <= 1) {
          scale = local_scale(ex, j);
        } else {
          for (long k = j; k <= p.degree(); ++k) {
            scale += binom * std::fabs(fmpz_get_d(p.get()->coeffs + k)) * std::pow(t, static_cast<double>(k - j));
            binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - j);
          }
        }
        SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", t = " + std::to_string(t) + ", j = " +
                     std::to_string(j));
        EXPECT_LE(std::fabs(b[static_cast<std::size_t>(j)] - ed(j)), std::ldexp(scale, -40) + 1e-300);
      }
    }
  }
  double b[17];
  EXPECT_THROW(LocalPoly(Poly(std::vector<long>{1, 2, 3})).eval_double_taylor(0.5, 16, b), InvalidArgument);
  EXPECT_THROW(LocalPoly(Poly(std::vector<long>{1, 2, 3})).eval_double_taylor(0.5, -1, b), InvalidArgument);
}

TEST(LocalPoly, DoubleValuesMatchTheExactValuesAtCellEndsAndInside) {
  // eval_double (uncertified, the optimisers' sigma^2) picks the cell of t
  // from t's double: at the ends k/64 of the point level's cells, one ulp
  // either side of them, and at random points, p, p', p'' agree with the
  // exact values to 2^-40 of the local expansion's scale.
  // Low degrees (3-16, small coefficients) too: there eval_double may take
  // Horner's rule on the power basis, whose error is bounded by the power
  // basis' scale sum_k C(k, j) |c_k| t^(k-j) instead.
  std::mt19937_64 rng(4242);
  std::uniform_real_distribution<double> in(0.0, 1.0);
  for (long it = 0; it < iterations(30); ++it) {
    const bool low = it % 3 == 2;
    const Poly p = low ? random_poly(rng, std::uniform_int_distribution<long>(3, 16)(rng), 20) : random_test_poly(rng);
    const LocalPoly lp(p);
    std::vector<double> ts{0.0, 1.0, in(rng), in(rng)};
    for (int k = 1; k < 64; k += 1 + static_cast<int>(rng() % 9)) {
      const double e = std::ldexp(static_cast<double>(k), -6);
      ts.insert(ts.end(), {e, std::nextafter(e, 0.0), std::nextafter(e, 1.0)});
    }
    for (double t : ts) {
      double v, d1, d2;
      lp.eval_double(t, &v, &d1, &d2);
      const std::vector<double> ex = exact_taylor(p, t);
      const double got[3] = {v, d1, d2 / 2};  // Taylor coefficients e_0, e_1, e_2
      for (int j = 0; j < 3; ++j) {
        const double want = static_cast<std::size_t>(j) < ex.size() ? ex[static_cast<std::size_t>(j)] : 0.0;
        SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", t = " + std::to_string(t) + ", j = " +
                     std::to_string(j));
        double scale = local_scale(ex, j);
        if (low) {
          double power = 0, binom = 1;
          for (long k = j; k <= p.degree(); ++k) {
            power += binom * std::fabs(fmpz_get_d(p.get()->coeffs + k)) * std::pow(t, static_cast<double>(k - j));
            binom = binom * static_cast<double>(k + 1) / static_cast<double>(k + 1 - j);
          }
          scale = std::max(scale, power);
        }
        EXPECT_LE(std::fabs(got[j] - want), std::ldexp(scale, -40) + 1e-300);
      }
    }
  }
}

// eval_double and eval_double_taylor keep each thread's recent cells: a
// LocalPoly made where an earlier one was destroyed (often at the same
// address), of another polynomial, must get its own cells, never the
// earlier one's. Short-lived LocalPolys of random polynomials, evaluated at
// the same points one after the other, agree with the exact values.
TEST(LocalPoly, DoubleValuesOfShortLivedPolynomialsAreTheirOwn) {
  std::mt19937_64 rng(20261204);
  const double ts[] = {0.1, 0.37, 0.5, 0.81};
  for (long it = 0; it < iterations(40); ++it) {
    const Poly p = random_test_poly(rng);
    const LocalPoly lp(p);
    for (double t : ts) {
      double v, b[3];
      lp.eval_double(t, &v, nullptr, nullptr);
      lp.eval_double_taylor(t, 2, b);
      const std::vector<double> ex = exact_taylor(p, t);
      SCOPED_TRACE("degree " + std::to_string(p.degree()) + ", t = " + std::to_string(t));
      EXPECT_LE(std::fabs(v - ex[0]), std::ldexp(local_scale(ex, 0), -40) + 1e-300);
      for (int j = 0; j < 3; ++j) {
        const double want = static_cast<std::size_t>(j) < ex.size() ? ex[static_cast<std::size_t>(j)] : 0.0;
        EXPECT_LE(std::fabs(b[j] - want), std::ldexp(local_scale(ex, j), -40) + 1e-300) << "j = " << j;
      }
    }
  }
}

}  // namespace
}  // namespace uniparam
