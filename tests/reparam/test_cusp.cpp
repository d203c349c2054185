// Cusps: curves whose p' numerators share a factor with a real root c in
// [0, 1] (p'(c) = 0 at a rational c, inside or at an end). The angular speed
// omega is finite there after cancellation (docs/math.md §1), and every
// sign, value, zero and integral inside a piece must come from the cancelled
// speed. Oracles: closed forms evaluated with Arb ((u^k, u^(k+1)) with
// u = t - c has omega = k (k+1) / (k^2 + (k+1)^2 u^2), so mu = atan((k+1)
// (1-c) / k) + atan((k+1) c / k)), and curves with the factor removed by hand
// (q' parallel to p', no common factor: the evaluation path of ordinary
// curves) whose certified results must overlap the cusp curve's, because both
// enclose the same true numbers.
#include <gtest/gtest.h>

#include <arb.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

constexpr long kPrec = 256;  // working precision of the oracles and evaluations

Ball exact(const Rational& q) { return Ball(q, kPrec); }

::testing::AssertionResult agrees(const Ball& got, const Ball& want) {
  if (!got.is_finite()) return ::testing::AssertionFailure() << "not finite: " << got.str(30);
  if (arb_overlaps(got.get(), want.get())) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << got.str(40) << " misses " << want.str(40);
}

// The degree of gcd(X_1, ..., X_n) of p' = X / W.
long common_factor_degree(const Curve& c) {
  Poly g;
  for (const auto& x : c.derivative_numerators()) g = gcd(g, x);
  return g.degree();
}

// "((t - c)^k, (t - c)^(k+1))": a cusp of order k - 1 at c, omega finite and
// nonzero everywhere.
std::string power_cusp(long k, const Rational& c) {
  const std::string u = "(t - (" + c.str() + "))";
  return "(" + u + "^" + std::to_string(k) + ", " + u + "^" + std::to_string(k + 1) + ")";
}

// omega(t) of power_cusp(k, c), exactly.
Rational power_cusp_omega(long k, const Rational& c, const Rational& t) {
  const Rational u = t - c;
  return Rational(k * (k + 1)) / (Rational(k * k) + Rational((k + 1) * (k + 1)) * u * u);
}

// mu of power_cusp(k, c) on [0, 1].
Ball power_cusp_mu(long k, const Rational& c) {
  Ball a = exact(Rational(k + 1, k) * (Rational(1) - c)), b = exact(Rational(k + 1, k) * c), r;
  arb_atan(a.get(), a.get(), kPrec);
  arb_atan(b.get(), b.get(), kPrec);
  arb_add(r.get(), a.get(), b.get(), kPrec);
  return r;
}

// A random rational in [0, 1] with denominator at most 40.
Rational random_position(std::mt19937_64& rng) {
  const long q = std::uniform_int_distribution<long>(1, 40)(rng);
  return Rational(std::uniform_int_distribution<long>(0, q)(rng), q);
}

double to_double(const Rational& q) { return arf_get_d(arb_midref(exact(q).get()), ARF_RND_NEAR); }

// sigma (squared: sigma^2) at the exact rational t, with the signs of `p`.
Ball speed_at(const Speed& s, const Speed::PieceSigns& p, const Rational& t, bool squared) {
  acb_t z, w;
  acb_init(z);
  acb_init(w);
  arb_set_fmpq(acb_realref(z), t.get(), kPrec);
  if (squared) s.eval_squared(w, z, kPrec);
  else s.eval(w, z, p, false, kPrec);
  Ball r;
  arb_set(r.get(), acb_realref(w));
  acb_clear(z);
  acb_clear(w);
  return r;
}

struct Pair {
  const char* cusp;     // p'(c) = 0 at a rational c in [0, 1]
  const char* reduced;  // a curve with q' parallel to p' and no common factor
  Rational c;           // the cusp where it is rational (the C0 check's breakpoint where it is inside)
  bool omega_vanishes;  // omega has a zero in [0, 1] (then no C1 target)
};

