// Tests of uniparam/algebra/approx_roots.hpp (UNCERTIFIED approximations):
// polynomials built from known roots, so the exact roots are the oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/approx_roots.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::iterations;
using C = std::complex<double>;

/// Greedy matching: every expected root has its own approximation within
/// tol * max(1, |root|); false (with a message) otherwise.
::testing::AssertionResult all_matched(std::vector<C> got, const std::vector<C>& want, double tol) {
  if (got.size() != want.size())
    return ::testing::AssertionFailure() << got.size() << " approximations for " << want.size() << " roots";
  for (const C& w : want) {
    std::size_t best = got.size();
    double d = 1e300;
    for (std::size_t i = 0; i < got.size(); ++i)
      if (std::abs(got[i] - w) < d) {
        d = std::abs(got[i] - w);
        best = i;
      }
    if (best == got.size() || d > tol * std::max(1.0, std::abs(w)))
      return ::testing::AssertionFailure() << "root " << w.real() << " + " << w.imag() << " i: nearest at " << d;
    got.erase(got.begin() + static_cast<long>(best));
  }
  return ::testing::AssertionSuccess();
}

TEST(ApproxRoots, RecoversRandomRationalAndComplexRoots) {
  // p = prod (q t - r) * prod (t^2 + b t + c) with b^2 < 4c: known roots
  // r / q and -b/2 +- i sqrt(c - b^2/4), all distinct.
  std::mt19937 rng(20261123u);
  std::uniform_int_distribution<long> num(-40, 40), den(1, 9), lin(0, 5), quad(0, 4), bq(-6, 6), cq(1, 30);
  const long n = iterations(40);
  for (long it = 0; it < n; ++it) {
    Poly p(1);
    std::vector<C> want;
    const long nl = lin(rng), nq = quad(rng);
    for (long i = 0; i < nl; ++i) {
      const long r = num(rng), q = den(rng);
      const C root(static_cast<double>(r) / static_cast<double>(q), 0);
      bool dup = false;
      for (const C& w : want) dup = dup || std::abs(w - root) < 1e-3;
      if (dup) continue;
      p = p * Poly(std::vector<long>{-r, q});
      want.push_back(root);
    }
    for (long i = 0; i < nq; ++i) {
      const long b = bq(rng), c = cq(rng);
      if (b * b >= 4 * c) continue;
      const C root(-0.5 * static_cast<double>(b), std::sqrt(static_cast<double>(c) - 0.25 * static_cast<double>(b * b)));
      bool dup = false;
      for (const C& w : want) dup = dup || std::abs(w - root) < 1e-3;
      if (dup) continue;
      p = p * Poly(std::vector<long>{c, b, 1});
      want.push_back(root);
      want.push_back(std::conj(root));
    }
    SCOPED_TRACE("iteration " + std::to_string(it) + ": " + p.str());
    bool converged = false;
    const auto got = approximate_complex_roots(p, &converged);
    EXPECT_TRUE(converged);
    EXPECT_TRUE(all_matched(got, want, 1e-6));
    EXPECT_EQ(got, approximate_complex_roots(p)) << "not deterministic";
  }
}

TEST(ApproxRoots, RootsAtZeroAreExactAndHugeCoefficientsScale) {
  // t^3 (t - 2) (t^2 + 1), times 2^300: the scaling keeps it in range
  Poly p = Poly(std::vector<long>{0, 0, 0, 1}) * Poly(std::vector<long>{-2, 1}) * Poly(std::vector<long>{1, 0, 1});
  Integer big;
  fmpz_one(big.get());
  fmpz_mul_2exp(big.get(), big.get(), 300);
  p = p * Poly(std::vector<Integer>{big});
  bool converged = false;
  const auto got = approximate_complex_roots(p, &converged);
  ASSERT_EQ(got.size(), 6u);
  EXPECT_TRUE(converged);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(got[static_cast<std::size_t>(i)], C(0, 0));
  EXPECT_TRUE(all_matched({got.begin() + 3, got.end()}, {C(2, 0), C(0, 1), C(0, -1)}, 1e-9));
}

TEST(ApproxRoots, MultipleRootsAreApproximatedLoosely) {
  // (2t - 1)^3 (t + 3)^2: a triple and a double root, which Aberth's
  // iteration approaches only linearly and double arithmetic blurs
  Poly a(std::vector<long>{-1, 2}), b(std::vector<long>{3, 1});
  const Poly p = a * a * a * b * b;
  const auto got = approximate_complex_roots(p);
  EXPECT_TRUE(all_matched(got, {C(0.5, 0), C(0.5, 0), C(0.5, 0), C(-3, 0), C(-3, 0)}, 1e-3));
}

TEST(ApproxRoots, ConstantsAndTheZeroPolynomial) {
  bool converged = false;
  EXPECT_TRUE(approximate_complex_roots(Poly(7), &converged).empty());
  EXPECT_TRUE(converged);
  EXPECT_THROW(approximate_complex_roots(Poly(0)), InvalidArgument);
  EXPECT_TRUE(all_matched(approximate_complex_roots(Poly(std::vector<long>{3, 4})), {C(-0.75, 0)}, 1e-12));
}

