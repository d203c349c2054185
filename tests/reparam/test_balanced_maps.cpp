// The Moebius, piecewise Moebius and radical methods on rational curves whose
// weights grow geometrically (scaling.hpp): they run on the balanced curve
// q = p o m and compose the map with m exactly. Properties checked on random
// curves: the composed map's data are p's own (its piece integrals equal the
// integrals computed directly on p, where that is feasible: ratios about
// 2^20 per degree), its points and speeds are q o r_q's, exact rational maps
// compose exactly (p(r(s)) = q(r_q(s)) in Q, C1 exactly), and huge ratios
// (the weights 1, 8e40, 1e82; 2^200 to 2^3000 per degree) finish
// with certified results that match closed forms. A regression to the
// unscaled computation fails the huge cases with BudgetExceeded (the
// TimeBudget is generous: these run in well under a second each).
#include <gtest/gtest.h>

#include <arb.h>

#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/scaling.hpp"

using namespace uniparam;

namespace {

constexpr double kBudgetSeconds = 120;
constexpr long kPrec = 256;

// Iterations of the random loops (UNIPARAM_TEST_ITERATIONS scales them).
int iterations(int base) {
  const char* e = std::getenv("UNIPARAM_TEST_ITERATIONS");
  const int f = e ? std::atoi(e) : 1;
  return base * (f > 0 ? f : 1);
}

Rational rpow(const Rational& x, long e) {
  Rational r(1);
  for (long i = 0; i < e; ++i) r = r * x;
  return r;
}

// A rational Bezier curve with the given control points and weights
// f_i lambda^i (or lambda^(n - i) when `falling`).
Curve bezier(const std::vector<std::vector<long>>& pts, const std::vector<long>& f, const Rational& lambda,
             bool falling) {
  std::vector<std::vector<Rational>> P;
  for (const auto& p : pts) P.push_back({Rational(p[0]), Rational(p[1])});
  const long n = static_cast<long>(pts.size()) - 1;
  std::vector<Rational> w;
  for (long i = 0; i <= n; ++i) w.push_back(Rational(f[static_cast<std::size_t>(i)]) * rpow(lambda, falling ? n - i : i));
  return BezierCurve(P, w).to_curve();
}

struct Case {
  Curve p;
  std::string what;
};

// Random geometric weights with a ratio lambda per degree whose log2 lies in
// [lo_bits, hi_bits] (not a power of 2), rising or falling; quadratics and
// an S-shaped cubic (its angular speed vanishes at an inflection); the
// first `shapes` of these three.
Case random_case(std::mt19937& rng, long lo_bits, long hi_bits, long shapes = 3) {
  std::uniform_int_distribution<long> bits(lo_bits, hi_bits), small(1, 5), coin(0, 1), shape(0, shapes - 1);
  const long e = bits(rng);
  Rational lambda(1);
  for (long i = 0; i < e; ++i) lambda = lambda * Rational(2);
  lambda = lambda * Rational(small(rng) + 5, 5);
  const bool falling = coin(rng) == 1;
  const long k = shape(rng);
  std::vector<std::vector<long>> pts;
  if (k == 0) pts = {{1, 0}, {1, 1}, {0, 1}};
  else if (k == 1) pts = {{0, 0}, {small(rng), 3}, {4, small(rng) - 3}};
  else pts = {{0, 0}, {1, 2}, {2, -2}, {3, 0}};
  std::vector<long> f;
  for (std::size_t i = 0; i < pts.size(); ++i) f.push_back(small(rng));
  std::string what = "shape " + std::to_string(k) + ", lambda = " + lambda.str() + (falling ? " falling" : " rising") +
                     ", f =";
  for (long x : f) what += " " + std::to_string(x);
  return Case{bezier(pts, f, lambda, falling), what};
}

Ball ball(const RealAlgebraic& x) { return x.to_ball(kPrec); }

// m(tau) = a tau / (a tau + b (1 - tau)) on balls.
Ball m_of(const BalancedCurve& bal, const Ball& tau) {
  Ball at, bt, d;
  arb_mul_fmpz(at.get(), tau.get(), bal.a.get(), kPrec);
  arb_sub_si(bt.get(), tau.get(), 1, kPrec);
  arb_neg(bt.get(), bt.get());
  arb_mul_fmpz(bt.get(), bt.get(), bal.b.get(), kPrec);
  arb_add(d.get(), at.get(), bt.get(), kPrec);
  arb_div(at.get(), at.get(), d.get(), kPrec);
  return at;
}

bool overlaps(const Ball& x, const Ball& y) { return arb_overlaps(x.get(), y.get()); }
bool overlaps(const std::vector<Ball>& x, const std::vector<Ball>& y) {
  if (x.size() != y.size()) return false;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (!overlaps(x[i], y[i])) return false;
  return true;
}

// The u of the piecewise Moebius map with r's T, S and alphas, from piece
// integrals computed directly on p (no balancing, no data of r but its map):
// mu^2 / sum_i (k_i A_i + B_i + C_i / k_i) / ds_i, k_i = (1 - alpha_i) / alpha_i.
Ball direct_u_after(const Speed& sp, const MoebiusResult& r, const Ball& mu, std::vector<PieceIntegrals>* out) {
  Ball total(0);
  for (std::size_t i = 0; i < r.pieces(); ++i) {
    const PieceIntegrals I = piece_integrals(sp, Breakpoint{r.T[i].t}, Breakpoint{r.T[i + 1].t}, 80, 8192);
    Ball k, f, t, ds;
    arb_sub_si(k.get(), r.alpha[i].get(), 1, kPrec);
    arb_neg(k.get(), k.get());
    arb_div(k.get(), k.get(), r.alpha[i].get(), kPrec);
    arb_mul(f.get(), k.get(), I.A.get(), kPrec);
    arb_add(f.get(), f.get(), I.B.get(), kPrec);
    arb_div(t.get(), I.C.get(), k.get(), kPrec);
    arb_add(f.get(), f.get(), t.get(), kPrec);
    arb_sub(ds.get(), r.S[i + 1].get(), r.S[i].get(), kPrec);
    arb_div(f.get(), f.get(), ds.get(), kPrec);
    arb_add(total.get(), total.get(), f.get(), kPrec);
    if (out) out->push_back(I);
  }
  Ball u;
  arb_sqr(u.get(), mu.get(), kPrec);
  arb_div(u.get(), u.get(), total.get(), kPrec);
  return u;
}

// t = r(s) of a rational Moebius map, exactly.
Rational exact_r(const MoebiusResult& r, const Rational& s) {
  std::size_t i = 0;
  while (i + 1 < r.pieces() && s > r.exact->S[i + 1]) ++i;
  const Rational& a = r.exact->alpha[i];
  const Rational u = (s - r.exact->S[i]) / (r.exact->S[i + 1] - r.exact->S[i]);
  return r.exact->T[i] + (r.exact->T[i + 1] - r.exact->T[i]) * (Rational(1) - a) * u / (a + (Rational(1) - a - a) * u);
}

// The checks every balanced Moebius result must pass (ball form).
void check_moebius_map(const Curve& p, SpeedKind kind, const MoebiusResult& r, const Options& o,
                       const std::string& what) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(r.balanced) << "the curve's weights grow geometrically: the map must be composed";
  const BalancedCurve& bal = *r.balanced->curve;
  const MoebiusResult& rq = *r.balanced->on;
  const Speed sp(p, kind), sq(bal.q, kind);
  ASSERT_EQ(r.pieces(), rq.pieces());
  // T = m(T_q) exactly, increasing from 0 to 1
  for (std::size_t i = 0; i <= r.pieces(); ++i) {
    EXPECT_TRUE(overlaps(ball(r.T[i].t), m_of(bal, ball(rq.T[i].t)))) << i;
    if (i > 0) EXPECT_LT(compare(r.T[i - 1].t, r.T[i].t), 0);
  }
  EXPECT_EQ(compare(r.T.front().t, RealAlgebraic(0)), 0);
  EXPECT_EQ(compare(r.T.back().t, RealAlgebraic(1)), 0);
  // u_before is p's; mu invariant
  const UniformityResult u = uniformity(p, kind, o);
  EXPECT_TRUE(overlaps(r.u_before, u.u));
  EXPECT_TRUE(overlaps(r.mu, u.mu));
  for (const Ball* x : {&r.mu, &r.u_before, &r.u_after}) EXPECT_TRUE(x->meets_digits(o.digits)) << x->str(20);
  for (const Ball& a : r.alpha) {
    EXPECT_TRUE(a.meets_digits(o.digits)) << a.str(20);
    EXPECT_TRUE(arb_is_positive(a.get()));
    Ball oma;
    arb_sub_si(oma.get(), a.get(), 1, kPrec);
    EXPECT_TRUE(arb_is_negative(oma.get())) << "1 - alpha must stay resolvable: " << a.str(30);
  }
  // points and speeds: p(r(s)) = q(r_q(s)) and sigma_{p o r} = sigma_{q o r_q}
  for (long j = 0; j <= 12; ++j) {
    const Ball s(Rational(j, 12), kPrec);
    const Ball t = eval_r(r, s, kPrec);
    EXPECT_TRUE(overlaps(t, m_of(bal, eval_r(rq, s, kPrec)))) << j;
    EXPECT_TRUE(overlaps(p.eval(t, kPrec), bal.q.eval(eval_r(rq, s, kPrec), kPrec))) << j;
    EXPECT_TRUE(overlaps(eval_point(p, r, s, kPrec), p.eval(t, kPrec))) << j;
    EXPECT_TRUE(overlaps(eval_speed(r, sp, s, kPrec), eval_speed(rq, sq, s, kPrec))) << j;
  }
}

}  // namespace

