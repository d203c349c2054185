// Tests of the double-word balls (core/dd_ball.hpp): every result must
// contain the exact result at exact points of the inputs (rational
// arithmetic, or Arb at 400 bits for square roots), and results of exact
// inputs must be accurate to ~2^-95 (which fails if an error-free
// transformation is not exact, e.g. under floating-point contraction).
#include <gtest/gtest.h>

#include <arb.h>
#include <flint/fmpq.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/core/number.hpp"
#include "uniparam/core/poly.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

// The exact value hi + lo + f * rad as a rational, f in [-1, 1] (a point of x).
Rational point(const DDBall& x, double f) {
  arf_t a;
  arf_init(a);
  Rational r, t;
  arf_set_d(a, x.hi);
  arf_get_fmpq(r.get(), a);
  arf_set_d(a, x.lo);
  arf_get_fmpq(t.get(), a);
  r = r + t;
  arf_set_d(a, f * x.rad);  // f * rad is exact for f = +-1, 0 and within x otherwise
  arf_get_fmpq(t.get(), a);
  r = r + t;
  arf_clear(a);
  return r;
}

bool contains(const DDBall& x, const Rational& q) {
  arb_t b;
  arb_init(b);
  dd_get_arb(b, x);
  const bool ok = arb_contains_fmpq(b, q.get());
  arb_clear(b);
  return ok;
}

// A random normalized double word of magnitude ~2^e, e in [-40, 40], and a
// radius of 0 or ~2^(e - s), s in [20, 100].
DDBall random_ball(std::mt19937_64& rng, bool exact) {
  std::uniform_real_distribution<double> mant(0.5, 1.0);
  std::uniform_int_distribution<int> ex(-40, 40), sgn(0, 1), gap(20, 100);
  const int e = ex(rng);
  double hi = std::ldexp(mant(rng), e);
  if (sgn(rng)) hi = -hi;
  double lo = std::ldexp(mant(rng), e - 54) * (sgn(rng) ? 1 : -1);  // |lo| < ulp(hi) / 2
  DDBall x{hi + lo, 0, 0};
  x.lo = lo - (x.hi - hi);  // normalized, same exact sum
  x.rad = exact ? 0 : std::ldexp(mant(rng), e - gap(rng));
  return x;
}

const double kFractions[] = {-1, -0.5, 0, 0.25, 1};

TEST(DDBall, ArithmeticContainsEveryExactResult) {
  std::mt19937_64 rng(11);
  for (long it = 0; it < iterations(400); ++it) {
    const bool exact = it % 3 == 0;
    const DDBall a = random_ball(rng, exact), b = random_ball(rng, exact);
    const DDBall s = dd_add(a, b), d = dd_sub(a, b), p = dd_mul(a, b);
    // scaling by 2^e, within and beyond the exponents of the fast path
    const int e = std::uniform_int_distribution<int>(-80, 80)(rng);
    const DDBall sc = dd_mul_2exp(a, e);
    Rational two_e(1);
    for (int i = 0; i < std::abs(e); ++i) two_e = e > 0 ? two_e * Rational(2) : two_e / Rational(2);
    DDBall q;
    const bool divided = dd_div(q, a, b);
    ASSERT_TRUE(dd_is_finite(s) && dd_is_finite(d) && dd_is_finite(p));
    ASSERT_TRUE(divided);  // |b| >> rad(b) for these balls
    for (double fa : kFractions)
      for (double fb : kFractions) {
        const Rational x = point(a, fa), y = point(b, fb);
        ASSERT_TRUE(contains(s, x + y)) << it;
        ASSERT_TRUE(contains(sc, x * two_e)) << it << ", 2^" << e;
        ASSERT_TRUE(contains(d, x - y)) << it;
        ASSERT_TRUE(contains(p, x * y)) << it;
        ASSERT_TRUE(contains(q, x / y)) << it;
      }
    if (exact) {  // only rounding: ~2^-99 of the result
      EXPECT_LE(dd_rel_rad(p), std::ldexp(1.0, -95)) << it;
      EXPECT_LE(dd_rel_rad(q), std::ldexp(1.0, -95)) << it;
    }
  }
}

