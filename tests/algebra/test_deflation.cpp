// Tests of uniparam/algebra/deflation.hpp: p = q * (t - gamma)^k with known
// q, exact quotients for rational gamma, independent Arb references and the
// identity q(t) (t - gamma)^k = p(t) at random points for irrational gamma.
#include <arb.h>
#include <arb_poly.h>
#include <arf.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/algebra/deflation.hpp"
#include "uniparam/core/error.hpp"

namespace uniparam {
namespace {

using test_support::iterations;

Poly constant(const Integer& c) { return Poly(std::vector<Integer>{c}); }

Poly random_poly(std::mt19937_64& rng, long max_degree, long max_coeff) {
  const long n = std::uniform_int_distribution<long>(0, max_degree)(rng);
  std::vector<long> c(static_cast<std::size_t>(n + 1));
  for (long& v : c) v = std::uniform_int_distribution<long>(-max_coeff, max_coeff)(rng);
  if (c.back() == 0) c.back() = 1;
  return Poly(c);
}

TEST(Deflation, RationalGammaGivesTheExactQuotient) {
  std::mt19937_64 rng(555);
  const long iters = iterations(200);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 555)");
    const Rational g(std::uniform_int_distribution<long>(-20, 20)(rng), std::uniform_int_distribution<long>(1, 7)(rng));
    const Poly lin(std::vector<Integer>{Integer(0) - g.num(), g.den()});  // d t - n
    Poly q = random_poly(rng, 8, 50);
    if (q.sign_at(g) == 0) continue;
    const int k = static_cast<int>(std::uniform_int_distribution<long>(0, 4)(rng));
    const Poly p = q * lin.pow(static_cast<unsigned long>(k));
    const RealAlgebraic gamma(g);
    EXPECT_EQ(root_multiplicity(p, gamma), k);
    for (int j = 0; j <= k; ++j) {
      // p / (t - g)^j = q * d^j * (d t - n)^(k - j), exactly.
      const Poly expect = q * constant(g.den()).pow(static_cast<unsigned long>(j)) *
                          lin.pow(static_cast<unsigned long>(k - j));
      const BallPoly d = deflate(p, gamma, j, 64);
      ASSERT_EQ(d.degree(), expect.degree()) << p.str() << " / (t - " << g.str() << ")^" << j;
      for (long i = 0; i <= expect.degree(); ++i)
        EXPECT_TRUE(d.coeff(i).contains(Rational(expect.coeff(i)))) << "coefficient " << i << " of " << p.str();
    }
    EXPECT_THROW(deflate(p, gamma, k + 1, 64), DomainError);
  }
}

/// Irrational gammas with their irreducible polynomial and an isolating
/// interval, and a reference enclosure from Arb.
struct Gamma {
  Poly minpoly;
  Rational lo, hi;
  Ball ref;  // at 2000 bits
};

std::vector<Gamma> irrational_gammas() {
  std::vector<Gamma> out;
  auto add = [&](std::vector<long> c, Rational lo, Rational hi, Ball ref) {
    out.push_back({Poly(c), lo, hi, ref});
  };
  const long prec = 2000;
  Ball r;
  arb_sqrt_ui(r.get(), 2, prec);
  add({-2, 0, 1}, Rational(1), Rational(2), r);  // sqrt2
  arb_neg(r.get(), r.get());
  add({-2, 0, 1}, Rational(-2), Rational(-1), r);  // -sqrt2
  arb_set_ui(r.get(), 2);
  arb_root_ui(r.get(), r.get(), 3, prec);
  add({-2, 0, 0, 1}, Rational(1), Rational(2), r);  // 2^(1/3)
  arb_set_ui(r.get(), 27);
  arb_root_ui(r.get(), r.get(), 4, prec);
  arb_inv(r.get(), r.get(), prec);
  add({-1, 0, 0, 0, 27}, Rational(0), Rational(1), r);  // 27^(-1/4)
  arb_sqrt_ui(r.get(), 7, prec);
  arb_mul_ui(r.get(), r.get(), 10, prec);
  add({-700, 0, 1}, Rational(20), Rational(30), r);  // 10 sqrt7 (|gamma| > 1)
  return out;
}

