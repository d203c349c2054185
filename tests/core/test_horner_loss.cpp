// Tests of horner_loss_bits (core/horner_loss.hpp), the one estimate of
// Horner's cancellation: exact oracles on polynomials whose coefficient sums
// and peaks are known, and the callers that take it.
#include <flint/fmpz.h>
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/horner_loss.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {
namespace {

Poly linear(long a, long b) { return Poly(std::vector<long>{b, a}); }  // a t + b

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }

Integer pow2(unsigned long e) {
  Integer r(1);
  fmpz_mul_2exp(r.get(), r.get(), e);
  return r;
}

// (2t - 1)^n: sum |c_k| = 3^n, max on [0, 1] = 1 (at 0 and 1, grid points);
// its j-th derivative is 2^j n!/(n-j)! (2t - 1)^(n-j): loss (n - j) log2 3.
// (Up to degree 16: a loss near 53 bits would drown the peak in Horner's
// own rounding in double.)
TEST(HornerLoss, PowersOfACentredLinearFactorLoseNLog2Three) {
  for (int n = 1; n <= 16; n += 3) {
    const Poly p = linear(2, -1).pow(static_cast<unsigned long>(n));
    for (int order = 0; order <= 2; ++order)
      EXPECT_NEAR(horner_loss_bits(p, 0, 1, order), n * std::log2(3.0), 1e-6) << "n = " << n;
    // on [-1, 1]: max at t = -1, |(-3)^n| = 3^n = the sum: nothing lost
    EXPECT_NEAR(horner_loss_bits(p, -1, 1, 0), 0, 1e-6);
  }
}

// Positive coefficients: Horner at t = 1 sums them exactly, no loss; the
// estimate ignores the common scale and the sign.
TEST(HornerLoss, PositiveCoefficientsLoseNothingAtAnyScale) {
  const Poly p = linear(1, 1).pow(30);
  EXPECT_NEAR(horner_loss_bits(p, 0, 1, 2), 0, 1e-12);
  const Poly big = p * constant(pow2(3000));
  EXPECT_NEAR(horner_loss_bits(big, 0, 1, 2), 0, 1e-12);
  EXPECT_NEAR(horner_loss_bits(Poly() - big, 0, 1, 2), 0, 1e-12);
}

// The most over the orders: a huge constant hides p's own loss, not its
// derivatives'.
TEST(HornerLoss, TheDerivativesCountUpToTheOrderAsked) {
  const int n = 25;
  const Poly p = linear(2, -1).pow(n) + constant(pow2(200));
  EXPECT_LT(horner_loss_bits(p, 0, 1, 0), 1e-6);
  EXPECT_NEAR(horner_loss_bits(p, 0, 1, 1), (n - 1) * std::log2(3.0), 1e-6);
  EXPECT_NEAR(horner_loss_bits(p, 0, 1, 2), (n - 1) * std::log2(3.0), 1e-6);
}

TEST(HornerLoss, RefusesTheZeroPolynomialAndOrdersAboveTwo) {
  const Poly p = linear(2, -1);
  EXPECT_THROW(horner_loss_bits(Poly(), 0, 1, 0), InvalidArgument);
  EXPECT_THROW(horner_loss_bits(p, 0, 1, 3), InvalidArgument);
}

// DDPoly's path choice is this estimate (one estimator, not a copy).
TEST(HornerLoss, DoubleWordPolynomialsReportTheSameEstimate) {
  for (int n = 2; n <= 30; n += 4) {
    const Poly p = linear(2, -1).pow(static_cast<unsigned long>(n)) * linear(3, 1) + constant(Integer(7));
    const DDPoly d(p);
    ASSERT_TRUE(d.usable());
    EXPECT_EQ(d.cancellation_bits(), horner_loss_bits(p, 0, 1, 2)) << "n = " << n;
  }
}

}  // namespace
}  // namespace uniparam
