// optimise_breakpoints (uniparam/reparam/breakpoints.hpp), the floating-point
// search for T, on speeds given as callbacks. Oracle: sigma^2 a random
// polynomial positive on [0, 1] whose piece moments are integrated exactly
// (polynomial arithmetic in double), so Phi is known at any T independently of
// the search; the returned T must be a local minimum of that Phi.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

using Coeffs = std::vector<double>;  // low to high degree

double horner(const Coeffs& p, double t) {
  double r = 0;
  for (std::size_t i = p.size(); i-- > 0;) r = r * t + p[i];
  return r;
}

// q(u) = p(a + h u), by repeated synthetic division (Taylor shift then scale).
Coeffs shifted(Coeffs p, double a, double h) {
  const std::size_t n = p.size();
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = n - 1; j > i; --j) p[j - 1] += a * p[j];
  double s = 1;
  for (double& c : p) {
    c *= s;
    s *= h;
  }
  return p;
}

// int_0^1 q(u) u^k (1 - u)^m du for the three weights, times h (over dt).
PieceMoments exact_moments(const Coeffs& sigma2, double a, double b) {
  const double h = b - a;
  const Coeffs q = shifted(sigma2, a, h);
  // int_0^1 u^j (1-u)^2 = 2 / ((j+1)(j+2)(j+3)), int u^j 2u(1-u) = 2 / ((j+2)(j+3)), int u^j u^2 = 1/(j+3)
  PieceMoments m;
  for (std::size_t j = 0; j < q.size(); ++j) {
    const double d = static_cast<double>(j);
    m.A += q[j] * 2 / ((d + 1) * (d + 2) * (d + 3));
    m.B += q[j] * 2 / ((d + 2) * (d + 3));
    m.C += q[j] / (d + 3);
  }
  m.A *= h;
  m.B *= h;
  m.C *= h;
  return m;
}

double phi(const Coeffs& sigma2, const std::vector<double>& t) {
  double s = 0;
  for (std::size_t i = 0; i + 1 < t.size(); ++i) {
    const PieceMoments m = exact_moments(sigma2, t[i], t[i + 1]);
    s += std::sqrt((t[i + 1] - t[i]) * (m.B + 2 * std::sqrt(m.A * m.C)));
  }
  return s;
}

// 1/20 + r(t)^2 with r of degree 3 to 5 and coefficients in [-4, 4]: peaks
// and valleys inside [0, 1].
Coeffs random_sigma2(std::mt19937& rng) {
  std::uniform_real_distribution<double> coef(-4, 4);
  std::uniform_int_distribution<int> deg(3, 5);
  Coeffs r(static_cast<std::size_t>(deg(rng)) + 1);
  for (double& c : r) c = coef(rng);
  Coeffs p(2 * r.size() - 1, 0.0);
  for (std::size_t i = 0; i < r.size(); ++i)
    for (std::size_t j = 0; j < r.size(); ++j) p[i + j] += r[i] * r[j];
  p[0] += 0.05;
  return p;
}

BreakpointChoice run(const Coeffs& sigma2, long N) {
  return optimise_breakpoints(
      N, [&](double a, double b) { return exact_moments(sigma2, a, b); },
      [&](double t) { return horner(sigma2, t); });
}

}  // namespace

TEST(OptimiseBreakpoints, ReturnsALocalMinimumOfPhiOnRandomSpeeds) {
  std::mt19937 rng(20261123);
  for (int trial = 0; trial < 12; ++trial) {
    const Coeffs s2 = random_sigma2(rng);
    const long N = 2 + trial % 4;
    const BreakpointChoice c = run(s2, N);
    ASSERT_EQ(c.t.size(), static_cast<std::size_t>(N + 1));
    EXPECT_EQ(c.t.front(), 0.0);
    EXPECT_EQ(c.t.back(), 1.0);
    for (long j = 0; j < N; ++j) ASSERT_GT(c.t[j + 1] - c.t[j], 1e-12) << "trial " << trial;
    // Phi as reported is Phi at t, and never above the equal spacing's
    const double p = phi(s2, c.t);
    EXPECT_NEAR(c.phi, p, 1e-13 * p) << "trial " << trial;
    std::vector<double> eq;
    for (long i = 0; i <= N; ++i) eq.push_back(static_cast<double>(i) / static_cast<double>(N));
    EXPECT_NEAR(c.phi_equal, phi(s2, eq), 1e-13 * p);
    EXPECT_LE(c.phi, c.phi_equal);
    EXPECT_LT(c.stationarity, 1e-6) << "trial " << trial;
    // a local minimum: moving any one breakpoint either way raises Phi
    for (long j = 1; j < N; ++j) {
      const double d = 1e-3 * std::min(c.t[j] - c.t[j - 1], c.t[j + 1] - c.t[j]);
      for (double sign : {-1.0, 1.0}) {
        std::vector<double> t = c.t;
        t[j] += sign * d;
        EXPECT_GE(phi(s2, t), p * (1 - 1e-13)) << "trial " << trial << " breakpoint " << j;
      }
    }
  }
}

TEST(OptimiseBreakpoints, OnePieceAndBadCounts) {
  const Coeffs s2 = {1, -2, 3};
  const BreakpointChoice c = run(s2, 1);
  ASSERT_EQ(c.t.size(), 2u);
  EXPECT_EQ(c.iterations, 0);
  EXPECT_DOUBLE_EQ(c.phi, phi(s2, {0.0, 1.0}));
  EXPECT_THROW(run(s2, 0), InvalidArgument);
}
