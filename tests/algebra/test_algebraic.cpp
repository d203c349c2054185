// Tests of uniparam/algebra/algebraic.hpp against exact oracles (quadratic
// irrationals s*sqrt(r), compared by squaring) and independent Arb values.
#include <arb.h>
#include <arf.h>
#include <gtest/gtest.h>
#include <mag.h>

#include <flint/flint.h>

#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/algebraic.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }
Integer pow_int(long base, unsigned long e) {
  Integer r;
  fmpz_set_si(r.get(), base);
  fmpz_pow_ui(r.get(), r.get(), e);
  return r;
}
Rational pow10(long e) {
  const Rational p(pow_int(10, static_cast<unsigned long>(e < 0 ? -e : e)));
  return e >= 0 ? p : Rational(1) / p;
}

/// Exact oracle: a rational q, or s * sqrt(r) with r > 0 not a rational square.
struct Quad {
  bool rational;
  Rational q;  // the value, or r
  int s;

  /// Sign of (this - x), exact.
  int cmp(const Rational& x) const {
    if (rational) return q < x ? -1 : (x < q ? 1 : 0);
    const Rational x2 = x * x;
    if (s > 0) return x.sign() <= 0 ? 1 : (q < x2 ? -1 : 1);
    return x.sign() >= 0 ? -1 : (q < x2 ? 1 : -1);
  }
  /// Sign of (this - o), exact.
  int cmp(const Quad& o) const {
    if (o.rational) return cmp(o.q);
    if (rational) return -o.cmp(q);
    if (s != o.s) return s;
    if (q == o.q) return 0;
    return (q < o.q ? -1 : 1) * s;
  }
  std::string str() const { return rational ? q.str() : (s < 0 ? "-sqrt(" : "sqrt(") + q.str() + ")"; }
};

bool is_rational_square(const Rational& q) {
  return fmpz_is_square(fmpq_numref(q.get())) && fmpz_is_square(fmpq_denref(q.get()));
}

/// d t^2 - c for r = c/d.
Poly quad_poly(const Rational& r) { return Poly(std::vector<Integer>{Integer(0) - r.num(), Integer(0), r.den()}); }

/// s*sqrt(r) as a RealAlgebraic, isolated by `extra * (d t^2 - c)` in an
/// interval (0, r + 1) or (-(r + 1), 0); `extra` must have no root there.
RealAlgebraic make(const Quad& x, const Poly& extra = Poly(1)) {
  if (x.rational) return RealAlgebraic(x.q);
  const Rational top = x.q + Rational(1);
  return x.s > 0 ? RealAlgebraic(quad_poly(x.q) * extra, Rational(0), top)
                 : RealAlgebraic(quad_poly(x.q) * extra, -top, Rational(0));
}

/// Exact bounds of a finite ball.
std::pair<Rational, Rational> bounds(const Ball& b) {
  Rational mid, rad;
  arf_get_fmpq(mid.get(), arb_midref(b.get()));
  arf_t r;
  arf_init(r);
  arf_set_mag(r, arb_radref(b.get()));
  arf_get_fmpq(rad.get(), r);
  arf_clear(r);
  return {mid - rad, mid + rad};
}

/// rad(b) <= 2^-prec * |x| (relative at every size), checked with the
/// exact oracle |x| >= m.
void expect_radius_contract(const Ball& b, long prec, const Quad& x) {
  ASSERT_TRUE(b.is_finite());
  const auto [lo, hi] = bounds(b);
  EXPECT_GE(x.cmp(lo), 0) << x.str() << " not in " << b.str();
  EXPECT_LE(x.cmp(hi), 0) << x.str() << " not in " << b.str();
  // |x| > min(|lo|, |hi|) when the ball excludes 0 (x = 0: an exact ball)
  Rational m(0);
  if (lo.sign() > 0) m = lo;
  if (hi.sign() < 0) m = -hi;
  const Rational rad = (hi - lo) * Rational(1, 2);
  EXPECT_TRUE(rad <= pow2(-prec) * m) << "radius " << b.str() << " too large for prec " << prec;
}

