// The parametric speed |p'| through every method (uniformity, the optimal
// Moebius map, C0 piecewise Moebius with optimised breakpoints, piecewise
// radical), for plane and space curves, regular ones and ones with cusps
// (p' = 0, zeros of the parametric speed lifted by the radical method).
//
// Oracles are independent of the library's quadrature: composite
// Gauss-Legendre in long double of |p'| evaluated from the exact derivative,
// exact rational integrals for polynomial curves, and the reparameterized
// speed of the returned map integrated directly in its own parameter
// (mu^2 / int sigma_{p o r}(z)^2 dz), not the L, M formulas.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

using LD = long double;

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on P_n).
struct GaussLegendre {
  std::vector<LD> x, w;
  explicit GaussLegendre(int n) {
    const LD pi = 3.141592653589793238462643383279502884L;
    for (int i = 0; i < n; ++i) {
      LD z = std::cos(pi * (i + 0.75L) / (n + 0.5L)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        LD p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          LD p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const LD dz = p1 / dp;
        z -= dz;
        if (std::fabs(dz) < 1e-19L) break;
      }
      x.push_back(z);
      w.push_back(2 / ((1 - z * z) * dp * dp));
    }
  }
};

const GaussLegendre& gl() {
  static const GaussLegendre g(24);
  return g;
}

// Composite Gauss-Legendre of f over [a, b] with m equal panels.
LD integrate(const std::function<LD(LD)>& f, LD a, LD b, int m = 24) {
  LD s = 0;
  const LD h = (b - a) / m;
  for (int k = 0; k < m; ++k) {
    const LD c = a + (k + 0.5L) * h;
    for (std::size_t i = 0; i < gl().x.size(); ++i) s += gl().w[i] * f(c + gl().x[i] * h / 2);
  }
  return s * h / 2;
}

LD to_ld(const Rational& q) {
  return static_cast<LD>(fmpz_get_d(fmpq_numref(q.get()))) / static_cast<LD>(fmpz_get_d(fmpq_denref(q.get())));
}

LD eval_poly(const Poly& p, LD t) {
  LD s = 0;
  for (long k = p.degree(); k >= 0; --k) s = s * t + static_cast<LD>(fmpz_get_d(p.coeff(k).get()));
  return s;
}

LD mid(const Ball& b) { return static_cast<LD>(arf_get_d(arb_midref(b.get()), ARF_RND_NEAR)); }

// |p'(t)|^2 from the exact derivative of the components, in long double.
struct ParametricSpeed {
  std::vector<RatFunc> d;
  explicit ParametricSpeed(const Curve& c) {
    for (const auto& x : c.components()) d.push_back(x.derivative());
  }
  LD squared(LD t) const {
    LD s = 0;
    for (const auto& x : d) {
      const LD v = eval_poly(x.num(), t) / eval_poly(x.den(), t);
      s += v * v;
    }
    return s;
  }
  LD operator()(LD t) const { return std::sqrt(squared(t)); }
};

struct Case {
  const char* curve;
  std::vector<std::pair<Rational, int>> zeros;  // zeros of |p'| in [0, 1] with multiplicities
  bool polynomial;
};

std::vector<Case> cases() {
  return {
      {"(t, t^2)", {}, true},
      {"(t^3 - t, 2t^2 + t)", {}, true},
      {"((1 - t^2)/(1 + t^2), 2t/(1 + t^2))", {}, false},
      {"(t, t^2, t^3)", {}, true},
      {"((1 - t^2)/(1 + t^2), 2t/(1 + t^2), t)", {}, false},
      {"(t^2, t^3)", {{Rational(0), 1}}, true},                                    // plane cusp
      {"(t^3, t^4)", {{Rational(0), 2}}, true},                                    // zero of order 2
      {"((2t - 1)^2, (2t - 1)^3)", {{Rational(1, 2), 1}}, true},                  // interior cusp
      {"(t^2, t^3, t^4)", {{Rational(0), 1}}, true},                               // space cusp
      {"((2t - 1)^2, (2t - 1)^3, (2t - 1)^4)", {{Rational(1, 2), 1}}, true},
      {"(t^2/(1 + t), t^3/(1 + t))", {{Rational(0), 1}}, false},                   // rational, cusp
  };
}

