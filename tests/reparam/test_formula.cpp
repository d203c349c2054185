// The printed Moebius maps of radical and moebius (formula.hpp): parsed back
// exactly, each keeps the shape of its certified map, also where alpha is
// closer to 0 or 1 than the printed digits, where an expanded
// (A z + B) / (C z + D) degenerates to a constant.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "support/curves.hpp"
#include "uniparam/core/decimal.hpp"
#include "uniparam/core/parser.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;

namespace {

// The rational a printed decimal of b stands for (the midpoint the formulas print).
Rational printed(const Ball& b, long digits) {
  const RatFunc v = parse_expression(format_decimal(b, digits, Format::Text));
  return v(Rational(0));
}

// A printed text formula in the variable v, read back as an exact rational function of t.
RatFunc read_formula(std::string f, char v) {
  std::replace(f.begin(), f.end(), v, 't');
  return parse_expression(f);
}

Ball sub(const Ball& a, const Ball& b, long prec) {
  Ball r;
  arb_sub(r.get(), a.get(), b.get(), prec);
  return r;
}

// True when the exact rational q lies within rel * |b| of b (b's radius included).
bool near(const Rational& q, const Ball& b, double rel, long prec) {
  Ball d = sub(Ball(q, prec), b, prec), tol, r;
  arb_abs(tol.get(), b.get());
  arb_set_d(r.get(), rel);
  arb_mul(tol.get(), tol.get(), r.get(), prec);
  arb_abs(d.get(), d.get());
  return arb_le(d.get(), tol.get()) != 0;
}

// Checks the printed map f of the variable v on one piece [vi, vj] -> [wi, wj],
//   f(v) = wi + (wj - wi) x(v),  x = (1 - a)(v - vi) / (a (vj - v) + (1 - a)(v - vi)),
// at distances w from each end inside both transition layers (widths
// a (vj - vi) next to vi and (1 - a)(vj - vi) next to vj) and in the middle:
// f(v^i + w) - w^i against (wj - wi) x(vi + w) and f(v^j) - f(v^j - w) against
// (wj - wi)(1 - x(vj - w)), to 10^-12 relative (the hats are the printed
// decimals of 15 digits; in the local form no coefficient cancels).
void check_map(const std::string& what, const RatFunc& f, const Ball& vi, const Ball& vj, const Ball& wi,
               const Ball& wj, const Ball& a, long digits) {
  const long prec = 256;
  const Rational vi_h = printed(vi, digits), vj_h = printed(vj, digits), wi_h = printed(wi, digits);
  const Ball dv = sub(vj, vi, prec), dw = sub(wj, wi, prec);
  Ball oma;
  arb_sub_ui(oma.get(), a.get(), 1, prec);
  arb_neg(oma.get(), oma.get());
  // (wj - wi) times the share of the end at distance `near_end` from it:
  // x(vi + w) = (1 - a) w / (a (dv - w) + (1 - a) w), 1 - x(vj - w) = a w / (a w + (1 - a)(dv - w)).
  auto share = [&](const Rational& w, bool left_end) {
    Ball bw(w, prec), rest = sub(dv, bw, prec), num, other, den;
    arb_mul(num.get(), left_end ? oma.get() : a.get(), bw.get(), prec);
    arb_mul(other.get(), left_end ? a.get() : oma.get(), rest.get(), prec);
    arb_add(den.get(), num.get(), other.get(), prec);
    arb_div(num.get(), num.get(), den.get(), prec);
    arb_mul(num.get(), num.get(), dw.get(), prec);
    return num;
  };
  const Rational dv_h = printed(dv, 30), a_h = printed(a, 30), oma_h = printed(oma, 30);
  std::vector<Rational> theta;
  for (const Rational& layer : {a_h, oma_h})
    for (const Rational& k : {Rational(1, 4), Rational(1), Rational(4)})
      if (layer * k < Rational(1, 2)) theta.push_back(layer * k);
  theta.push_back(Rational(1, 2));
  for (const Rational& th : theta) {
    const Rational w = th * dv_h;
    const Rational left = f(vi_h + w) - wi_h, right = f(vj_h) - f(vj_h - w);
    EXPECT_TRUE(near(left, share(w, true), 1e-12, prec))
        << what << ": f(v_i + w) - w_i = " << Ball(left, 64).str(17) << ", certified " << share(w, true).str(17)
        << ", w / (v_j - v_i) = " << Ball(th, 64).str(5);
    EXPECT_TRUE(near(right, share(w, false), 1e-12, prec))
        << what << ": f(v_j) - f(v_j - w) = " << Ball(right, 64).str(17) << ", certified " << share(w, false).str(17)
        << ", w / (v_j - v_i) = " << Ball(th, 64).str(5);
  }
}

}  // namespace