Quad random_quad(std::mt19937_64& rng, bool allow_rational = true) {
  std::uniform_int_distribution<long> num(1, 60), den(1, 9);
  if (allow_rational && rng() % 4 == 0)
    return {true, Rational(std::uniform_int_distribution<long>(-40, 40)(rng), den(rng)), 0};
  for (;;) {
    const Rational r(num(rng), den(rng));
    if (!is_rational_square(r)) return {false, r, rng() % 2 ? 1 : -1};
  }
}

TEST(Algebraic, RefineSqrt2To1000Bits) {
  const RealAlgebraic x(Poly(std::vector<long>{-2, 0, 1}), Rational(1), Rational(2));
  EXPECT_FALSE(x.is_rational());
  x.refine(1000);
  EXPECT_TRUE(x.hi() - x.lo() <= pow2(-1000));
  EXPECT_TRUE(x.lo() * x.lo() < Rational(2) && Rational(2) < x.hi() * x.hi());
  // Against Arb's sqrt at 1100 bits.
  Ball ref;
  arb_sqrt_ui(ref.get(), 2, 1100);
  const Ball b = x.to_ball(1000);
  EXPECT_TRUE(arb_overlaps(b.get(), ref.get()));
  expect_radius_contract(b, 1000, {false, Rational(2), 1});
  // Refinement only shrinks.
  const Rational lo = x.lo(), hi = x.hi();
  x.refine(10);
  EXPECT_EQ(x.lo(), lo);
  EXPECT_EQ(x.hi(), hi);
}

TEST(Algebraic, RefineInverseFourthRootOf27) {
  // 27^(-1/4): the root of 27 t^4 - 1 in (0, 1).
  const Poly p(std::vector<long>{-1, 0, 0, 0, 27});
  const RealAlgebraic x(p, Rational(0), Rational(1));
  x.refine(1000);
  EXPECT_TRUE(x.hi() - x.lo() <= pow2(-1000));
  const Rational l4 = x.lo() * x.lo() * x.lo() * x.lo(), h4 = x.hi() * x.hi() * x.hi() * x.hi();
  EXPECT_TRUE(l4 * Rational(27) < Rational(1) && Rational(1) < h4 * Rational(27));
  Ball ref;
  arb_set_ui(ref.get(), 27);
  arb_root_ui(ref.get(), ref.get(), 4, 1200);
  arb_inv(ref.get(), ref.get(), 1200);
  for (long prec : {10L, 100L, 1000L, 1500L}) {
    const Ball b = x.to_ball(prec);
    EXPECT_TRUE(arb_overlaps(b.get(), ref.get())) << prec;
    mag_t bound;
    mag_init(bound);
    mag_one(bound);
    mag_mul_2exp_si(bound, bound, -prec);
    EXPECT_LE(mag_cmp(arb_radref(b.get()), bound), 0) << prec;
    mag_clear(bound);
  }
  EXPECT_EQ(x.str().rfind("root of 27*t^4 - 1 in [", 0), 0u) << x.str();
}

TEST(Algebraic, ToBallRadiusContract) {
  std::mt19937_64 rng(99);
  const long iters = iterations(60);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 99)");
    Quad x = random_quad(rng);
    // Scale by 10^(+-30) sometimes: huge and tiny magnitudes.
    const int scale = static_cast<int>(rng() % 3) - 1;
    if (scale != 0) {
      const Rational f = scale > 0 ? Rational(pow_int(10, 60)) : Rational(Integer(1), pow_int(10, 60));
      x.q = x.rational ? x.q * (scale > 0 ? Rational(pow_int(10, 30)) : Rational(Integer(1), pow_int(10, 30)))
                       : x.q * f;
    }
    const RealAlgebraic a = make(x);
    for (long prec : {1L, 2L, 53L, 200L, 1000L}) expect_radius_contract(a.to_ball(prec), prec, x);
  }
}

