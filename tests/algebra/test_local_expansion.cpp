// Tests of uniparam/algebra/local_expansion.hpp, the expansion engine under
// LocalPoly's cells and the root isolation's subdivision: at random exact
// points w of the disc |w| <= rho of a cell, P(w) widened by the tails must
// contain G(c + w), G'(c + w) and G''(c + w) computed exactly with rationals
// -- for exact expansions, truncated ones, children shifted from their
// parents, and deflations by a root.
#include <arb_poly.h>
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/local_expansion.hpp"
#include "uniparam/core/error.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

// A random polynomial of degree 3..60: small dense coefficients, or a
// product of linear factors with roots in [0, 1] (values far below the
// power-basis coefficients there).
Poly random_poly(std::mt19937_64& rng) {
  const long n = std::uniform_int_distribution<long>(3, 60)(rng);
  if (rng() % 2 == 0) {
    std::vector<long> c(static_cast<std::size_t>(n + 1));
    for (auto& x : c) x = std::uniform_int_distribution<long>(-50, 50)(rng);
    c.back() = 1 + static_cast<long>(rng() % 50);
    return Poly(c);
  }
  Poly p(std::vector<long>{1});
  for (long k = 0; k < n; ++k) {
    const long d = 64, r = std::uniform_int_distribution<long>(0, d)(rng);
    p = p * Poly(std::vector<long>{-r, d});
  }
  return p;
}

// Checks at 12 random dyadic points w, |w| <= 2^log2_rho (and the disc's
// ends), that P^(i)(w) +- tail[i] contains G^(i)(c + w) for i < orders.
void expect_encloses(const LocalExpansion& e, const Poly& G, long log2_rho, int orders, std::mt19937_64& rng,
                     const std::string& what) {
  Rational c;
  arf_get_fmpq(c.get(), e.centre);
  const Poly dG[3] = {G, G.derivative(), G.derivative().derivative()};
  arb_poly_t D[3];
  for (auto& d : D) arb_poly_init(d);
  arb_poly_set(D[0], e.P);
  arb_poly_derivative(D[1], D[0], 4000);
  arb_poly_derivative(D[2], D[1], 4000);
  arb_t x, y;
  arb_init(x);
  arb_init(y);
  for (int k = 0; k < 14; ++k) {
    // w = s 2^log2_rho with s in [-1, 1] on a grid of 2^-20 (k < 2: the ends)
    const long num = k == 0 ? -(1L << 20) : k == 1 ? (1L << 20)
                            : std::uniform_int_distribution<long>(-(1L << 20), 1L << 20)(rng);
    const Rational w = Rational(num) * pow2(log2_rho - 20);
    arb_set_fmpq(x, w.get(), 4000);
    for (int i = 0; i < orders; ++i) {
      arb_poly_evaluate(y, D[i], x, 4000);
      arb_add_error_mag(y, e.tail + i);
      const Rational exact = dG[i](c + w);
      EXPECT_TRUE(arb_contains_fmpq(y, exact.get()))
          << what << ": order " << i << " at w = " << w.str() << " (level " << e.level << ", j " << e.j << ")";
    }
  }
  arb_clear(x);
  arb_clear(y);
  for (auto& d : D) arb_poly_clear(d);
}

TEST(LocalExpansion, ExactAndTruncatedExpansionsEncloseTheExactValues) {
  std::mt19937_64 rng(31337);
  for (long it = 0; it < iterations(60); ++it) {
    const Poly G = random_poly(rng);
    const int level = static_cast<int>(rng() % 12);
    const unsigned long long j = rng() % (1ULL << level);
    const long wp = rng() % 2 ? 64 : 192;
    LocalExpansion e;
    local_expansion_exact(e, G, level, j, wp);
    EXPECT_EQ(arb_poly_length(e.P), G.degree() + 1);
    expect_encloses(e, G, -level, 3, rng, "exact");
    // truncated on rho = h (orders 2) or 2h (orders 3), at 2^-eb of 1
    const int orders = rng() % 2 ? 2 : 3;
    const long log2_rho = orders == 2 ? -(level + 1) : -level;
    mag_t eps;
    mag_init(eps);
    mag_set_ui_2exp_si(eps, 1, -static_cast<long>(rng() % 40));
    truncate_local_expansion(e, log2_rho, eps, orders);
    EXPECT_GE(arb_poly_length(e.P), std::min<slong>(orders, G.degree() + 1));
    expect_encloses(e, G, log2_rho, orders, rng, "truncated");
    mag_clear(eps);
  }
}