std::vector<Pair> pairs() {
  return {
      {"((t-1/2)^2, (t-1/2)^3)", "(2*t, 3*(t-1/2)^2/2)", Rational(1, 2), false},
      {"((t-1/3)^3, (t-1/3)^4 + (t-1/3)^5)", "(3*t, 2*(t-1/3)^2 + 5*(t-1/3)^3/3)", Rational(1, 3), false},
      {"((t-1)^2, (t-1)^3)", "(2*t, 3*(t-1)^2/2)", Rational(1), false},
      {"(t^2, t^3)", "(2*t, 3*t^2/2)", Rational(0), false},
      {"((t-2/5)^2, (t-2/5)^3, (t-2/5)^4)", "(2*t, 3*(t-2/5)^2/2, 4*(t-2/5)^3/3)", Rational(2, 5), false},
      {"((t-1)^3, (t-1)^4, (t-1)^6)", "(3*t, 2*(t-1)^2, 3*(t-1)^4/2)", Rational(1), false},
      // omega vanishes at the cusp itself (multiplicity 2, then 1)
      {"((t-3/5)^2, (t-3/5)^5)", "(2*t, 5*(t-3/5)^4/4)", Rational(3, 5), true},
      {"((t-1/4)^3, (t-1/4)^5)", "(3*t, 5*(t-1/4)^3/3)", Rational(1, 4), true},
      // a rational cusp at t = 2/3: (u^2, u^3) o m with m = t / (2 - t), u = m - 1/2
      {"((t/(2-t)-1/2)^2, (t/(2-t)-1/2)^3)", "(2*t/(2-t), 3*(t/(2-t)-1/2)^2/2)", Rational(2, 3), false},
      // an irrational cusp at t = 1/sqrt(2): (f^2, f^3), f = t^2 - 1/2, p' = f f' (2, 3 f);
      // omega vanishes at t = 0 (an inflection of the direction)
      {"((t^2-1/2)^2, (t^2-1/2)^3)", "(2*t, t^3 - 3*t/2)", Rational(0), true},
  };
}

}  // namespace

// The angular speed at and around random rational cusps of every order is the
// closed form, from every evaluation path (certified balls, the exact signs
// of piece_signs on a piece whose sign point is the cusp itself, the double
// evaluation of the optimisers), and mu is certified.
TEST(Cusp, AngularSpeedIsTheCancelledOneAtRandomRationalCusps) {
  std::mt19937_64 rng(20261203);
  const long n = test_support::iterations(12);
  for (long it = 0; it < n; ++it) {
    const long k = 2 + it % 3;
    const Rational c = it == 0 ? Rational(1, 2) : it == 1 ? Rational(0) : it == 2 ? Rational(1) : random_position(rng);
    const std::string text = power_cusp(k, c);
    SCOPED_TRACE(text);
    const Curve p = Curve::parse(text);
    ASSERT_GT(common_factor_degree(p), 0);
    const Speed s(p, SpeedKind::Angular);
    EXPECT_TRUE(s.zeros().empty());
    Speed::PieceSigns whole;
    ASSERT_NO_THROW(whole = s.piece_signs(RealAlgebraic(0), RealAlgebraic(1)));
    std::vector<Rational> ts{Rational(0), Rational(1), c, Rational(1, 2)};
    for (const Rational& d : {Rational(1, 1000), Rational(1, 1L << 40)}) {
      if (c - d > Rational(0)) ts.push_back(c - d);
      if (c + d < Rational(1)) ts.push_back(c + d);
    }
    for (const Rational& t : ts) {
      SCOPED_TRACE("t = " + t.str());
      const Rational w = power_cusp_omega(k, c, t);
      const Ball v = speed_at(s, whole, t, false), v2 = speed_at(s, whole, t, true);
      EXPECT_TRUE(v.is_finite() && v.contains(w)) << v.str(30);
      EXPECT_TRUE(v2.is_finite() && v2.contains(w * w)) << v2.str(30);
      const double wd = to_double(w), d = s.squared_double(to_double(t));
      EXPECT_TRUE(std::isfinite(d) && std::fabs(d - wd * wd) <= 1e-9 * wd * wd) << d << " vs " << wd * wd;
    }
    if (c > Rational(0) && c < Rational(1)) {
      // A piece around c whose simplest rational, where the signs are taken,
      // is c: every other rational within 1/(4 q^2) of c = p/q has a
      // denominator above 4q.
      const Rational q(c.den());
      const Rational h = Rational(1) / (Rational(4) * q * q);
      Speed::PieceSigns around;
      ASSERT_NO_THROW(around = s.piece_signs(RealAlgebraic(c - h), RealAlgebraic(c + h)));
      EXPECT_EQ(around.g, whole.g);
      EXPECT_EQ(around.component, whole.component);
    }
    const UniformityResult r = uniformity(p, SpeedKind::Angular);
    EXPECT_TRUE(agrees(r.mu, power_cusp_mu(k, c)));
  }
}