TEST(Algebraic, CompareAgainstExactOracle) {
  std::mt19937_64 rng(2024);
  const long iters = iterations(40);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 2024)");
    std::vector<Quad> q;
    for (int i = 0; i < 6; ++i) q.push_back(random_quad(rng));
    q.push_back(q[0]);  // an equal pair
    if (!q[1].rational) q.push_back({true, q[1].q, 0});  // r next to sqrt(r)
    std::vector<RealAlgebraic> a;
    for (std::size_t i = 0; i < q.size(); ++i) {
      // The repeated value gets a different polynomial: equality by gcd.
      const Poly extra = (i + 1 == 7) ? Poly(std::vector<long>{1, 0, 1}) : Poly(1);
      a.push_back(make(q[i], extra));
    }
    for (std::size_t i = 0; i < q.size(); ++i) {
      EXPECT_EQ(a[i].sign(), q[i].cmp(Rational(0))) << q[i].str();
      for (std::size_t j = 0; j < q.size(); ++j) {
        const int expect = q[i].cmp(q[j]);
        EXPECT_EQ(compare(a[i], a[j]), expect) << q[i].str() << " vs " << q[j].str();
        EXPECT_EQ(a[i] == a[j], expect == 0);
        EXPECT_EQ(a[i] < a[j], expect < 0);
      }
    }
  }
}

TEST(Algebraic, EqualityAcrossPolynomials) {
  const Poly t2m2(std::vector<long>{-2, 0, 1});
  const RealAlgebraic a(t2m2, Rational(1), Rational(2));
  const RealAlgebraic b(t2m2 * Poly(std::vector<long>{-3, 1}), Rational(1), Rational(2));         // (t^2-2)(t-3)
  const RealAlgebraic c(t2m2 * Poly(std::vector<long>{-3, 0, 1}), Rational(7, 5), Rational(3, 2));  // (t^2-2)(t^2-3)
  const RealAlgebraic d(Poly(std::vector<long>{-3, 0, 1}), Rational(1), Rational(2));              // sqrt3
  EXPECT_EQ(compare(a, b), 0);
  EXPECT_EQ(compare(b, c), 0);
  EXPECT_TRUE(a == c);
  EXPECT_EQ(compare(a, d), -1);
  EXPECT_EQ(compare(d, c), 1);
  // sqrt2 vs sqrt2 + 10^-30: the root of (10^30 t - 1)^2 - 2 10^60.
  const Integer e30 = pow_int(10, 30);
  const Poly f2 = (Poly::t() * constant(e30) - Poly(1)).pow(2) - constant(pow_int(10, 60) * Integer(2));
  const RealAlgebraic e(f2, Rational(1), Rational(2));
  EXPECT_EQ(compare(a, e), -1);
  EXPECT_EQ(compare(e, a), 1);
  // Against rationals close by.
  EXPECT_EQ(compare(a, RealAlgebraic(Rational(99, 70))), -1);  // 99^2 = 2 * 70^2 + 1
  EXPECT_EQ(compare(a, RealAlgebraic(Rational(140, 99))), 1);  // 140^2 = 2 * 99^2 - 2
  EXPECT_EQ(compare(a, RealAlgebraic(Rational(141421357, 100000000))), -1);
  EXPECT_EQ(compare(RealAlgebraic(Rational(1, 3)), RealAlgebraic(Rational(1, 3))), 0);
  EXPECT_EQ(compare(RealAlgebraic(2), a), 1);
}