// Must show: for quadratics at ratios of 2^18 to 2^20 per degree, where the
// unscaled computation is feasible, the composed map's piece integrals A, B, C, L, M
// and alphas equal those integrated directly on p over its breakpoints, and
// its u_after equals the u of its (T, S, alpha) computed from those direct
// integrals, for the single, the C0 (given and optimised breakpoints) and
// the C1 map (where its breakpoints are rational), both speeds.
TEST(BalancedMaps, ModerateRatiosMatchDirectIntegralsOnP) {
  TimeBudget budget(kBudgetSeconds * 4);
  std::mt19937 rng(20261203);
  Options o;
  for (int it = 0; it < iterations(3); ++it) {
    const Case c = random_case(rng, 18, 19, 2);
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const std::string what = c.what + (kind == SpeedKind::Angular ? ", angular" : ", parametric");
      SCOPED_TRACE(what);
      const Speed sp(c.p, kind);
      const Ball mu = uniformity(c.p, kind, o).mu;
      std::vector<MoebiusResult> maps;
      maps.push_back(moebius_optimal(c.p, kind, o));
      maps.push_back(moebius_c0(c.p, kind, {RealAlgebraic(0), RealAlgebraic(Rational(1, 1 << 20)),
                                             RealAlgebraic(Rational(1, 3)), RealAlgebraic(1)}, o));
      maps.push_back(reparam_c0(c.p, kind, 3, o));
      maps.push_back(reparam_c1(c.p, kind, Rational(99, 100), o, 4));
      for (const MoebiusResult& r : maps) {
        check_moebius_map(c.p, kind, r, o, what);
        // the direct integrals over p's pieces (rational breakpoints: the C1
        // map's irrational ones are checked through q in check_moebius_map)
        bool rational_T = true;
        for (const Breakpoint& b : r.T) rational_T = rational_T && b.t.is_rational();
        if (!rational_T) continue;
        std::vector<PieceIntegrals> direct;
        EXPECT_TRUE(overlaps(r.u_after, direct_u_after(sp, r, mu, &direct))) << r.u_after.str(20);
        if (r.continuity != Continuity::C0) continue;
        for (std::size_t i = 0; i < r.pieces(); ++i) {
          const PieceIntegrals& I = r.integrals[i];
          const PieceIntegrals& D = direct[i];
          EXPECT_TRUE(overlaps(I.A, D.A)) << i << ": " << I.A.str(20) << " vs " << D.A.str(20);
          EXPECT_TRUE(overlaps(I.B, D.B)) << i;
          EXPECT_TRUE(overlaps(I.C, D.C)) << i << ": " << I.C.str(20) << " vs " << D.C.str(20);
          EXPECT_TRUE(overlaps(I.L, D.L)) << i;
          EXPECT_TRUE(overlaps(I.M, D.M)) << i;
          EXPECT_TRUE(overlaps(I.alpha, D.alpha)) << i;
          EXPECT_TRUE(overlaps(r.alpha[i], D.alpha)) << i;
        }
      }
    }
  }
}