// Splits [0, 1] at the zeros (where |p'| is not smooth) and integrates f.
LD integrate_split(const std::function<LD(LD)>& f, const Case& c) {
  std::vector<LD> ends{0};
  for (const auto& z : c.zeros)
    if (z.first != Rational(0) && z.first != Rational(1)) ends.push_back(to_ld(z.first));
  ends.push_back(1);
  LD s = 0;
  for (std::size_t i = 0; i + 1 < ends.size(); ++i) s += integrate(f, ends[i], ends[i + 1]);
  return s;
}

struct Oracle {
  LD mu, sq, A, B, C;
};

Oracle oracle(const Curve& curve, const Case& c) {
  const ParametricSpeed s(curve);
  Oracle o;
  o.mu = integrate_split([&](LD t) { return s(t); }, c);
  o.sq = integrate_split([&](LD t) { return s.squared(t); }, c);
  o.A = integrate_split([&](LD t) { return s.squared(t) * (1 - t) * (1 - t); }, c);
  o.B = integrate_split([&](LD t) { return s.squared(t) * 2 * t * (1 - t); }, c);
  o.C = integrate_split([&](LD t) { return s.squared(t) * t * t; }, c);
  return o;
}

// Exact int_0^1 f (1-t)^a t^b for a polynomial f.
Rational exact_moment(const RatFunc& f, int a, int b) {
  const RatFunc t = RatFunc::t();
  const RatFunc g = f * (RatFunc(1) - t).pow(a) * t.pow(b);
  EXPECT_LE(g.den().degree(), 0);
  Rational s(0);
  for (long k = 0; k <= g.num().degree(); ++k) s = s + Rational(g.num().coeff(k), Integer(k + 1));
  return s / Rational(g.den().coeff(0));
}

RatFunc exact_speed_squared(const Curve& c) {
  RatFunc s(0);
  for (const auto& x : c.components()) s = s + x.derivative() * x.derivative();
  return s;
}

bool close(const Ball& b, LD x, LD tol = 1e-13L) {
  return std::fabs(mid(b) - x) <= tol * std::max<LD>(1, std::fabs(x));
}

// mu^2 / int_0^1 sigma_{p o r}(z)^2 dz by Gauss-Legendre over the pieces of
// r (breakpoints Zb), with `speed` the library's evaluation of the
// reparameterized speed at a point; `q[i]` > 1 substitutes z~ = w^q (zero at
// the left end) or 1 - (1 - w)^q (right end) so that the integrand stays
// analytic at a lifted zero.
LD direct_u(LD mu, const std::vector<Ball>& Zb, const std::vector<int>& q, const std::vector<ZeroSide>& side,
            const std::function<Ball(const Ball&)>& speed) {
  LD total = 0;
  for (std::size_t i = 0; i + 1 < Zb.size(); ++i) {
    const LD z0 = mid(Zb[i]), z1 = mid(Zb[i + 1]), dz = z1 - z0;
    auto f = [&](LD w) {
      LD zt = w, jac = 1;
      if (side[i] == ZeroSide::Left) { zt = std::pow(w, q[i]); jac = q[i] * std::pow(w, q[i] - 1); }
      if (side[i] == ZeroSide::Right) { zt = 1 - std::pow(1 - w, q[i]); jac = q[i] * std::pow(1 - w, q[i] - 1); }
      Ball z;
      arb_set_d(z.get(), static_cast<double>(z0 + dz * zt));
      const LD v = mid(speed(z));
      return v * v * jac * dz;
    };
    total += integrate(f, 0, 1, 16);
  }
  return mu * mu / total;
}

}  // namespace