TEST(Algebraic, Constructors) {
  const Poly t2m2(std::vector<long>{-2, 0, 1});
  // Rational roots come back exact, with a degree-1 polynomial.
  const RealAlgebraic h(Poly(std::vector<long>{-1, 2}) * t2m2, Rational(0), Rational(1));
  ASSERT_TRUE(h.is_rational());
  EXPECT_EQ(h.rational(), Rational(1, 2));
  EXPECT_EQ(h.poly(), Poly(std::vector<long>{-1, 2}));
  EXPECT_EQ(h.str(), "1/2");
  const RealAlgebraic r(Rational(-7, 3));
  EXPECT_TRUE(r.is_rational());
  EXPECT_EQ(r.poly(), Poly(std::vector<long>{7, 3}));
  EXPECT_EQ(r.sign(), -1);
  EXPECT_EQ(RealAlgebraic(0L).sign(), 0);
  // Violated preconditions.
  EXPECT_THROW(RealAlgebraic(t2m2.pow(2), Rational(1), Rational(2)), InvalidArgument);   // not squarefree
  EXPECT_THROW(RealAlgebraic(t2m2, Rational(-2), Rational(2)), InvalidArgument);         // two roots
  EXPECT_THROW(RealAlgebraic(t2m2, Rational(2), Rational(3)), InvalidArgument);          // no root
  EXPECT_THROW(RealAlgebraic(t2m2, Rational(2), Rational(1)), InvalidArgument);          // empty
  EXPECT_THROW(RealAlgebraic(t2m2 * Poly(std::vector<long>{-1, 1}), Rational(1), Rational(2)),
               InvalidArgument);  // end is a root
  EXPECT_THROW(RealAlgebraic(Poly(3), Rational(1), Rational(2)), InvalidArgument);
  const RealAlgebraic s(t2m2, Rational(1), Rational(2));
  EXPECT_THROW(s.rational(), InvalidArgument);
  // From the isolator; and a forged IsolatedRoot is refused.
  const auto roots = isolate_real_roots(t2m2 * Poly(std::vector<long>{-1, 3}), Rational(-2), Rational(2));
  ASSERT_EQ(roots.size(), 3u);
  EXPECT_EQ(compare(RealAlgebraic(roots[0]), make({false, Rational(2), -1})), 0);
  EXPECT_EQ(compare(RealAlgebraic(roots[1]), RealAlgebraic(Rational(1, 3))), 0);
  EXPECT_EQ(compare(RealAlgebraic(roots[2]), s), 0);
  IsolatedRoot bad{Rational(2), Rational(3), t2m2, 1};
  EXPECT_THROW(RealAlgebraic{bad}, InvalidArgument);
}

TEST(Algebraic, SignIsExactAndShrinksAroundZero) {
  const Poly t2m2(std::vector<long>{-2, 0, 1});
  const RealAlgebraic m(t2m2, Rational(-2), Rational(1));  // -sqrt2
  EXPECT_EQ(m.sign(), -1);
  EXPECT_TRUE(m.lo() < m.hi() && m.hi() <= Rational(1));
  EXPECT_EQ(compare(m, make({false, Rational(2), -1})), 0);
  const RealAlgebraic p(Poly(std::vector<long>{-1, 0, 0, 0, 27}), Rational(-1, 10), Rational(1));
  EXPECT_EQ(p.sign(), 1);
}

/// p(s sqrt r) = A + C sqrt r exactly; its sign.
int oracle_sign_at(const Poly& p, const Quad& x) {
  if (x.rational) return p.sign_at(x.q);
  Rational A, B, rp(1);
  for (long i = 0; i <= p.degree(); i += 2, rp = rp * x.q) A = A + Rational(p.coeff(i)) * rp;
  rp = Rational(1);
  for (long i = 1; i <= p.degree(); i += 2, rp = rp * x.q) B = B + Rational(p.coeff(i)) * rp;
  const Rational C = x.s > 0 ? B : -B;
  if (C.sign() == 0) return A.sign();
  if (A.sign() == 0 || A.sign() == C.sign()) return C.sign();
  const Rational d = A * A - C * C * x.q;  // never 0: sqrt r is irrational
  return A.sign() > 0 ? d.sign() : -d.sign();
}

TEST(Algebraic, SignAtAgainstExactOracle) {
  std::mt19937_64 rng(31337);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 31337)");
    const Quad x = random_quad(rng);
    const long n = std::uniform_int_distribution<long>(0, 8)(rng);
    std::vector<long> c(static_cast<std::size_t>(n + 1));
    for (long& v : c) v = std::uniform_int_distribution<long>(-30, 30)(rng);
    Poly p(c);
    if (rng() % 3 == 0) p = p * (x.rational ? Poly(std::vector<Integer>{Integer(0) - x.q.num(), x.q.den()})
                                            : quad_poly(x.q));  // a root
    const RealAlgebraic a = make(x);
    EXPECT_EQ(sign_at(p, a), oracle_sign_at(p, x)) << p.str() << " at " << x.str();
  }
  // A polynomial vanishing very close to (but not at) sqrt2.
  const Integer e30 = pow_int(10, 30);
  const Poly f2 = (Poly::t() * constant(e30) - Poly(1)).pow(2) - constant(pow_int(10, 60) * Integer(2));
  const RealAlgebraic s2(Poly(std::vector<long>{-2, 0, 1}), Rational(1), Rational(2));
  EXPECT_EQ(sign_at(f2, s2), -1);  // f2 < 0 between its roots 1e-30 - sqrt2 and sqrt2 + 1e-30
  EXPECT_EQ(sign_at(f2 * Poly(std::vector<long>{-2, 0, 1}), s2), 0);
}

