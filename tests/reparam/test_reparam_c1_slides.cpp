// reparam_c1's refinement rule on random curves: every breakpoint that the
// slides' rule adds (found in floating point from the uncertified draft) must
// be a genuine sign change of the exact slides' equation of its piece, and
// the certified result must be C1 and honest about the target.
//
// The oracle, derived from docs/math.md section 3 (ImUp, Yang, Wang, Hong 2014),
// independently of reparam/src/moebius_c1.cpp: on a piece [a, b] with
// parameter alpha the slides' equation is
//     F(t) = sigma'(t) (b - a) [alpha t~ + (1 - alpha)(1 - t~)] - 2 sigma(t) (1 - 2 alpha),
// t~ = (t - a) / (b - a), i.e. (b - a)[...] = l(t) = alpha (t - a) + (1 - alpha)(b - t).
// With sigma^2 = G / H exactly (Speed::squared(), a canonical rational
// function), 2 sigma F = (sigma^2)' l - 4 (1 - 2 alpha) sigma^2, so
//     H^2 2 sigma F = P(t) := (G' H - G H') l(t) - 4 (1 - 2 alpha) G H,
// and where sigma > 0 (G != 0) the sign of F is the sign of P. P is evaluated
// at rational t with the polynomials G, G', H, H' exactly in Q; only l(t),
// whose ends a, b may be algebraic numbers, is an Arb ball (256 bits), and a
// sign counts only if the ball certifies it. No double, no jets, no quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "support/curves.hpp"
#include "support/iterations.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::iterations;
using uniparam::test_support::random_poly;

