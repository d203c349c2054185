// Tests of uniparam/algebra/squarefree.hpp: random products of known,
// pairwise coprime squarefree factors with known multiplicities.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/squarefree.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }

/// Irreducible building blocks: distinct linear d t - n (gcd 1, d > 0) and
/// t^2 + c (c > 0, no real roots, irreducible) or t^2 - c (c not a square).
std::vector<Poly> building_blocks() {
  std::vector<Poly> out;
  for (long d = 1; d <= 4; ++d)
    for (long n = -5; n <= 5; ++n) {
      Integer g;
      fmpz_gcd(g.get(), Integer(d).get(), Integer(n).get());
      if (g == Integer(1)) out.push_back(Poly(std::vector<long>{-n, d}));
    }
  for (long c : {1L, 2L, 3L, 5L, 7L}) out.push_back(Poly(std::vector<long>{c, 0, 1}));
  for (long c : {2L, 3L, 5L, 6L, 7L}) out.push_back(Poly(std::vector<long>{-c, 0, 1}));
  out.push_back(Poly(std::vector<long>{-2, 0, 0, 1}));  // t^3 - 2
  out.push_back(Poly(std::vector<long>{1, 1, 1}));      // t^2 + t + 1
  return out;
}

TEST(Squarefree, RandomProductsOfKnownFactors) {
  std::mt19937_64 rng(4242);
  const std::vector<Poly> blocks = building_blocks();
  const long iters = iterations(300);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 4242)");
    // Expected: multiplicity -> product of the blocks with that multiplicity.
    std::map<int, Poly> expected;
    Integer content(static_cast<long>(std::uniform_int_distribution<long>(1, 60)(rng)) * (rng() % 2 ? 1 : -1));
    Poly p = constant(content);
    std::vector<bool> used(blocks.size(), false);
    const long nf = std::uniform_int_distribution<long>(0, 6)(rng);
    for (long i = 0; i < nf; ++i) {
      const std::size_t j = rng() % blocks.size();
      if (used[j]) continue;
      used[j] = true;
      const int m = static_cast<int>(std::uniform_int_distribution<long>(1, 5)(rng));
      // A random sign on the block (the factorisation normalises it).
      const Poly b = rng() % 2 ? blocks[j] : -blocks[j];
      if (!expected.count(m)) expected[m] = Poly(1);
      expected[m] = expected[m] * blocks[j];
      p = p * b.pow(static_cast<unsigned long>(m));
    }
    SCOPED_TRACE("p = " + p.str());
    const SquarefreeFactorization sf = squarefree_factorization(p);
    // content * prod f_i^m_i == p exactly.
    Poly back = constant(sf.content);
    for (const auto& f : sf.factors) back = back * f.factor.pow(static_cast<unsigned long>(f.multiplicity));
    EXPECT_EQ(back, p);
    // |content| is the content of p.
    Integer c;
    fmpz_poly_content(c.get(), p.get());
    Integer ac;
    fmpz_abs(ac.get(), sf.content.get());
    EXPECT_EQ(ac, c);
    // One factor per multiplicity, equal to the known product.
    ASSERT_EQ(sf.factors.size(), expected.size());
    for (std::size_t i = 0; i < sf.factors.size(); ++i) {
      const auto& f = sf.factors[i];
      ASSERT_TRUE(expected.count(f.multiplicity)) << f.multiplicity;
      EXPECT_EQ(f.factor, expected[f.multiplicity].primitive());
      EXPECT_GE(f.factor.degree(), 1);
      EXPECT_EQ(f.factor, f.factor.primitive());
      EXPECT_EQ(gcd(f.factor, f.factor.derivative()).degree(), 0) << "not squarefree";
      for (std::size_t j = i + 1; j < sf.factors.size(); ++j) {
        EXPECT_EQ(gcd(f.factor, sf.factors[j].factor).degree(), 0) << "not coprime";
        EXPECT_NE(f.multiplicity, sf.factors[j].multiplicity);
      }
      if (i + 1 < sf.factors.size()) EXPECT_LE(f.multiplicity, sf.factors[i + 1].multiplicity);
    }
    // The squarefree part is the product of all blocks.
    if (!p.is_zero()) {
      Poly all(1);
      for (const auto& e : expected) all = all * e.second;
      EXPECT_EQ(squarefree_part(p), all.primitive());
    }
  }
}