// Must show: the radical map r = m o r_q at moderate ratios: its breakpoints
// are p's (every zero of p's speed, with its multiplicity; each breakpoint
// m(T_q)), and its points and speeds evaluated from p's speed and the
// pieces (the outer Moebius maps and the radical ends' cancelled singular
// factors included) are q o r_q's (ratios up to 2^200).
TEST(BalancedMaps, RadicalMapIsPsOwn) {
  TimeBudget budget(kBudgetSeconds * 4);
  std::mt19937 rng(31415);
  Options o;
  bool saw_zero = false;
  for (int it = 0; it < iterations(4); ++it) {
    const Case c = it % 2 == 0 ? random_case(rng, 16, 20) : random_case(rng, 20, 200);
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      SCOPED_TRACE(c.what + (kind == SpeedKind::Angular ? ", angular" : ", parametric"));
      const RadicalResult r = radical(c.p, kind, o);
      ASSERT_TRUE(r.balanced);
      const RadicalResult& rq = *r.balanced->on;
      const BalancedCurve& bal = *r.balanced->curve;
      const Speed sp(c.p, kind), sq(bal.q, kind);
      ASSERT_EQ(r.T.size(), rq.T.size());
      ASSERT_EQ(r.outer_k.size(), r.pieces());
      std::size_t zeros = 0;
      for (std::size_t i = 0; i < r.T.size(); ++i) {
        EXPECT_TRUE(overlaps(ball(r.T[i].t), m_of(bal, ball(rq.T[i].t))));
        EXPECT_EQ(r.T[i].multiplicity, rq.T[i].multiplicity);
        if (r.T[i].multiplicity > 0) {
          ASSERT_LT(zeros, sp.zeros().size());
          EXPECT_EQ(compare(r.T[i].t, sp.zeros()[zeros].t), 0);
          EXPECT_EQ(r.T[i].multiplicity, sp.zeros()[zeros].multiplicity);
          ++zeros;
          saw_zero = true;
        }
      }
      EXPECT_EQ(zeros, sp.zeros().size());
      EXPECT_TRUE(overlaps(r.u_before, uniformity(c.p, kind, o).u));
      for (long j = 0; j <= 16; ++j) {
        const Ball z(Rational(j, 16), kPrec);
        const Ball t = eval_r(r, z, kPrec);
        EXPECT_TRUE(overlaps(t, m_of(bal, eval_r(rq, z, kPrec)))) << j;
        EXPECT_TRUE(overlaps(c.p.eval(t, kPrec), bal.q.eval(eval_r(rq, z, kPrec), kPrec))) << j;
        EXPECT_TRUE(overlaps(eval_speed(r, sp, z, kPrec), eval_speed(rq, sq, z, kPrec))) << j;
      }
      // refining keeps the composition
      const RadicalResult x = refine_radical_data(sp, r, o.digits + 10, o.max_prec);
      ASSERT_TRUE(x.balanced);
      for (std::size_t i = 0; i < x.pieces(); ++i) EXPECT_TRUE(overlaps(x.outer_k[i], r.outer_k[i]));
      EXPECT_TRUE(overlaps(x.Z, r.Z));
    }
  }
  EXPECT_TRUE(saw_zero) << "no case had a zero of the speed: the radical pieces were not exercised";
}