namespace {

// Every piece's printed m(z) of radical on c against its certified map.
void check_radical(const std::string& curve, SpeedKind kind, long digits) {
  const Curve c = parse_curve(curve);
  Options o;
  o.digits = digits;
  const RadicalResult r = radical(c, kind, o);
  const auto f = radical_formulas(c, r, Format::Text, digits);
  ASSERT_EQ(f.size(), r.pieces());
  for (std::size_t i = 0; i < r.pieces(); ++i)
    check_map(curve + ", piece " + std::to_string(i) + ", m(z) = " + f[i].m, read_formula(f[i].m, 'z'), r.Z[i],
              r.Z[i + 1], r.S[i], r.S[i + 1], r.integrals[i].alpha, digits);
}

// Every piece's printed r(s) of a Moebius result against its certified map.
void check_moebius(const std::string& curve, const MoebiusResult& r, long digits) {
  const Curve c = parse_curve(curve);
  const auto f = moebius_formulas(c, r, Format::Text, digits);
  ASSERT_EQ(f.size(), r.pieces());
  const long prec = 256;
  for (std::size_t i = 0; i < r.pieces(); ++i)
    check_map(curve + ", piece " + std::to_string(i) + ", r(s) = " + f[i].r, read_formula(f[i].r, 's'), r.S[i],
              r.S[i + 1], r.T[i].t.to_ball(prec), r.T[i + 1].t.to_ball(prec), r.alpha[i], digits);
}

}  // namespace

TEST(Formula, RadicalMapsKeepTheirShapeWhereAlphaIsNextToZeroOrOne) {
  // A peak of height C at each of t = 0, 1 and a zero of sigma in between:
  // alpha of the pieces next to the peaks is within ~1/C of 0 or 1.
  for (const char* C : {"7777777777777777777777777777777", "10^40"}) {
    check_radical(std::string("(t, ") + C + "*t^2*(1-t)^2)", SpeedKind::Angular, 15);
    check_radical(std::string("(t, ") + C + "*t^2*(1-t)^2)", SpeedKind::Angular, 30);
  }
}

TEST(Formula, RadicalMapsMatchTheirCertifiedMapsOnRandomCurves) {
  // a straight line's angular speed is 0: alpha = 1/2 exactly, the linear map
  check_radical("(t, 2*t)", SpeedKind::Angular, 15);
  std::mt19937_64 rng(20261204);
  for (int k = 0; k < test_support::iterations(12); ++k) {
    const Poly x = test_support::random_poly(rng, 1 + k % 3, 5), y = test_support::random_poly(rng, 2 + k % 4, 9);
    const std::string curve = "(" + x.str() + ", " + y.str() + ")";
    check_radical(curve, k % 2 ? SpeedKind::Angular : SpeedKind::Parametric, 15);
  }
}

TEST(Formula, MoebiusMapsKeepTheirShapeWhereAlphaIsNextToZeroOrOne) {
  // alpha ~ 10^-20 for a pole 10^-20 to the right of 1 (parametric speed ~ 1/(t - 1 - eps)^2)
  for (const char* curve : {"(t, 1/(t - 1 - 1/10^20))", "(t, 1/(t + 1/10^25))"}) {
    const MoebiusResult r = moebius_optimal(parse_curve(curve), SpeedKind::Parametric);
    ASSERT_FALSE(r.exact.has_value());
    check_moebius(curve, r, 15);
  }
  const std::string curve = "(t, 10^30*t^2*(1-t)^2 + t)";
  check_moebius(curve, reparam_c0(parse_curve(curve), SpeedKind::Angular, 4), 15);
}