TEST(Parametric, UniformityAgainstDirectIntegration) {
  Options o;
  for (const Case& c : cases()) {
    const Curve curve = parse_curve(c.curve);
    const UniformityResult r = uniformity(curve, SpeedKind::Parametric, o);
    ASSERT_EQ(r.zeros.size(), c.zeros.size()) << c.curve;
    for (std::size_t i = 0; i < c.zeros.size(); ++i) {
      EXPECT_TRUE(r.zeros[i].t == RealAlgebraic(c.zeros[i].first)) << c.curve;
      EXPECT_EQ(r.zeros[i].multiplicity, c.zeros[i].second) << c.curve;
    }
    EXPECT_EQ(r.speed_squared, exact_speed_squared(curve)) << c.curve;
    const Oracle x = oracle(curve, c);
    EXPECT_TRUE(close(r.mu, x.mu)) << c.curve << ": " << r.mu.str(20) << " vs " << static_cast<double>(x.mu);
    EXPECT_TRUE(close(r.mean_square, x.sq)) << c.curve;
    EXPECT_TRUE(close(r.u, x.mu * x.mu / x.sq)) << c.curve;
    if (c.polynomial) EXPECT_TRUE(r.mean_square.contains(exact_moment(exact_speed_squared(curve), 0, 0))) << c.curve;
  }
  // closed forms: (t^2, t^3): mu = (13^(3/2) - 8) / 27, int |p'|^2 = 47/15
  const UniformityResult r = uniformity(parse_curve("(t^2, t^3)"), SpeedKind::Parametric, o);
  Ball mu;
  arb_set_ui(mu.get(), 13);
  arb_pow_ui(mu.get(), mu.get(), 3, 256);
  arb_sqrt(mu.get(), mu.get(), 256);
  arb_sub_ui(mu.get(), mu.get(), 8, 256);
  arb_div_ui(mu.get(), mu.get(), 27, 256);
  EXPECT_TRUE(r.mu.contains(mu)) << r.mu.str(30);
  EXPECT_TRUE(r.mean_square.contains(Rational(47, 15)));
}

TEST(Parametric, OptimalMoebiusAgainstDirectIntegration) {
  Options o;
  for (const Case& c : cases()) {
    const Curve curve = parse_curve(c.curve);
    const MoebiusResult r = moebius_optimal(curve, SpeedKind::Parametric, o);
    const Oracle x = oracle(curve, c);
    const PieceIntegrals& p = r.integrals.at(0);
    EXPECT_TRUE(close(p.A, x.A)) << c.curve;
    EXPECT_TRUE(close(p.B, x.B)) << c.curve;
    EXPECT_TRUE(close(p.C, x.C)) << c.curve;
    EXPECT_TRUE(close(p.alpha, 1 / (1 + std::sqrt(x.C / x.A)))) << c.curve;
    EXPECT_TRUE(close(r.u_after, x.mu * x.mu / (x.B + 2 * std::sqrt(x.A * x.C)))) << c.curve;
    EXPECT_EQ(r.speed_vanishes, !c.zeros.empty()) << c.curve;
    if (c.polynomial) {
      const RatFunc s2 = exact_speed_squared(curve);
      EXPECT_TRUE(p.A.contains(exact_moment(s2, 2, 0))) << c.curve;
      EXPECT_TRUE(p.C.contains(exact_moment(s2, 0, 2))) << c.curve;
    }
    // the map's own speed, integrated directly in s
    const Speed sp(curve, SpeedKind::Parametric);
    const LD u = direct_u(x.mu, r.S, {1}, {ZeroSide::None},
                          [&](const Ball& s) { return eval_speed(r, sp, s, 128); });
    EXPECT_TRUE(close(r.u_after, u, 1e-12L)) << c.curve << ": " << r.u_after.str(20) << " vs " << static_cast<double>(u);
  }
}

TEST(Parametric, PiecewiseMoebiusAgainstDirectIntegration) {
  Options o;
  o.digits = 12;
  for (const Case& c : cases()) {
    const Curve curve = parse_curve(c.curve);
    for (long N : {2L, 3L}) {
      const MoebiusResult r = reparam_c0(curve, SpeedKind::Parametric, N, o);
      ASSERT_EQ(r.pieces(), static_cast<std::size_t>(N));
      const Oracle x = oracle(curve, c);
      const Speed sp(curve, SpeedKind::Parametric);
      const LD u = direct_u(x.mu, r.S, std::vector<int>(N, 1), std::vector<ZeroSide>(N, ZeroSide::None),
                            [&](const Ball& s) { return eval_speed(r, sp, s, 128); });
      EXPECT_TRUE(close(r.u_after, u, 1e-11L)) << c.curve << " N = " << N;
      EXPECT_TRUE(arb_ge(r.u_after.get(), r.u_before.get()) || arb_overlaps(r.u_after.get(), r.u_before.get()));
    }
  }
}