// Must show: exact rational maps compose exactly. For each Moebius method's
// make_rational on random geometric weights up to 2^300 per degree: t = r(s)
// from p's rational data equals m(r_q(s)) from q's, and p(t) = q(r_q(s)),
// exactly in Q at random rational s; the C1 maps satisfy the C1 condition
// (Delta t_i / Delta s_i) k_i^-1 = (Delta t_{i+1} / Delta s_{i+1}) k_{i+1}
// exactly on p's data; refine_moebius_data keeps the map.
TEST(BalancedMaps, RationalMapsComposeExactly) {
  TimeBudget budget(kBudgetSeconds * 4);
  std::mt19937 rng(2718);
  std::uniform_int_distribution<long> num(0, 1000);
  Options o;
  for (int it = 0; it < iterations(3); ++it) {
    const Case c = random_case(rng, 18, 300);
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const std::string what = c.what + (kind == SpeedKind::Angular ? ", angular" : ", parametric");
      SCOPED_TRACE(what);
      const Speed sp(c.p, kind);
      for (const MoebiusResult& r0 : {reparam_c0(c.p, kind, 3, o), reparam_c1(c.p, kind, Rational(99, 100), o, 16)}) {
        check_moebius_map(c.p, kind, r0, o, what);
        const MoebiusResult x = refine_moebius_data(sp, r0, o.digits + 10, o.max_prec);
        ASSERT_TRUE(x.balanced);
        EXPECT_TRUE(overlaps(x.alpha, r0.alpha));
        EXPECT_TRUE(overlaps(x.S, r0.S));
        const MoebiusResult r = make_rational(c.p, r0, 8, o);
        ASSERT_TRUE(r.exact.has_value() && r.balanced && r.balanced->on->exact.has_value());
        check_moebius_map(c.p, kind, r, o, what + ", rational");
        const MoebiusResult& rq = *r.balanced->on;
        const BalancedCurve& bal = *r.balanced->curve;
        EXPECT_EQ(r.exact->S, rq.exact->S);
        for (int j = 0; j < 8; ++j) {
          const Rational s(num(rng), 1000);
          const Rational t = exact_r(r, s), tau = exact_r(rq, s);
          const Rational at = Rational(bal.a) * tau;
          EXPECT_EQ(t, at / (at + Rational(bal.b) * (Rational(1) - tau))) << s.str();
          for (std::size_t k = 0; k < c.p.dimension(); ++k)
            EXPECT_EQ(c.p.components()[k](t), bal.q.components()[k](tau)) << s.str();
        }
        if (r.continuity == Continuity::C1)
          for (std::size_t i = 0; i + 1 < r.pieces(); ++i) {
            auto k = [&](std::size_t j) { return (Rational(1) - r.exact->alpha[j]) / r.exact->alpha[j]; };
            auto rho = [&](std::size_t j) {
              return (r.exact->T[j + 1] - r.exact->T[j]) / (r.exact->S[j + 1] - r.exact->S[j]);
            };
            EXPECT_EQ(rho(i) / k(i), rho(i + 1) * k(i + 1)) << i;
          }
        // the exact u of the rational map, from direct integrals on p where feasible
        if (balance_bits(bal) <= 24 && kind == SpeedKind::Parametric) {
          const Ball mu = uniformity(c.p, kind, o).mu;
          EXPECT_TRUE(overlaps(r.u_after, direct_u_after(sp, r, mu, nullptr)));
        }
      }
    }
  }
}