TEST(DDBall, SquareRootContainsEveryPointsRoot) {
  std::mt19937_64 rng(12);
  arb_t exact, ours;
  arb_init(exact);
  arb_init(ours);
  for (long it = 0; it < iterations(400); ++it) {
    DDBall a = random_ball(rng, it % 3 == 0);
    if (a.hi < 0) a = dd_neg(a);
    DDBall r;
    ASSERT_TRUE(dd_sqrt(r, a));
    dd_get_arb(ours, r);
    for (double f : kFractions) {
      const Rational x = point(a, f);
      arb_set_fmpq(exact, x.get(), 400);
      arb_sqrt(exact, exact, 400);
      ASSERT_TRUE(arb_contains(ours, exact)) << it;
    }
    if (a.rad == 0) EXPECT_LE(dd_rel_rad(r), std::ldexp(1.0, -95)) << it;
  }
  arb_clear(exact);
  arb_clear(ours);
}

TEST(DDBall, DivisionAndSquareRootRefuseBallsReachingZero) {
  DDBall r;
  EXPECT_FALSE(dd_div(r, dd_from_double(1), DDBall{1e-3, 0, 2e-3}));
  EXPECT_FALSE(dd_is_finite(r));
  EXPECT_FALSE(dd_div(r, dd_from_double(1), dd_from_double(0)));
  EXPECT_FALSE(dd_sqrt(r, DDBall{1e-3, 0, 2e-3}));
  EXPECT_FALSE(dd_sqrt(r, dd_from_double(-4)));
  EXPECT_TRUE(dd_sqrt(r, dd_from_double(4)));
  EXPECT_TRUE(contains(r, Rational(2)));
  // out may alias an input
  DDBall x = dd_from_double(3), y = dd_from_double(4);
  ASSERT_TRUE(dd_div(x, x, y));
  EXPECT_TRUE(contains(x, Rational(3, 4)));
  ASSERT_TRUE(dd_div(y, x, y));
  EXPECT_TRUE(contains(y, Rational(3, 16)));
  ASSERT_TRUE(dd_sqrt(y, y));
  EXPECT_TRUE(dd_is_finite(y));
}

TEST(DDBall, ConversionFromArbContainsTheBall) {
  std::mt19937_64 rng(13);
  std::uniform_int_distribution<long> bits(1, 300), ex(-200, 200);
  flint_rand_t st;
  flint_randinit(st);
  arb_t x, back;
  arb_init(x);
  arb_init(back);
  for (long it = 0; it < iterations(400); ++it) {
    // a midpoint of up to 300 bits (more than a double word holds)
    arb_randtest(x, st, bits(rng), 8);
    arb_mul_2exp_si(x, x, ex(rng));
    DDBall d;
    if (!dd_set_arb(d, x)) continue;
    dd_get_arb(back, d);
    ASSERT_TRUE(arb_contains(back, x)) << it;
  }
  arb_set_d(x, 1e300);
  arb_mul(x, x, x, 64);  // 1e600 > 2^900
  DDBall d;
  EXPECT_FALSE(dd_set_arb(d, x));
  arb_indeterminate(x);
  EXPECT_FALSE(dd_set_arb(d, x));
  arb_clear(x);
  arb_clear(back);
  flint_randclear(st);
}

