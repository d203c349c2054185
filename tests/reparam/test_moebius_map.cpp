// The local Moebius map of a piece (reparam/src/moebius_map.hpp), written once
// for real balls, complex balls and exact rationals: exact values against the
// closed form, enclosures against the exact values, exact ends.
#include <gtest/gtest.h>

#include <random>

#include "../../reparam/src/moebius_map.hpp"
#include "uniparam/core/ball.hpp"
#include "uniparam/core/number.hpp"

namespace uniparam {
namespace {

using detail::AcbMapArith;
using detail::BallMapArith;
using detail::RationalMapArith;

Rational random_unit(std::mt19937_64& g, bool open) {
  std::uniform_int_distribution<long> den(1, 1000);
  const long q = den(g);
  std::uniform_int_distribution<long> num(open ? 1 : 0, open ? q - 1 : q);
  if (open && q == 1) return Rational(1, 2);
  return Rational(num(g), q);
}

// A ball of radius about 2^-40 around x (so never exact).
Ball fuzzy(const Rational& x) {
  Ball b(x, 80);
  mag_set_ui_2exp_si(arb_radref(b.get()), 1, -40);
  return b;
}

TEST(MoebiusMap, RationalMatchesTheClosedForm) {
  std::mt19937_64 g(35);
  for (int k = 0; k < 300; ++k) {
    const Rational a = random_unit(g, true), u = random_unit(g, false);
    Rational x, dx;
    detail::moebius_alpha_map(RationalMapArith{}, &x, &dx, &u, &a);
    const Rational den = a + (Rational(1) - Rational(2) * a) * u;
    EXPECT_EQ(x, (Rational(1) - a) * u / den) << "alpha " << a.str() << ", u " << u.str();
    EXPECT_EQ(dx, a * (Rational(1) - a) / (den * den));
    // the balancing form k u / (k u + 1 - u) with k = (1 - a) / a is the same map
    const Rational kk = (Rational(1) - a) / a;
    Rational y, d;
    detail::moebius_map(RationalMapArith{}, &y, nullptr, &d, &u, &kk, nullptr);
    EXPECT_EQ(y, x);
    EXPECT_EQ(d, kk * u + Rational(1) - u);
  }
}

TEST(MoebiusMap, BallsEncloseTheExactValues) {
  std::mt19937_64 g(36);
  for (int k = 0; k < 300; ++k) {
    const Rational a = random_unit(g, true), u = random_unit(g, false);
    Rational x, dx;
    detail::moebius_alpha_map(RationalMapArith{}, &x, &dx, &u, &a);
    const Ball ab = fuzzy(a), ub = fuzzy(u);
    Ball xb, dxb;
    detail::moebius_alpha_map(BallMapArith{64}, xb.get(), dxb.get(), ub.get(), ab.get());
    EXPECT_TRUE(xb.contains(x)) << xb.str() << " vs " << x.str();
    EXPECT_TRUE(dxb.contains(dx)) << dxb.str() << " vs " << dx.str();
    AcbBox ac, uc, xc, dxc;
    acb_set_arb(ac, ab.get());
    acb_set_arb(uc, ub.get());
    detail::moebius_alpha_map(AcbMapArith{64}, xc, dxc, uc, ac);
    EXPECT_TRUE(arb_contains_fmpq(acb_realref(xc.get()), x.get()));
    EXPECT_TRUE(arb_contains_fmpq(acb_realref(dxc.get()), dx.get()));
    EXPECT_TRUE(arb_contains_zero(acb_imagref(xc.get())));
  }
}

TEST(MoebiusMap, ExactEndsStayExact) {
  std::mt19937_64 g(37);
  for (int k = 0; k < 50; ++k) {
    const Ball ab = fuzzy(random_unit(g, true));  // an inexact alpha
    for (long e = 0; e <= 1; ++e) {
      const Ball u(e);
      Ball x;
      detail::moebius_alpha_map(BallMapArith{64}, x.get(), nullptr, u.get(), ab.get());
      EXPECT_TRUE(x.is_exact());
      EXPECT_TRUE(x.contains(Rational(e)));
      AcbBox ac, uc, xc;
      acb_set_arb(ac, ab.get());
      acb_set_arb(uc, u.get());
      detail::moebius_alpha_map(AcbMapArith{64}, xc, nullptr, uc, ac);
      EXPECT_TRUE(acb_is_exact(xc.get()));
      EXPECT_TRUE(e == 0 ? acb_is_zero(xc.get()) : acb_is_one(xc.get()));
    }
  }
}

TEST(MoebiusMap, WideArgumentEnclosesTheImage) {
  // x is increasing: a ball u = [lo, hi] must give x containing x(lo) and x(hi)
  std::mt19937_64 g(38);
  for (int k = 0; k < 200; ++k) {
    const Rational a = random_unit(g, true);
    Rational lo = random_unit(g, false), hi = random_unit(g, false);
    if (hi < lo) std::swap(lo, hi);
    Ball ub;
    arb_set_fmpq(ub.get(), ((lo + hi) / Rational(2)).get(), 128);
    Ball half((hi - lo) / Rational(2), 128);
    arb_add_error(ub.get(), half.get());
    Ball xb, ab(a, 128);
    detail::moebius_alpha_map(BallMapArith{128}, xb.get(), nullptr, ub.get(), ab.get());
    for (const Rational& u : {lo, hi}) {
      Rational x;
      detail::moebius_alpha_map(RationalMapArith{}, &x, nullptr, &u, &a);
      EXPECT_TRUE(xb.contains(x)) << "alpha " << a.str() << ", u " << u.str();
    }
  }
}

}  // namespace
}  // namespace uniparam