TEST(Algebraic, DecimalWithinOneUnit) {
  std::mt19937_64 rng(7);
  const long iters = iterations(30);
  for (long it = 0; it < iters; ++it) {
    Quad x = random_quad(rng);
    if (it % 5 == 1 && !x.rational) x.q = x.q * Rational(Integer(1), pow_int(10, 60));  // ~1e-30
    const RealAlgebraic a = make(x);
    for (long digits : {1L, 5L, 15L, 40L}) {
      const std::string s = a.decimal(digits);
      SCOPED_TRACE(x.str() + " -> " + s);
      const Rational d = Rational::parse(s);
      // One unit of the last of `digits` significant digits of d.
      Rational unit(1);
      if (!d.is_zero()) {
        const Rational ad = d.sign() < 0 ? -d : d;
        long e = 0;  // 10^e <= |d| < 10^(e+1)
        while (pow10(e) > ad) --e;
        while (pow10(e + 1) <= ad) ++e;
        unit = pow10(e - digits + 1);
      }
      EXPECT_GE(x.cmp(d - unit), 0);
      EXPECT_LE(x.cmp(d + unit), 0);
    }
  }
  EXPECT_THROW(RealAlgebraic(1).decimal(0), InvalidArgument);
}


// Copies share their refinement: what one copy refined, another adopts at
// its next refine (even one asking for fewer bits), and every interval stays
// isolating. Oracle: sqrt(r) for random non-square r, by exact squares.
TEST(Algebraic, CopiesShareRefinement) {
  std::mt19937_64 rng(4242);
  std::uniform_int_distribution<long> pick(2, 10000);
  for (int it = 0; it < iterations(20); ++it) {
    long r = pick(rng);
    long k = 1;
    while ((k + 1) * (k + 1) <= r) ++k;
    if (k * k == r) ++r;  // not a square (k^2 < r < (k+1)^2 still)
    const RealAlgebraic x(Poly(std::vector<long>{-r, 0, 1}), Rational(k), Rational(k + 1));
    const RealAlgebraic y = x;  // NOLINT(performance-unnecessary-copy-initialization): the copy is the point
    const long bits = 100 + 50 * (it % 5);
    y.refine(bits);
    x.refine(4);  // adopts y's interval
    SCOPED_TRACE("sqrt(" + std::to_string(r) + ")");
    EXPECT_TRUE(x.hi() - x.lo() <= pow2(-bits));
    EXPECT_EQ(x.lo(), y.lo());
    EXPECT_EQ(x.hi(), y.hi());
    EXPECT_TRUE(x.lo() * x.lo() < Rational(r) && Rational(r) < x.hi() * x.hi());
    // an independent number (not a copy) does not see it
    const RealAlgebraic z(Poly(std::vector<long>{-r, 0, 1}), Rational(k), Rational(k + 1));
    z.refine(4);
    EXPECT_TRUE(z.hi() - z.lo() > pow2(-bits));
  }
}