TEST(Parametric, RadicalLiftsCuspsAgainstDirectIntegration) {
  Options o;
  for (const Case& c : cases()) {
    const Curve curve = parse_curve(c.curve);
    const RadicalResult r = radical(curve, SpeedKind::Parametric, o);
    // every zero of |p'| is a breakpoint with its multiplicity
    for (const auto& z : c.zeros) {
      bool found = false;
      for (const auto& b : r.T)
        if (b.t == RealAlgebraic(z.first)) {
          found = true;
          EXPECT_EQ(b.multiplicity, z.second) << c.curve;
        }
      EXPECT_TRUE(found) << c.curve;
    }
    const Oracle x = oracle(curve, c);
    EXPECT_TRUE(close(r.mu, x.mu)) << c.curve;
    EXPECT_TRUE(close(r.u_before, x.mu * x.mu / x.sq)) << c.curve;
    const Speed sp(curve, SpeedKind::Parametric);
    std::vector<int> q;
    std::vector<ZeroSide> side;
    for (std::size_t i = 0; i < r.pieces(); ++i) {
      q.push_back(r.root_index(i));
      side.push_back(r.side(i));
    }
    const LD u = direct_u(x.mu, r.Z, q, side, [&](const Ball& z) { return eval_speed(r, sp, z, 128); });
    EXPECT_TRUE(close(r.u_after, u, 1e-12L)) << c.curve << ": " << r.u_after.str(20) << " vs " << static_cast<double>(u);
    // A cusp is lifted: the reparameterized speed does not vanish there
    // (a rational map keeps the zero: sigma_{p o m} = 0 at the cusp).
    if (!c.zeros.empty()) {
      EXPECT_TRUE(arb_gt(r.u_after.get(), moebius_optimal(curve, SpeedKind::Parametric, o).u_after.get())) << c.curve;
      for (std::size_t i = 0; i < r.T.size(); ++i)
        if (r.T[i].multiplicity > 0) {
          const Ball v = eval_speed(r, sp, r.Z[i], 128);
          EXPECT_TRUE(v.certainly_positive()) << c.curve << " at z = " << r.Z[i].str(10);
        }
    }
  }
}

// (t^2, t^3): phi is t = sqrt(s), q = p o phi has |q'|^2 = (4 + 9 s) / 4
// exactly, so u(p o phi), A, B, C and u(p o phi o m) have closed forms.
TEST(Parametric, PlaneCuspClosedForms) {
  Options o;
  o.digits = 20;
  const RadicalResult r = radical(parse_curve("(t^2, t^3)"), SpeedKind::Parametric, o);
  ASSERT_EQ(r.pieces(), 1u);
  EXPECT_EQ(r.T[0].multiplicity, 1);
  const RatFunc s = RatFunc::t();
  const RatFunc q2 = (RatFunc(4) + RatFunc(9) * s) / RatFunc(4);
  const Rational L = exact_moment(q2, 0, 0), A = exact_moment(q2, 2, 0), C = exact_moment(q2, 0, 2),
                 B = exact_moment(q2 * RatFunc(2), 1, 1);
  EXPECT_EQ(L, Rational(17, 8));
  EXPECT_TRUE(r.integrals[0].L.contains(L));
  EXPECT_TRUE(r.integrals[0].A.contains(A));
  EXPECT_TRUE(r.integrals[0].B.contains(B));
  EXPECT_TRUE(r.integrals[0].C.contains(C));
  const long prec = 256;
  Ball mu;
  arb_set_ui(mu.get(), 13);
  arb_pow_ui(mu.get(), mu.get(), 3, prec);
  arb_sqrt(mu.get(), mu.get(), prec);
  arb_sub_ui(mu.get(), mu.get(), 8, prec);
  arb_div_ui(mu.get(), mu.get(), 27, prec);
  Ball mu2, u, Lb(L, prec), M, Ab(A, prec), Bb(B, prec), Cb(C, prec);
  arb_mul(mu2.get(), mu.get(), mu.get(), prec);
  arb_div(u.get(), mu2.get(), Lb.get(), prec);
  EXPECT_TRUE(r.u_radical.contains(u)) << r.u_radical.str(25);
  arb_mul(M.get(), Ab.get(), Cb.get(), prec);
  arb_sqrt(M.get(), M.get(), prec);
  arb_mul_2exp_si(M.get(), M.get(), 1);
  arb_add(M.get(), M.get(), Bb.get(), prec);
  arb_div(u.get(), mu2.get(), M.get(), prec);
  EXPECT_TRUE(r.u_after.contains(u)) << r.u_after.str(25);
}