TEST(DDPoly, HornerContainsTheExactValueAndDerivatives) {
  std::mt19937_64 rng(14);
  std::uniform_int_distribution<long> deg(0, 40), bits(1, 100), sgn(0, 1);
  std::uniform_int_distribution<unsigned long> word;
  std::uniform_real_distribution<double> pos(-1.25, 1.25);
  std::uniform_int_distribution<int> gap(60, 100);
  for (long it = 0; it < iterations(200); ++it) {
    const long n = deg(rng);
    std::vector<Integer> c;
    const long b = bits(rng);
    for (long k = 0; k <= n; ++k) {
      Integer v;
      fmpz_set_ui(v.get(), word(rng));
      if (b < 64) fmpz_fdiv_q_2exp(v.get(), v.get(), static_cast<ulong>(64 - b));
      else fmpz_mul_2exp(v.get(), v.get(), static_cast<ulong>(b - 64));  // low bits zero: a double word
      if (sgn(rng)) fmpz_neg(v.get(), v.get());
      c.push_back(v);
    }
    const Poly p(c), p1 = p.derivative(), p2 = p1.derivative();
    const DDPoly dp(p);
    ASSERT_TRUE(dp.usable()) << it;
    DDBall x = dd_from_double(pos(rng));
    x = dd_add(x, DDBall{0, 0, 0});  // a tiny radius from the rounding allowance
    if (it % 2) x.rad = std::ldexp(1.0, -gap(rng));
    DDBall v, d1, d2;
    ASSERT_TRUE(dp.eval(&v, &d1, &d2, x)) << it;
    for (double f : kFractions) {
      const Rational t = point(x, f);
      ASSERT_TRUE(contains(v, p(t))) << it;
      ASSERT_TRUE(contains(d1, p1(t))) << it;
      ASSERT_TRUE(contains(d2, p2(t))) << it;
    }
  }
}

// Lanes of one interleaved Horner loop: every lane's ball is bit for bit
// eval's, for polynomials of different degrees (the zero polynomial and
// constants too), derivatives 0-2, double and double-word coefficients, on
// both product paths.
TEST(DDPoly, InterleavedLanesGiveEvalsBallsBitForBit) {
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<long> deg(-1, 30), sgn(0, 1), lanes(1, DDPoly::kMaxLanes);
  std::uniform_int_distribution<int> der(0, 2);
  std::uniform_int_distribution<unsigned long> word;
  std::uniform_real_distribution<double> pos(-1.25, 1.25);
  auto same = [](const DDBall& a, const DDBall& b) {
    return std::memcmp(&a.hi, &b.hi, sizeof(double)) == 0 && std::memcmp(&a.lo, &b.lo, sizeof(double)) == 0 &&
           std::memcmp(&a.rad, &b.rad, sizeof(double)) == 0;
  };
  long fast = 0;
  for (bool fma : {false, true}) {
    dd_set_fma(fma);
    for (long it = 0; it < iterations(150); ++it) {
      const int k = static_cast<int>(lanes(rng));
      const bool dword = it % 5 == 0;  // one lane with double-word coefficients: lane by lane
      std::vector<DDPoly> polys;
      for (int q = 0; q < k; ++q) {
        const long n = deg(rng);
        std::vector<Integer> c;
        for (long i = 0; i <= n; ++i) {
          Integer v;
          fmpz_set_ui(v.get(), word(rng) >> (dword && q == 0 ? 0 : 12));  // 64 bits: a double word
          if (sgn(rng)) fmpz_neg(v.get(), v.get());
          c.push_back(v);
        }
        polys.emplace_back(n < 0 ? Poly(0) : Poly(c));
        ASSERT_TRUE(polys.back().usable());
      }
      std::vector<const DDPoly*> p;
      std::vector<int> j;
      std::vector<DDBall> got(static_cast<std::size_t>(k));
      std::vector<DDBall*> out;
      for (int q = 0; q < k; ++q) {
        p.push_back(&polys[static_cast<std::size_t>(q)]);
        j.push_back(der(rng));
        out.push_back(&got[static_cast<std::size_t>(q)]);
      }
      DDBall x = dd_from_double(pos(rng));
      if (it % 2) x.rad = std::ldexp(1.0, -70);
      const bool ok = DDPoly::eval_many(k, p.data(), j.data(), out.data(), x);
      bool ok_each = true;
      for (int q = 0; q < k; ++q) {
        DDBall o[3];
        DDBall* want[3] = {nullptr, nullptr, nullptr};
        want[j[static_cast<std::size_t>(q)]] = &o[j[static_cast<std::size_t>(q)]];
        ok_each = polys[static_cast<std::size_t>(q)].eval(want[0], want[1], want[2], x) && ok_each;
        if (ok) ASSERT_TRUE(same(got[static_cast<std::size_t>(q)], o[j[static_cast<std::size_t>(q)]])) << it << " lane " << q;
      }
      ASSERT_EQ(ok, ok_each) << it;
      fast += ok && !dword;
    }
  }
  dd_set_fma(true);
  EXPECT_GT(fast, iterations(150));  // the interleaved loop ran
  DDBall o;
  const DDPoly one(Poly(1));
  const DDPoly* p1[1] = {&one};
  const int j0[1] = {0};
  DDBall* o1[1] = {&o};
  EXPECT_FALSE(DDPoly::eval_many(0, p1, j0, o1, dd_from_double(0.5)));  // no lanes
}