namespace {

constexpr long kPrec = 256;

// The certified sign of P(x) (0 when the ball does not decide it).
int slides_sign(const Poly& G, const Poly& H, const RealAlgebraic& a, const RealAlgebraic& b,
                const Rational& alpha, const Rational& x) {
  const Rational g = G(x), h = H(x), dg = G.derivative()(x), dh = H.derivative()(x);
  const Rational d = dg * h - g * dh, e = Rational(4) * (Rational(1) - Rational(2) * alpha) * g * h;
  // l(x) = alpha (x - a) + (1 - alpha)(b - x)
  Ball l, t;
  const Ball al(alpha, kPrec), one_minus(Rational(1) - alpha, kPrec), xb(x, kPrec);
  arb_sub(l.get(), xb.get(), a.to_ball(kPrec).get(), kPrec);
  arb_mul(l.get(), l.get(), al.get(), kPrec);
  arb_sub(t.get(), b.to_ball(kPrec).get(), xb.get(), kPrec);
  arb_addmul(l.get(), t.get(), one_minus.get(), kPrec);
  Ball p;
  arb_mul(p.get(), l.get(), Ball(d, kPrec).get(), kPrec);
  arb_sub(p.get(), p.get(), Ball(e, kPrec).get(), kPrec);
  return p.certainly_positive() ? 1 : p.certainly_negative() ? -1 : 0;
}

Rational approx(const RealAlgebraic& x) { return mid_rational(x.to_ball(kPrec)); }

// Random low-degree curves (the test skips those the method rejects: cusps,
// poles, DomainError).
struct Case {
  std::vector<RatFunc> comps;
  SpeedKind kind;
};

Case random_case(std::mt19937_64& rng, int variant) {
  switch (variant % 4) {
    case 0:  // plane polynomial cubic, angular speed
      return {{RatFunc(random_poly(rng, 3, 6)), RatFunc(random_poly(rng, 3, 6))}, SpeedKind::Angular};
    case 1:  // plane polynomial cubic, parametric speed
      return {{RatFunc(random_poly(rng, 3, 6)), RatFunc(random_poly(rng, 3, 6))}, SpeedKind::Parametric};
    case 2: {  // plane rational quadratic over a denominator positive on [0, 1], angular
      Poly q = random_poly(rng, 2, 3);
      q = q * q + Poly(std::vector<long>{1});
      return {{RatFunc(random_poly(rng, 2, 6)) / RatFunc(q), RatFunc(random_poly(rng, 2, 6)) / RatFunc(q)},
              SpeedKind::Angular};
    }
    default:  // space polynomial curve of degree 2-3, angular
      return {{RatFunc(random_poly(rng, 3, 5)), RatFunc(random_poly(rng, 2, 5)), RatFunc(random_poly(rng, 3, 5))},
              SpeedKind::Angular};
  }
}

// For every breakpoint q the slides' rule added in a piece [a, b] of width h,
// the exact slides' equation of that piece (with the alpha the rule used)
// takes opposite certified signs at q - delta and q + delta, and sigma has no
// zero in [q - delta, q + delta] (so the sign change is one of F, not the jump
// of sigma' at a zero of sigma, which the rule must drop).
//
// The tolerance delta = 1.1e-6 h: the rule rounds its double root on purpose
// to the simplest rational within 1e-6 h (moebius_c1.cpp, refine), so the
// exact root can be 1e-6 h away from q for that reason alone; the rest,
// 1e-7 h, is for the floating point: Newton to 1e-13 h on E evaluated in
// double from jets, the piece's ends and alpha rounded within 1e-12 (h resp.
// absolute) -- each ~1e-12 h, so 1e-7 h leaves 10^5 for ill-conditioned
// roots. A root of a wrong equation is generically off by a fraction of h.
// (Measured: at most 1.0e-6 h over 2700 breakpoints. With the ends rounded
// within 1e-9 absolute instead, 1.2e-6 h on a piece of width
// 0.04: seed 5086 at UNIPARAM_TEST_MULTIPLIER=30.)
//
// Also: the draft's alpha for the returned T agrees with the certified one
// within 1e-10 (the draft's integrals are good to ~1e-13 relative, alpha is a
// well-conditioned function of them and the C1 chain over <= 60 pieces
// multiplies the errors by at most ~60: ~1e-11; measured <= 5e-13); the
// result is C1 (one-sided derivatives of neighbouring pieces overlap at every
// interior joint, and are exactly equal after make_rational); target.reached
// iff u_after >= target is certified.
void check_slides_rule(long n, unsigned long seed_base, const Rational& target, long max_pieces) {
  long checked = 0, curves = 0, bisected = 0;
  double worst_offset = 0, worst_alpha = 0, min_h = 1;
  for (long seed = 0; seed < n; ++seed) {
    std::mt19937_64 rng(seed_base + static_cast<unsigned long>(seed));
    const Case cs = random_case(rng, static_cast<int>(seed));
    std::unique_ptr<Curve> c;
    try {
      c = std::make_unique<Curve>(cs.comps);
      Speed probe(*c, cs.kind);
      if (probe.identically_zero()) continue;
    } catch (const DomainError&) {
      continue;
    }
    detail::C1Trace trace;
    MoebiusResult r;
    try {
      r = detail::reparam_c1_traced(*c, cs.kind, target, {}, max_pieces, &trace);
    } catch (const DomainError&) {
      continue;  // non-regular in [0, 1]
    }
    ++curves;
    const std::string name = c->str() + " " + to_string(cs.kind);
    const Speed s(*c, cs.kind);
    const Poly G = s.squared().num(), H = s.squared().den();
    bisected += static_cast<long>(trace.bisections.size());

    for (const auto& bp : trace.slides) {
      ASSERT_LT(bp.round, trace.rounds.size());
      const auto& T = trace.rounds[bp.round].T;
      ASSERT_LT(bp.piece + 1, T.size());
      EXPECT_EQ(compare(bp.a, T[bp.piece]), 0);
      EXPECT_EQ(compare(bp.b, T[bp.piece + 1]), 0);
      EXPECT_LT(compare(bp.a, RealAlgebraic(bp.t)), 0);
      EXPECT_LT(compare(RealAlgebraic(bp.t), bp.b), 0);
      // the rule's alpha is the draft's
      const double da = std::fabs(trace.rounds[bp.round].alpha[bp.piece] -
                                  arf_get_d(arb_midref(Ball(bp.alpha, 64).get()), ARF_RND_NEAR));
      EXPECT_LE(da, 2e-12) << name;  // rounded within 1e-12, plus double rounding
      const Rational h = approx(bp.b) - approx(bp.a);
      const Rational delta = h * Rational(11, 10000000);
      min_h = std::min(min_h, arf_get_d(arb_midref(Ball(h, 64).get()), ARF_RND_NEAR));
      const Rational lo = bp.t - delta, hi = bp.t + delta;
      const int sl = slides_sign(G, H, bp.a, bp.b, bp.alpha, lo), sh = slides_sign(G, H, bp.a, bp.b, bp.alpha, hi);
      EXPECT_TRUE(sl != 0 && sh != 0 && sl == -sh)
          << name << ": round " << bp.round << " piece " << bp.piece << " breakpoint " << bp.t.str()
          << " alpha " << bp.alpha.str() << ": signs " << sl << ", " << sh << " at t -+ 1.1e-6 h, h = " << Ball(h, 64).str(6);
      EXPECT_TRUE(G(lo).sign() != 0 && G(hi).sign() != 0 && count_real_roots(G, lo, hi) == 0)
          << name << ": breakpoint " << bp.t.str() << " at a zero of sigma";
      ++checked;
      if (sl != 0 && sh != 0 && sl == -sh) {  // where is the exact root? (for the record)
        Rational x0 = lo, x1 = hi;
        for (int it = 0; it < 40; ++it) {
          const Rational m = (x0 + x1) * Rational(1, 2);
          const int sm = slides_sign(G, H, bp.a, bp.b, bp.alpha, m);
          if (sm == 0) {  // P(m) = 0 exactly (l(m) rational) or undecided: the root is (about) m
            x0 = x1 = m;
            break;
          }
          (sm == sl ? x0 : x1) = m;
        }
        const Rational off = (x0 - bp.t) / h;
        worst_offset = std::max(worst_offset, std::fabs(arf_get_d(arb_midref(Ball(off, 64).get()), ARF_RND_NEAR)));
      }
    }

    // the returned T had a draft; its alpha agrees with the certified one
    const auto it = std::find_if(trace.rounds.begin(), trace.rounds.end(), [&](const detail::C1Trace::Round& rd) {
      if (rd.T.size() != r.T.size()) return false;
      for (std::size_t i = 0; i < rd.T.size(); ++i)
        if (compare(rd.T[i], r.T[i].t) != 0) return false;
      return true;
    });
    ASSERT_NE(it, trace.rounds.end()) << name;
    for (std::size_t i = 0; i < r.alpha.size(); ++i) {
      Ball diff;
      Ball dr;
      arb_set_d(dr.get(), it->alpha[i]);
      arb_sub(diff.get(), r.alpha[i].get(), dr.get(), 128);
      arb_abs(diff.get(), diff.get());
      worst_alpha = std::max(worst_alpha, arf_get_d(arb_midref(diff.get()), ARF_RND_UP));
      EXPECT_TRUE(arb_le(diff.get(), Ball(Rational(1, 10000000000L), 64).get()))
          << name << " piece " << i << ": draft alpha " << it->alpha[i] << " certified " << r.alpha[i].str(20);
    }

    // C1 at every interior joint: rho_i alpha_i / (1 - alpha_i) = rho_{i+1} (1 - alpha_{i+1}) / alpha_{i+1}
    EXPECT_EQ(r.continuity, Continuity::C1);
    ASSERT_EQ(r.S.size(), r.T.size());
    for (std::size_t i = 0; i + 1 < r.pieces(); ++i) {
      auto rho = [&](std::size_t j) {
        Ball dt, ds, q;
        arb_sub(dt.get(), r.T[j + 1].t.to_ball(kPrec).get(), r.T[j].t.to_ball(kPrec).get(), kPrec);
        arb_sub(ds.get(), r.S[j + 1].get(), r.S[j].get(), kPrec);
        arb_div(q.get(), dt.get(), ds.get(), kPrec);
        return q;
      };
      Ball left = rho(i), right = rho(i + 1), k;
      Ball one(1);
      arb_sub(k.get(), one.get(), r.alpha[i].get(), kPrec);
      arb_div(k.get(), r.alpha[i].get(), k.get(), kPrec);
      arb_mul(left.get(), left.get(), k.get(), kPrec);
      arb_sub(k.get(), one.get(), r.alpha[i + 1].get(), kPrec);
      arb_div(k.get(), k.get(), r.alpha[i + 1].get(), kPrec);
      arb_mul(right.get(), right.get(), k.get(), kPrec);
      EXPECT_TRUE(arb_overlaps(left.get(), right.get())) << name << " joint " << i + 1;
    }
    const MoebiusResult q = make_rational(*c, r, 8, {});
    for (std::size_t i = 0; i + 1 < q.pieces(); ++i) {
      const Rational rl = (q.exact->T[i + 1] - q.exact->T[i]) / (q.exact->S[i + 1] - q.exact->S[i]);
      const Rational rr = (q.exact->T[i + 2] - q.exact->T[i + 1]) / (q.exact->S[i + 2] - q.exact->S[i + 1]);
      EXPECT_EQ(rl * q.exact->alpha[i] / (Rational(1) - q.exact->alpha[i]),
                rr * (Rational(1) - q.exact->alpha[i + 1]) / q.exact->alpha[i + 1])
          << name << " exact joint " << i + 1;
    }

    // honest about the target
    const bool certified = arb_ge(r.u_after.get(), Ball(target, 128).get());
    EXPECT_EQ(r.target->reached, certified) << name << " u = " << r.u_after.str(15);
  }
  std::printf("[ slides ] %ld curves, %ld slides breakpoints checked, %ld bisections; max |root - t| / h = %.3g, "
              "min h = %.3g, max |draft alpha - certified alpha| = %.3g\n",
              curves, checked, bisected, worst_offset, min_h, worst_alpha);
  EXPECT_GE(curves, n / 2);
  EXPECT_GT(checked, 0);
}

}  // namespace

TEST(ReparamC1Slides, AddedBreakpointsAreSignChangesOfTheExactSlidesEquation) {
  check_slides_rule(iterations(8), 1000, Rational(999, 1000), 12);
}

// Many small pieces (h down to ~1e-3 and below): the rounding of the piece's
// ends must stay small relative to h too.
TEST(ReparamC1Slides, AddedBreakpointsOnSmallPiecesAreSignChangesToo) {
  check_slides_rule(iterations(3), 5000, Rational(999999, 1000000), 60);
}