// Every method on a cusp curve gives what it gives on the curve with the
// factor removed by hand (same omega; that curve takes the ordinary path):
// uniformity, radical (and its independent direct uniformity), the optimal
// Moebius map, C0 with the cusp as a breakpoint, C0 with optimised
// breakpoints, the C1 target and the samples of the radical map.
TEST(Cusp, EveryMethodAgreesWithTheCurveWithoutTheFactor) {
  for (const Pair& pr : pairs()) {
    SCOPED_TRACE(pr.cusp);
    const Curve p = Curve::parse(pr.cusp), q = Curve::parse(pr.reduced);
    ASSERT_GT(common_factor_degree(p), 0);
    ASSERT_EQ(common_factor_degree(q), 0);
    const Speed sp(p, SpeedKind::Angular), sq(q, SpeedKind::Angular);
    ASSERT_EQ(sp.zeros().size(), sq.zeros().size());
    EXPECT_EQ(sp.zeros().empty(), !pr.omega_vanishes);
    for (std::size_t i = 0; i < sp.zeros().size(); ++i) {
      EXPECT_TRUE(sp.zeros()[i].t == sq.zeros()[i].t);
      EXPECT_EQ(sp.zeros()[i].multiplicity, sq.zeros()[i].multiplicity);
    }

    const UniformityResult up = uniformity(p, SpeedKind::Angular), uq = uniformity(q, SpeedKind::Angular);
    EXPECT_TRUE(agrees(up.mu, uq.mu));
    EXPECT_TRUE(agrees(up.u, uq.u));

    const RadicalResult rp = radical(p, SpeedKind::Angular), rq = radical(q, SpeedKind::Angular);
    ASSERT_EQ(rp.T.size(), rq.T.size());
    for (std::size_t i = 0; i < rp.T.size(); ++i) {
      EXPECT_TRUE(rp.T[i].t == rq.T[i].t);
      EXPECT_EQ(rp.T[i].multiplicity, rq.T[i].multiplicity);
    }
    EXPECT_TRUE(agrees(rp.u_radical, rq.u_radical));
    EXPECT_TRUE(agrees(rp.u_after, rq.u_after));
    EXPECT_TRUE(agrees(radical_direct_uniformity(rp, sp, 12, 4096), rp.u_after));

    const MoebiusResult mp = moebius_optimal(p, SpeedKind::Angular), mq = moebius_optimal(q, SpeedKind::Angular);
    EXPECT_TRUE(agrees(mp.alpha[0], mq.alpha[0]));
    EXPECT_TRUE(agrees(mp.u_after, mq.u_after));

    // the cusp as a breakpoint (or 1/2 where it is an end)
    const Rational mid = pr.c > Rational(0) && pr.c < Rational(1) ? pr.c : Rational(1, 2);
    const std::vector<RealAlgebraic> T{RealAlgebraic(0), RealAlgebraic(mid), RealAlgebraic(1)};
    const MoebiusResult cp = moebius_c0(p, SpeedKind::Angular, T), cq = moebius_c0(q, SpeedKind::Angular, T);
    EXPECT_TRUE(agrees(cp.u_after, cq.u_after));

    // optimised breakpoints: never worse than equal spacing (its contract)
    const MoebiusResult op = reparam_c0(p, SpeedKind::Angular, 3);
    const std::vector<RealAlgebraic> E{RealAlgebraic(0), RealAlgebraic(Rational(1, 3)), RealAlgebraic(Rational(2, 3)),
                                       RealAlgebraic(1)};
    const MoebiusResult ep = moebius_c0(p, SpeedKind::Angular, E), eq = moebius_c0(q, SpeedKind::Angular, E);
    EXPECT_TRUE(agrees(ep.u_after, eq.u_after));
    EXPECT_FALSE(arb_lt(op.u_after.get(), ep.u_after.get())) << op.u_after.str(20) << " < " << ep.u_after.str(20);

    if (!pr.omega_vanishes) {
      const MoebiusResult c1 = reparam_c1(p, SpeedKind::Angular, Rational(99, 100));
      EXPECT_TRUE(c1.target->reached);
      EXPECT_TRUE(arb_ge(c1.u_after.get(), exact(Rational(99, 100)).get())) << c1.u_after.str(20);
    }

    // samples of p o r and q o r for the same radical map r: same r(s) and speed
    const Samples a = sample(p, sp, Reparameterization(rp), 9, 12, 4096);
    const Samples b = sample(q, sq, Reparameterization(rq), 9, 12, 4096);
    ASSERT_EQ(a.after.size(), b.after.size());
    for (std::size_t i = 0; i < a.after.size(); ++i) {
      SCOPED_TRACE("sample " + std::to_string(i));
      EXPECT_TRUE(agrees(a.after[i].t, b.after[i].t));
      EXPECT_TRUE(agrees(a.after[i].speed, b.after[i].speed));
      EXPECT_TRUE(agrees(a.before[i].speed, b.before[i].speed));
    }
  }
}