// The centred variant: random roots near [0, 1] (rational, and complex
// pairs at distance <= 1/4 of the axis) are found as t, not as s = 2t - 1;
// the reported loss decides, on either side of max_loss.
TEST(ApproxRoots, NearTheUnitIntervalFindsTheRootsAndHonoursItsLossLimit) {
  std::mt19937 rng(20261202u);
  std::uniform_int_distribution<long> num(0, 64), nlin(1, 8), nquad(0, 4), cre(0, 32), cim(1, 8);
  const long n = iterations(40);
  for (long it = 0; it < n; ++it) {
    Poly p(1);
    std::vector<C> want;
    const long nl = nlin(rng), nq = nquad(rng);
    for (long i = 0; i < nl; ++i) {  // r / 64 in [0, 1]
      const long r = num(rng);
      const C root(static_cast<double>(r) / 64, 0);
      bool dup = false;
      for (const C& w : want) dup = dup || std::abs(w - root) < 1e-3;
      if (dup) continue;
      p = p * Poly(std::vector<long>{-r, 64});
      want.push_back(root);
    }
    for (long i = 0; i < nq; ++i) {  // (32 t - a)^2 + b^2: roots (a +- i b) / 32
      const long a = cre(rng), b = cim(rng);
      const C root(static_cast<double>(a) / 32, static_cast<double>(b) / 32);
      bool dup = false;
      for (const C& w : want) dup = dup || std::abs(w - root) < 1e-3 || std::abs(w - std::conj(root)) < 1e-3;
      if (dup) continue;
      p = p * Poly(std::vector<long>{a * a + b * b, -64 * a, 1024});
      want.push_back(root);
      want.push_back(std::conj(root));
    }
    double loss = -1;
    const auto got = approximate_roots_near_unit_interval(p, 1000, &loss);
    ASSERT_GE(loss, 0) << p.str();  // sum |q_k| >= max |q|
    EXPECT_TRUE(all_matched(got, want, 1e-6)) << p.str();
    EXPECT_TRUE(approximate_roots_near_unit_interval(p, loss - 0.5).empty()) << p.str();
    EXPECT_EQ(approximate_roots_near_unit_interval(p, loss + 0.5).size(), want.size()) << p.str();
  }
}

// T_30(2t - 1): its centred basis 2^30 T_30(s) loses log2 of the sum of
// T_30's |coefficients| ((1 + sqrt 2)^30 / 2 + ..., ~37 bits) against its
// peak 1 on [-1, 1]: refused at 30 bits, its roots (1 + cos((2j + 1) pi /
// 60)) / 2 found at 40. The loss is measured on all of [-1, 1].
TEST(ApproxRoots, NearTheUnitIntervalRefusesACentredBasisThatLosesTooMuch) {
  const Poly x(std::vector<long>{-1, 2});  // 2t - 1
  Poly t0(1), t1 = x;
  for (int k = 1; k < 30; ++k) {
    const Poly t2 = Poly(2) * x * t1 - t0;
    t0 = t1;
    t1 = t2;
  }
  double loss = 0;
  EXPECT_TRUE(approximate_roots_near_unit_interval(t1, 30, &loss).empty());
  EXPECT_GT(loss, 36);
  EXPECT_LT(loss, 38);
  std::vector<C> want;
  for (int j = 0; j < 30; ++j) want.emplace_back((1 + std::cos((2 * j + 1) * 3.14159265358979323846 / 60)) / 2, 0);
  EXPECT_TRUE(all_matched(approximate_roots_near_unit_interval(t1, 40), want, 1e-6));
  EXPECT_THROW(approximate_roots_near_unit_interval(Poly(0), 30), InvalidArgument);
  // (1 - t)^24 is (1 - s)^24 times 2^-24: no loss, its peak at s = -1
  const Poly one_minus_t(std::vector<long>{1, -1});
  approximate_roots_near_unit_interval(one_minus_t.pow(24), 30, &loss);
  EXPECT_LT(loss, 1e-9);
}

// (2t - 1)^20: sum |a_k| = 3^20 against its peak 1 at t = 0 and 1, so
// 20 log2 3 bits on its own basis; none centred (2^20 s^20 ... scaled).
TEST(ApproxRoots, PowerBasisLossIsTheRatioOfTheAbsoluteSumToThePeak) {
  const Poly x(std::vector<long>{-1, 2});
  const Poly p = x.pow(20);
  EXPECT_NEAR(power_basis_loss(p), 20 * std::log2(3.0), 1e-9);
  double loss = -1;
  approximate_roots_near_unit_interval(p, 30, &loss);
  EXPECT_NEAR(loss, 0, 1e-9);
  EXPECT_THROW(power_basis_loss(Poly(0)), InvalidArgument);
}

}  // namespace
}  // namespace uniparam