TEST(DDPoly, CoefficientsThatAreNotDoubleWordsAreRefused) {
  Integer big;
  fmpz_one(big.get());
  fmpz_mul_2exp(big.get(), big.get(), 150);
  Integer mid;
  fmpz_one(mid.get());
  fmpz_mul_2exp(mid.get(), mid.get(), 60);
  Integer c;
  fmpz_add(c.get(), big.get(), mid.get());
  fmpz_add_ui(c.get(), c.get(), 1);  // 2^150 + 2^60 + 1: three doubles
  EXPECT_FALSE(DDPoly(Poly(std::vector<Integer>{Integer(1), c})).usable());
  EXPECT_TRUE(DDPoly(Poly(std::vector<Integer>{Integer(1), big})).usable());
  EXPECT_TRUE(DDPoly(Poly(0)).usable());
}

TEST(DDBall, FusedAndPortableProductsGiveTheSameBits) {
  // Where the processor has a fused multiply-add, the double-word products
  // use it (TwoProd's error term by fma); elsewhere Dekker's splitting.
  // Both TwoProds are exact, so every operation must give the same bits on
  // both paths: the tests above, run on one path, then hold for the other.
  if (!dd_fma_available()) GTEST_SKIP() << "no fused multiply-add on this processor: one path only";
  std::mt19937_64 rng(20261125u);
  std::uniform_int_distribution<long> coef(-999999, 999999), deg(0, 12);
  auto same = [](const DDBall& x, const DDBall& y) {
    return std::memcmp(&x.hi, &y.hi, sizeof(double)) == 0 && std::memcmp(&x.lo, &y.lo, sizeof(double)) == 0 &&
           std::memcmp(&x.rad, &y.rad, sizeof(double)) == 0;
  };
  const long n = iterations(2000);
  for (long it = 0; it < n; ++it) {
    const DDBall a = random_ball(rng, it % 3 == 0), b = random_ball(rng, it % 5 == 0);
    std::vector<long> c(static_cast<std::size_t>(deg(rng)) + 1);
    for (long& x : c) x = coef(rng);
    const DDPoly p{Poly(c)};
    DDBall r[2][7];
    bool ok[2][3];
    for (int path = 0; path < 2; ++path) {
      ASSERT_EQ(dd_set_fma(path == 1), path == 1);
      r[path][0] = dd_mul(a, b);
      r[path][1] = dd_add(a, b);
      ok[path][0] = dd_div(r[path][2], a, b);
      ok[path][1] = dd_sqrt(r[path][3], dd_mul(a, a));
      ok[path][2] = p.eval(&r[path][4], &r[path][5], &r[path][6], a);
    }
    SCOPED_TRACE("iteration " + std::to_string(it));
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ok[0][k], ok[1][k]) << k;
    for (int k = 0; k < 7; ++k)
      if (k < 2 || (k == 2 && ok[0][0]) || (k == 3 && ok[0][1]) || (k >= 4 && ok[0][2]))
        EXPECT_TRUE(same(r[0][k], r[1][k])) << k << ": " << r[0][k].hi << " " << r[0][k].lo << " " << r[0][k].rad
                                            << " vs " << r[1][k].hi << " " << r[1][k].lo << " " << r[1][k].rad;
  }
  dd_set_fma(true);
}

}  // namespace
}  // namespace uniparam
