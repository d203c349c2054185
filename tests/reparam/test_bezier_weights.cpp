// The new weights of the optimal bilinear reparameterization of an integral
// Bezier curve, v_i (1 - alpha)^i alpha^(n - i) in Q(sqrt c): equal (same
// canonical form) to the definition multiplied out, and computed with
// O(log n) products of two general surds, not O(n).
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using test_support::iterations;

namespace {

BezierCurve random_integral_bezier(std::mt19937_64& rng, long degree) {
  std::uniform_int_distribution<long> num(-9, 9), den(1, 5);
  for (;;) {
    std::vector<std::vector<Rational>> pts(static_cast<std::size_t>(degree + 1));
    for (auto& p : pts)
      for (int k = 0; k < 2; ++k) p.push_back(Rational(num(rng), den(rng)));
    bool constant = true;
    for (const auto& p : pts) constant = constant && p == pts.front();
    if (!constant) return BezierCurve(pts);
  }
}

long bit_length(long n) {
  long b = 0;
  for (; n > 0; n >>= 1) ++b;
  return b;
}

}  // namespace

// Oracle: (1 - alpha)^i alpha^(n - i) by n - 1 products; the canonical forms
// (hence the printed text) agree, and so do the values.
TEST(BezierWeights, EqualTheDefinitionMultipliedOut) {
  std::mt19937_64 rng(4711);
  Options o;
  o.digits = 8;
  long irrational = 0;
  for (long it = 0; it < iterations(3); ++it)
    for (long n = 1; n <= 12; ++n) {
      const BezierCurve b = random_integral_bezier(rng, n);
      const BezierResult r = bezier_optimal(b, o);
      ASSERT_TRUE(r.exact);
      const QuadraticSurd& a = *r.alpha_exact;
      irrational += a.is_rational() ? 0 : 1;
      const QuadraticSurd om = QuadraticSurd(Rational(1)) - a;
      ASSERT_EQ(r.weights_exact.size(), static_cast<std::size_t>(n + 1));
      for (long i = 0; i <= n; ++i) {
        QuadraticSurd w(Rational(1));
        for (long k = 0; k < i; ++k) w = w * om;
        for (long k = i; k < n; ++k) w = w * a;
        const QuadraticSurd& got = r.weights_exact[static_cast<std::size_t>(i)];
        EXPECT_EQ((w - got).sign(), 0) << b.str() << " weight " << i;
        EXPECT_EQ(w.str(Format::Text), got.str(Format::Text));
        EXPECT_EQ(w.x(), got.x());
        EXPECT_EQ(w.y(), got.y());
        EXPECT_EQ(w.c(), got.c());
      }
    }
  EXPECT_GT(irrational, 0);  // the surd path was exercised
}

// Work count: the weights take O(log n) products of two general surds
// (alpha^n by binary powering), the rest being products by y sqrt(c) or by
// rationals; a product per weight (O(n)) is what makes high degrees slow.
TEST(BezierWeights, LogarithmicNumberOfFullSurdProducts) {
  std::mt19937_64 rng(1997);
  Options o;
  o.digits = 5;
  for (long n : {16L, 40L, 90L}) {
    BezierCurve b = random_integral_bezier(rng, n);
    for (int tries = 0; tries < 20; ++tries) {
      // an irrational alpha (a rational one needs no surd product at all)
      if (!bezier_optimal(b, o).alpha_exact->is_rational()) break;
      b = random_integral_bezier(rng, n);
    }
    const std::size_t before = QuadraticSurd::full_products();
    const BezierResult r = bezier_optimal(b, o);
    const std::size_t used = QuadraticSurd::full_products() - before;
    ASSERT_FALSE(r.alpha_exact->is_rational());
    EXPECT_LE(used, static_cast<std::size_t>(2 * bit_length(n))) << "degree " << n;
  }
}