// The parametric speed |p'| of a cusp curve keeps the common factor: its
// real roots are zeros of sigma (multiplicity k - 1 for (u^k, u^(k+1))),
// lifted by the radical method. For k = 2, mu = int |u| sqrt(4 + 9 u^2) du =
// ((4 + 9 u^2)^(3/2) - 8) / 27 from 0 to |u| on each side of c.
TEST(Cusp, ParametricSpeedVanishesAtTheCuspAndIsLifted) {
  std::mt19937_64 rng(7);
  const long n = test_support::iterations(6);
  for (long it = 0; it < n; ++it) {
    const Rational c = it == 0 ? Rational(1, 2) : it == 1 ? Rational(1) : random_position(rng);
    const std::string text = power_cusp(2, c);
    SCOPED_TRACE(text);
    const Curve p = Curve::parse(text);
    const Speed s(p, SpeedKind::Parametric);
    ASSERT_EQ(s.zeros().size(), 1u);
    EXPECT_TRUE(s.zeros()[0].t == RealAlgebraic(c));
    EXPECT_EQ(s.zeros()[0].multiplicity, 1);
    auto side = [](const Rational& u) {  // ((4 + 9 u^2)^(3/2) - 8) / 27
      Ball v = exact(Rational(4) + Rational(9) * u * u), r;
      arb_sqrt(r.get(), v.get(), kPrec);
      arb_mul(r.get(), r.get(), v.get(), kPrec);
      arb_sub_ui(r.get(), r.get(), 8, kPrec);
      arb_div_ui(r.get(), r.get(), 27, kPrec);
      return r;
    };
    Ball mu;
    arb_add(mu.get(), side(c).get(), side(Rational(1) - c).get(), kPrec);
    const UniformityResult u = uniformity(p, SpeedKind::Parametric);
    EXPECT_TRUE(agrees(u.mu, mu));
    const RadicalResult r = radical(p, SpeedKind::Parametric);
    EXPECT_TRUE(agrees(radical_direct_uniformity(r, s, 12, 4096), r.u_after));
    EXPECT_NO_THROW(reparam_c0(p, SpeedKind::Parametric, 3));
  }
}

namespace {

// L int_0^t f_i for integer polynomials f_i, with L = lcm(1, ..., top + 1)
// (top the largest degree) so that every result is an integer polynomial: a
// common scale, which the angular speed does not see and which multiplies
// the parametric one by L.
std::vector<Poly> scaled_integrals(const std::vector<Poly>& fs, Integer& L) {
  long top = 0;
  for (const Poly& f : fs) top = std::max(top, f.degree());
  fmpz_one(L.get());
  for (long i = 1; i <= top + 1; ++i) fmpz_lcm(L.get(), L.get(), Integer(i).get());
  std::vector<Poly> out;
  for (const Poly& f : fs) {
    Poly r;
    Integer c;
    for (long i = 0; i <= f.degree(); ++i) {
      fmpz_poly_get_coeff_fmpz(c.get(), f.get(), i);
      fmpz_mul(c.get(), c.get(), L.get());
      fmpz_divexact_si(c.get(), c.get(), i + 1);
      fmpz_poly_set_coeff_fmpz(r.get(), i + 1, c.get());
    }
    out.push_back(r);
  }
  return out;
}

Curve curve_of(const std::vector<Poly>& ps) {
  std::vector<RatFunc> comps;
  for (const Poly& p : ps) comps.emplace_back(p);
  return Curve(comps);
}

}  // namespace

