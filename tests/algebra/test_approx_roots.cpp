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

}  // namespace
}  // namespace uniparam