TEST(Deflation, IrrationalGammaEnclosesTheQuotient) {
  std::mt19937_64 rng(8080);
  const std::vector<Gamma> gammas = irrational_gammas();
  const long iters = iterations(60);
  for (long it = 0; it < iters; ++it) {
    SCOPED_TRACE("iteration " + std::to_string(it) + " (seed 8080)");
    const Gamma& G = gammas[static_cast<std::size_t>(it) % gammas.size()];
    const RealAlgebraic gamma(G.minpoly, G.lo, G.hi);
    // q coprime to the irreducible minpoly, so q(gamma) != 0.
    Poly q = random_poly(rng, 7, 30);
    if (gcd(q, G.minpoly).degree() > 0) continue;
    const int k = static_cast<int>(std::uniform_int_distribution<long>(1, 4)(rng));
    const Poly p = q * G.minpoly.pow(static_cast<unsigned long>(k));
    ASSERT_EQ(root_multiplicity(p, gamma), k);
    const long prec = std::uniform_int_distribution<long>(30, 300)(rng);
    const BallPoly d = deflate(p, gamma, k, prec);
    ASSERT_EQ(d.degree(), p.degree() - k);
    // Reference quotient with Arb alone: p / (t - ref)^k by arb_poly_divrem.
    BallPoly lin_ref, divisor, quo, rem;
    arb_poly_set_coeff_si(lin_ref.get(), 1, 1);
    Ball neg;
    arb_neg(neg.get(), G.ref.get());
    arb_poly_set_coeff_arb(lin_ref.get(), 0, neg.get());
    arb_poly_pow_ui(divisor.get(), lin_ref.get(), static_cast<ulong>(k), 2000);
    ASSERT_TRUE(arb_poly_divrem(quo.get(), rem.get(), BallPoly(p).get(), divisor.get(), 2000));
    for (long i = 0; i <= d.degree(); ++i) {
      const Ball c = d.coeff(i), r = quo.coeff(i);
      EXPECT_TRUE(arb_overlaps(c.get(), r.get())) << "coefficient " << i << ": " << c.str() << " vs " << r.str();
      // Accuracy: the radius is about 2^-prec relative.
      Rational scale = mid_rational(r);
      if (scale.sign() < 0) scale = -scale;
      if (scale < Rational(1)) scale = Rational(1);
      EXPECT_TRUE(rad_rational(c) <= scale * pow2(-(prec - 8))) << "coefficient " << i << " too wide: " << c.str();
    }
    // q_deflated(t0) * (t0 - gamma)^k must contain p(t0) exactly.
    for (int s = 0; s < 5; ++s) {
      const Rational t0(std::uniform_int_distribution<long>(-300, 300)(rng), std::uniform_int_distribution<long>(1, 97)(rng));
      const long wp = prec + 64;
      Ball lhs = d(Ball(t0, wp), wp), diff;
      const Ball g = gamma.to_ball(wp);
      arb_sub(diff.get(), Ball(t0, wp).get(), g.get(), wp);
      arb_pow_ui(diff.get(), diff.get(), static_cast<ulong>(k), wp);
      arb_mul(lhs.get(), lhs.get(), diff.get(), wp);
      EXPECT_TRUE(lhs.contains(p(t0))) << "at t = " << t0.str() << ": " << lhs.str() << " vs " << p(t0).str();
    }
  }
}

TEST(Deflation, PreconditionsAndMultiplicities) {
  const Poly t2m2(std::vector<long>{-2, 0, 1}), t2m3(std::vector<long>{-3, 0, 1});
  const Poly p = t2m2.pow(2) * t2m3.pow(3) * Poly(std::vector<long>{-1, 2});
  const RealAlgebraic s2(t2m2, Rational(1), Rational(2)), s3(t2m3, Rational(1), Rational(2));
  // sqrt3 given by the reducible (t^2-2)(t^2-3) in (3/2, 2).
  const RealAlgebraic s3b(t2m2 * t2m3, Rational(3, 2), Rational(2));
  EXPECT_EQ(root_multiplicity(p, s2), 2);
  EXPECT_EQ(root_multiplicity(p, s3), 3);
  EXPECT_EQ(root_multiplicity(p, s3b), 3);
  EXPECT_EQ(root_multiplicity(p, RealAlgebraic(Rational(1, 2))), 1);
  EXPECT_EQ(root_multiplicity(p, RealAlgebraic(1)), 0);
  EXPECT_EQ(root_multiplicity(t2m2, s3), 0);
  EXPECT_THROW(root_multiplicity(Poly(), s2), InvalidArgument);
  EXPECT_THROW(deflate(p, s2, 3, 64), DomainError);
  EXPECT_THROW(deflate(p, s3b, 4, 64), DomainError);
  EXPECT_THROW(deflate(p, RealAlgebraic(1), 1, 64), DomainError);
  EXPECT_THROW(deflate(p, s2, -1, 64), InvalidArgument);
  EXPECT_NO_THROW(deflate(p, s3b, 3, 64));
  // k = 0 is p itself, exactly.
  const BallPoly same = deflate(p, s2, 0, 64);
  ASSERT_EQ(same.degree(), p.degree());
  for (long i = 0; i <= p.degree(); ++i) {
    EXPECT_TRUE(same.coeff(i).is_exact());
    EXPECT_TRUE(same.coeff(i).contains(Rational(p.coeff(i))));
  }
}

}  // namespace
}  // namespace uniparam