// High degree (48..200, the modular test's range): random dense p times a
// signed content, and h^2 g. provably_squarefree is never true for h^2 g
// (exactly: a square factor) and true for nearly every random p; the
// factorisation is exact either way (fails when the fast path drops the
// content's sign or its magnitude, or takes a square for squarefree).
TEST(Squarefree, HighDegreeThroughTheModularTest) {
  std::mt19937_64 rng(4848);
  long proven = 0;
  const long iters = iterations(60);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 4848)");
    auto dense = [&](long n) {
      std::vector<Integer> c;
      for (long k = 0; k <= n; ++k) c.push_back(Integer(static_cast<long>(rng() % 2001) - 1000));
      if (c.back().sign() == 0) c.back() = Integer(7);
      return Poly(c);
    };
    const Integer content(static_cast<long>(1 + rng() % 90) * (rng() % 2 ? 1 : -1));
    const bool square = it % 3 == 0;
    const Poly h = dense(1 + static_cast<long>(rng() % 20)), g = dense(48 + static_cast<long>(rng() % 150));
    const Poly p = constant(content) * (square ? h * h * g : g);
    SCOPED_TRACE("degree " + std::to_string(p.degree()) + (square ? ", h^2 g" : ""));
    const bool ps = provably_squarefree(p);
    if (square) EXPECT_FALSE(ps);
    if (ps) ++proven;
    const SquarefreeFactorization sf = squarefree_factorization(p);
    Poly back = constant(sf.content);
    for (const auto& f : sf.factors) {
      back = back * f.factor.pow(static_cast<unsigned long>(f.multiplicity));
      EXPECT_EQ(f.factor, f.factor.primitive());
      EXPECT_GT(f.factor.leading().sign(), 0);
    }
    EXPECT_EQ(back, p);
    Integer c, ac;
    fmpz_poly_content(c.get(), p.get());
    fmpz_abs(ac.get(), sf.content.get());
    EXPECT_EQ(ac, c);
    if (square) {
      bool has_square = false;
      for (const auto& f : sf.factors) has_square = has_square || f.multiplicity >= 2;
      EXPECT_TRUE(has_square);
    } else if (ps) {
      ASSERT_EQ(sf.factors.size(), 1u);
      EXPECT_EQ(sf.factors[0].multiplicity, 1);
    }
  }
  EXPECT_GT(proven, iters / 2);  // the random dense ones
}

TEST(Squarefree, Degenerate) {
  const SquarefreeFactorization z = squarefree_factorization(Poly());
  EXPECT_EQ(z.content, Integer(0));
  EXPECT_TRUE(z.factors.empty());
  const SquarefreeFactorization c = squarefree_factorization(Poly(-6));
  EXPECT_EQ(c.content, Integer(-6));
  EXPECT_TRUE(c.factors.empty());
  EXPECT_THROW(squarefree_part(Poly()), DomainError);
  EXPECT_EQ(squarefree_part(Poly(5)), Poly(1));
  // -4 (t - 1)^3 (2t + 1): negative leading coefficient goes to the content.
  const Poly p = Poly(-4) * Poly(std::vector<long>{-1, 1}).pow(3) * Poly(std::vector<long>{1, 2});
  const SquarefreeFactorization f = squarefree_factorization(p);
  ASSERT_EQ(f.factors.size(), 2u);
  EXPECT_EQ(f.content, Integer(-4));
  EXPECT_EQ(f.factors[0].factor, Poly(std::vector<long>{1, 2}));
  EXPECT_EQ(f.factors[0].multiplicity, 1);
  EXPECT_EQ(f.factors[1].factor, Poly(std::vector<long>{-1, 1}));
  EXPECT_EQ(f.factors[1].multiplicity, 3);
}

}  // namespace
}  // namespace uniparam