// Must show: the curve (the quarter circle's control points with
// weights 1, 8e40, 1e82) and circle arcs with weights up to 2^3000 per
// degree finish under the budget with every method, certified; for the arc
// of angle 2 atan(4/3) (control points (1, 0), (1, 4/3), (-7/25, 24/25),
// weights 1, 3/5 lambda, lambda^2) mu = 2 atan(4/3) for both speeds, every
// point p(r(s)) lies on the unit circle and both uniformities after are at
// most 1 and at least the one before.
TEST(BalancedMaps, HugeRatiosFinishCertified) {
  TimeBudget budget(kBudgetSeconds * 4);
  Options o;
  std::vector<Case> cases;
  cases.push_back(Case{BezierCurve::parse("[[1,0],[1,1],[0,1]]", "[1,8e40,1e82]").to_curve(), "the issue's weights"});
  for (long e : {200L, 1000L, 3000L}) {
    Rational lambda(1);
    for (long i = 0; i < e; ++i) lambda = lambda * Rational(2);
    lambda = lambda * Rational(7, 5);
    for (bool falling : {false, true}) {
      std::vector<std::vector<Rational>> P{{Rational(1), Rational(0)}, {Rational(1), Rational(4, 3)},
                                           {Rational(-7, 25), Rational(24, 25)}};
      std::vector<Rational> w{Rational(1), Rational(3, 5) * lambda, lambda * lambda};
      if (falling) std::swap(w[0], w[2]);
      cases.push_back(Case{BezierCurve(P, w).to_curve(), "arc, 2^" + std::to_string(e) + (falling ? " falling" : "")});
    }
  }
  Ball arc;
  {
    Ball x(Rational(4, 3), kPrec);
    arb_atan(arc.get(), x.get(), kPrec);
    arb_mul_2exp_si(arc.get(), arc.get(), 1);
  }
  for (std::size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    for (SpeedKind kind : {SpeedKind::Parametric, SpeedKind::Angular}) {
      const std::string what = c.what + (kind == SpeedKind::Angular ? ", angular" : ", parametric");
      SCOPED_TRACE(what);
      std::vector<MoebiusResult> maps{moebius_optimal(c.p, kind, o), reparam_c0(c.p, kind, 3, o),
                                      reparam_c1(c.p, kind, Rational(99, 100), o, 16)};
      maps.push_back(make_rational(c.p, maps[1], 8, o));
      const RadicalResult rad = radical(c.p, kind, o);
      ASSERT_TRUE(rad.balanced);
      std::vector<const Ball*> after{&rad.u_after};
      for (const MoebiusResult& r : maps) {
        check_moebius_map(c.p, kind, r, o, what);
        after.push_back(&r.u_after);
      }
      Ball one(1);
      for (const Ball* u : after) {
        EXPECT_TRUE(u->meets_digits(o.digits));
        EXPECT_FALSE(arb_gt(u->get(), one.get())) << u->str(20);
        EXPECT_FALSE(arb_lt(u->get(), rad.u_before.get())) << u->str(20);
      }
      if (ci == 0) continue;
      EXPECT_TRUE(overlaps(rad.mu, arc)) << rad.mu.str(20);
      for (long j = 0; j <= 10; ++j) {
        const Ball s(Rational(j, 10), kPrec);
        std::vector<std::vector<Ball>> pts{eval_point(c.p, rad, s, kPrec)};
        for (const MoebiusResult& r : maps) pts.push_back(eval_point(c.p, r, s, kPrec));
        for (const auto& x : pts) {
          Ball rr, y2;
          arb_sqr(rr.get(), x[0].get(), kPrec);
          arb_sqr(y2.get(), x[1].get(), kPrec);
          arb_add(rr.get(), rr.get(), y2.get(), kPrec);
          EXPECT_TRUE(arb_contains_si(rr.get(), 1)) << j << ": " << rr.str(20);
          EXPECT_LT(arf_cmpabs_2exp_si(arb_midref(rr.get()), 1), 0);
          Ball w;
          arb_sub_si(w.get(), rr.get(), 1, kPrec);
          EXPECT_LT(mag_cmp_2exp_si(arb_radref(w.get()), -40), 0) << "p(r(s)) must be accurate: " << rr.str(20);
        }
      }
    }
  }
}