// Random cusps: p' = h Y with h = (b t - a)^m (a cusp of order m at c = a / b
// in [0, 1]) and a random primitive direction Y (plane or space, degree 1 to
// 3). The exact oracle at rational points comes from Y alone: omega^2 =
// sum_{i<j} (Y_i' Y_j - Y_i Y_j')^2 / (sum Y_i^2)^2 (plane: omega itself,
// with the sign of each piece between zeros from piece_signs) and |p'|^2 =
// L^2 h^2 sum Y_i^2; mu and u agree with those of the curve int Y.
TEST(Cusp, RandomCuspsMatchTheirDirectionExactly) {
  std::mt19937_64 rng(424242);
  std::uniform_int_distribution<long> coef(-5, 5), deg(1, 3), den(1, 12), mult(1, 3), dim(2, 3);
  const long n = test_support::iterations(10);
  for (long it = 0; it < n; ++it) {
    const long b = den(rng), a = std::uniform_int_distribution<long>(0, b)(rng), m = mult(rng);
    const Rational c(a, b);
    std::vector<Poly> Y;
    bool ok = false;
    while (!ok) {
      Y.clear();
      const long d = dim(rng);
      for (long i = 0; i < d; ++i) {
        std::vector<long> k;
        for (long j = 0, e = deg(rng); j <= e; ++j) k.push_back(coef(rng));
        Y.emplace_back(k);
      }
      Poly g;
      for (const Poly& y : Y) g = gcd(g, y);
      ok = !g.is_zero() && g.degree() == 0;
      bool turns = false;  // not a straight line: some Y_i' Y_j - Y_i Y_j' != 0
      for (std::size_t i = 0; i < Y.size(); ++i)
        for (std::size_t j = i + 1; j < Y.size(); ++j)
          turns = turns || !(Y[i].derivative() * Y[j] - Y[i] * Y[j].derivative()).is_zero();
      ok = ok && turns;
    }
    const Poly h = Poly(std::vector<long>{-a, b}).pow(static_cast<unsigned long>(m));
    std::vector<Poly> f;
    for (const Poly& y : Y) f.push_back(h * y);
    Integer L, L0;
    const Curve p = curve_of(scaled_integrals(f, L)), q = curve_of(scaled_integrals(Y, L0));
    std::string text = p.str();
    SCOPED_TRACE(text + ", cusp of order " + std::to_string(m) + " at " + c.str());
    ASSERT_GE(common_factor_degree(p), m);
    const Speed sa(p, SpeedKind::Angular), sp(p, SpeedKind::Parametric);

    std::vector<Rational> ts{Rational(0), Rational(1), c};
    if (c - Rational(1, 997) > Rational(0)) ts.push_back(c - Rational(1, 997));
    if (c + Rational(1, 997) < Rational(1)) ts.push_back(c + Rational(1, 997));
    for (int k = 0; k < 5; ++k) ts.push_back(random_position(rng));
    const bool plane = Y.size() == 2;
    for (const Rational& t : ts) {
      SCOPED_TRACE("t = " + t.str());
      Rational F(0), S(0);
      for (std::size_t i = 0; i < Y.size(); ++i) {
        S = S + Y[i](t) * Y[i](t);
        for (std::size_t j = i + 1; j < Y.size(); ++j) {
          const Rational e = Y[i].derivative()(t) * Y[j](t) - Y[i](t) * Y[j].derivative()(t);
          F = F + e * e;
        }
      }
      const Rational w2 = F / (S * S);
      const Ball v2 = speed_at(sa, Speed::PieceSigns{}, t, true);
      EXPECT_TRUE(v2.is_finite() && v2.contains(w2)) << v2.str(30);
      const double d = sa.squared_double(to_double(t));
      EXPECT_TRUE(std::isfinite(d) && d >= 0) << d;
      const Rational Lr(L), ht = h(t);
      const Ball s2 = speed_at(sp, Speed::PieceSigns{}, t, true);
      EXPECT_TRUE(s2.is_finite() && s2.contains(Lr * Lr * ht * ht * S)) << s2.str(30);
      if (!plane) continue;
      // omega = |Y_1' Y_2 - Y_1 Y_2'| / S on the piece between zeros holding t
      const RealAlgebraic at(t);
      RealAlgebraic lo(0), hi(1);
      bool on_zero = false;
      for (const SpeedZero& z : sa.zeros()) {
        if (z.t == at) on_zero = true;
        else if (z.t < at) lo = z.t;
        else if (at < z.t && z.t < hi) hi = z.t;
      }
      if (on_zero) continue;
      const Rational e = Y[0].derivative()(t) * Y[1](t) - Y[0](t) * Y[1].derivative()(t);
      const Rational w = (e.sign() < 0 ? -e : e) / S;
      Speed::PieceSigns sg;
      ASSERT_NO_THROW(sg = sa.piece_signs(lo, hi));
      const Ball v = speed_at(sa, sg, t, false);
      EXPECT_TRUE(v.is_finite() && v.contains(w)) << v.str(30);
    }
    const UniformityResult up = uniformity(p, SpeedKind::Angular), uq = uniformity(q, SpeedKind::Angular);
    EXPECT_TRUE(agrees(up.mu, uq.mu));
    EXPECT_TRUE(agrees(up.u, uq.u));
  }
}