TEST(LocalExpansion, ChildrenShiftedFromTheirParentEncloseTheExactValues) {
  std::mt19937_64 rng(4242);
  for (long it = 0; it < iterations(40); ++it) {
    const Poly G = random_poly(rng);
    const int level = static_cast<int>(rng() % 8);
    const unsigned long long j = rng() % (1ULL << level);
    LocalExpansion parent;
    local_expansion_exact(parent, G, level, j, 128);
    mag_t eps;
    mag_init(eps);
    mag_set_ui_2exp_si(eps, 1, -30);
    truncate_local_expansion(parent, -level, eps, 3);  // tails on |w| <= 2h
    for (int side : {-1, 1}) {
      LocalExpansion child;
      local_expansion_child(child, parent, side, 128);
      EXPECT_EQ(child.level, level + 1);
      EXPECT_EQ(child.j, 2 * j + (side > 0 ? 1 : 0));
      LocalExpansion exact;
      local_expansion_exact(exact, G, child.level, child.j, 128);
      EXPECT_EQ(arf_cmp(child.centre, exact.centre), 0);
      // the child's disc |w| <= 2h' = h lies in the parent's |w| <= 2h
      expect_encloses(child, G, -(level + 1), 3, rng, "child");
    }
    mag_clear(eps);
  }
}

TEST(LocalExpansion, DeflationByARootEnclosesTheQuotient) {
  std::mt19937_64 rng(777);
  for (long it = 0; it < iterations(40); ++it) {
    const Poly H = random_poly(rng);
    const int level = static_cast<int>(rng() % 8);
    const unsigned long long j = rng() % (1ULL << level);
    // a root inside the cell's disc: gamma = c + s h, s in [-2, 2]
    const Rational h = pow2(-(level + 1));
    const Rational c = Rational(Integer(static_cast<long>(2 * j + 1))) * h;
    const Rational gamma = c + Rational(std::uniform_int_distribution<long>(-64, 64)(rng), 32) * h;
    const Poly G = H * Poly(std::vector<Integer>{Integer(0) - gamma.num(), gamma.den()});
    LocalExpansion e;
    local_expansion_exact(e, G, level, j, 128);
    arb_t g;
    arb_init(g);
    arb_set_fmpq(g, gamma.get(), 200);  // a ball containing gamma
    deflate_local_expansion(e, g, 128);
    arb_clear(g);
    // G / (t - gamma) = den(gamma) H
    expect_encloses(e, H * Poly(std::vector<Integer>{gamma.den()}), -level, 1, rng, "deflated");
  }
}

TEST(LocalExpansion, RefusesCellsOutsideTheUnitIntervalAndBadArguments) {
  const Poly G(std::vector<long>{1, 2, 3});
  LocalExpansion e;
  EXPECT_THROW(local_expansion_exact(e, G, -1, 0, 64), InvalidArgument);
  EXPECT_THROW(local_expansion_exact(e, G, 3, 8, 64), InvalidArgument);
  EXPECT_THROW(local_expansion_exact(e, G, kMaxExpansionLevel + 1, 0, 64), InvalidArgument);
  local_expansion_exact(e, G, 2, 3, 64);
  LocalExpansion child;
  EXPECT_THROW(local_expansion_child(child, e, 0, 64), InvalidArgument);
  mag_t eps;
  mag_init(eps);
  EXPECT_THROW(truncate_local_expansion(e, -2, eps, 4), InvalidArgument);
  mag_clear(eps);
  // the zero polynomial expands to 0
  local_expansion_exact(e, Poly(), 1, 0, 64);
  EXPECT_EQ(arb_poly_length(e.P), 0);
}

}  // namespace
}  // namespace uniparam
