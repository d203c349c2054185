// tests/support/known_roots.hpp -- an exact oracle for real-root isolation:
// polynomials built from known roots, and a check of every clause of the
// contract of isolate_real_roots against them (shared by the root tests).
#pragma once

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "uniparam/algebra/real_roots.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam::test_support {

/// A known real root: rational value q, or s * sqrt(q) with q > 0 not a
/// square of a rational (s = +-1).
struct Known {
  bool rational;
  Rational q;
  int s;
  int mult;
};

/// Exact sign of (root - x).
inline int cmp(const Known& k, const Rational& x) {
  if (k.rational) return k.q < x ? -1 : (x < k.q ? 1 : 0);
  if (k.s > 0) {
    if (x.sign() <= 0) return 1;
    const Rational x2 = x * x;
    return k.q < x2 ? -1 : 1;  // never equal: irrational
  }
  if (x.sign() >= 0) return -1;
  const Rational x2 = x * x;
  return k.q < x2 ? 1 : -1;
}
inline bool inside_closed(const Known& k, const Rational& a, const Rational& b) { return cmp(k, a) >= 0 && cmp(k, b) <= 0; }


/// Checks every clause of the contract of isolate_real_roots(p, a, b)
/// against the exact list of all real roots of p.
inline void check_isolation(const Poly& p, const Rational& a, const Rational& b, const std::vector<Known>& all,
                     const std::vector<IsolatedRoot>& got) {
  std::vector<const Known*> expected;
  for (const Known& k : all)
    if (inside_closed(k, a, b)) expected.push_back(&k);
  ASSERT_EQ(got.size(), expected.size()) << "p = " << p.str() << " on [" << a.str() << ", " << b.str() << "]";
  std::vector<int> used(all.size(), 0);
  for (std::size_t i = 0; i < got.size(); ++i) {
    const IsolatedRoot& r = got[i];
    SCOPED_TRACE("root " + std::to_string(i) + " [" + r.lo.str() + ", " + r.hi.str() + "] of " + p.str());
    ASSERT_TRUE(a <= r.lo && r.lo <= r.hi && r.hi <= b);
    if (i + 1 < got.size()) ASSERT_TRUE(r.hi < got[i + 1].lo) << "not sorted/disjoint";
    ASSERT_GE(r.factor.degree(), 1);
    EXPECT_TRUE(r.certified);  // the isolators vouch for their roots (RealAlgebraic skips its check)
    ASSERT_TRUE(r.factor.leading().sign() > 0);
    ASSERT_EQ(r.factor, r.factor.primitive());
    ASSERT_TRUE(divexact(p, r.factor).degree() >= 0);  // factor divides p (throws otherwise)
    // Which known roots lie in [lo, hi]?
    std::vector<std::size_t> in;
    for (std::size_t j = 0; j < all.size(); ++j)
      if (inside_closed(all[j], r.lo, r.hi)) in.push_back(j);
    ASSERT_EQ(in.size(), 1u) << "interval does not hold exactly one root";
    const Known& k = all[in[0]];
    ++used[in[0]];
    EXPECT_EQ(r.multiplicity, k.mult);
    if (k.rational) {
      ASSERT_TRUE(r.is_exact()) << "rational root not exact";
      EXPECT_EQ(r.lo, k.q);
      EXPECT_EQ(r.factor, Poly(std::vector<Integer>{Integer(0) - k.q.num(), k.q.den()}));  // den t - num
    } else {
      ASSERT_FALSE(r.is_exact());
      EXPECT_NE(p.sign_at(r.lo), 0);
      EXPECT_NE(p.sign_at(r.hi), 0);
      EXPECT_EQ(r.factor.sign_at(r.lo) * r.factor.sign_at(r.hi), -1);
    }
  }
  for (const Known* k : expected) EXPECT_EQ(used[static_cast<std::size_t>(k - all.data())], 1);
}

}  // namespace uniparam::test_support