// to_ball(prec) is the grid cell [k, k + 1] 2^-(prec+1+e) holding x, e =
// max(0, -floor(log2 x)), whatever
// was refined before (not at all, or to more bits than to_ball refines to
// itself), also where the isolating interval holds a grid point so that the
// exact comparison decides: x = c + s 2^(1/3) 2^-200, the one real root of
// (t - c)^3 - 2 s 2^-600, c a dyadic of 20 bits, s = +-1, given by an
// interval of width 2^-(prec+19) around c. Fails when the comparison takes
// the wrong cell or the refinement's depth changes the ball.
TEST(Algebraic, ToBallIsTheGridCellWhateverWasRefinedBefore) {
  std::mt19937_64 rng(2402);
  for (long it = 0; it < iterations(40); ++it) {
    const Rational c(static_cast<long>(1 + rng() % ((1L << 20) - 1)), 1L << 20);
    const int side = rng() % 2 ? 1 : -1;
    const long prec = 20 + static_cast<long>(rng() % 150);
    // 2^599 ((t - c)^3 - 2 s 2^-600) with c = N / D, times D^3
    const Integer N = c.num(), D = c.den();
    std::vector<Integer> a{Integer(0) - N * N * N, Integer(3) * N * N * D, Integer(-3) * N * D * D, D * D * D};
    for (Integer& v : a) fmpz_mul_2exp(v.get(), v.get(), 599);
    a[0] = a[0] - Integer(side) * D * D * D;
    IsolatedRoot r;  // as given (the constructor from (f, lo, hi) would isolate anew)
    r.factor = Poly(a).primitive();
    r.lo = c - pow2(-(prec + 20));
    r.hi = c + pow2(-(prec + 20));
    const RealAlgebraic fresh(r), deep(r);  // (ends checked exactly)
    ASSERT_TRUE(fresh.lo() < c && c < fresh.hi());
    deep.refine(prec + 60 + static_cast<long>(rng() % 200));
    const Ball b0 = fresh.to_ball(prec), b1 = deep.to_ball(prec);
    SCOPED_TRACE("iteration " + std::to_string(it) + ", c = " + c.str() + ", side " + std::to_string(side) +
                 ", prec " + std::to_string(prec));
    // the cell [c, c + 2^-p] (side +1) or [c - 2^-p, c] (side -1), p =
    // prec + 1 + e; x lies within 2^-199 of c on that side, where no power
    // of 2 but c itself lies: floor(log2 x) is that of c or of c - 2^-199
    const Rational below = side > 0 ? c : c - pow2(-199);
    long e = 0;  // -floor(log2 below), below in (0, 1)
    while (pow2(-e) > below) ++e;
    const long p = prec + 1 + e;
    Ball cell(c + pow2(-(p + 1)) * Rational(side), p + 64);
    mag_set_ui_2exp_si(arb_radref(cell.get()), 1, -(p + 1));
    EXPECT_TRUE(arb_equal(b0.get(), cell.get())) << b0.str(30) << " vs " << cell.str(30);
    EXPECT_TRUE(arb_equal(b1.get(), cell.get())) << b1.str(30) << " vs " << cell.str(30);
  }
}

// Copies refined from several threads at once: every interval isolates the
// root, and to_ball gives the same canonical ball on every copy.
TEST(Algebraic, CopiesRefinedFromThreadsStayIsolating) {
  const long r = 1234567;  // not a square: 1111^2 < r < 1112^2
  const RealAlgebraic x(Poly(std::vector<long>{-r, 0, 1}), Rational(1111), Rational(1112));
  constexpr int kThreads = 4;
  std::vector<RealAlgebraic> copies(kThreads, x);
  std::vector<Ball> balls(kThreads);
  std::vector<std::thread> pool;
  for (int t = 0; t < kThreads; ++t)
    pool.emplace_back([&, t] {
      for (long b = 8; b <= 600; b += 37 + 11 * t) copies[static_cast<std::size_t>(t)].refine(b);
      balls[static_cast<std::size_t>(t)] = copies[static_cast<std::size_t>(t)].to_ball(500);
      flint_cleanup();
    });
  for (auto& th : pool) th.join();
  for (int t = 0; t < kThreads; ++t) {
    const RealAlgebraic& c = copies[static_cast<std::size_t>(t)];
    EXPECT_TRUE(c.lo() * c.lo() < Rational(r) && Rational(r) < c.hi() * c.hi()) << "copy " << t;
    EXPECT_TRUE(c.hi() - c.lo() <= pow2(-500)) << "copy " << t;
    EXPECT_TRUE(arb_equal(balls[static_cast<std::size_t>(t)].get(), balls[0].get())) << "copy " << t;
  }
}

}  // namespace
}  // namespace uniparam
