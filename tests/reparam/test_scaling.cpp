// Uniformity of curves with huge coefficients or weights: the cost must not
// grow with the size of the numbers where the geometry allows it, and every
// result must contain an independent closed-form or extrapolated value.
// Each test runs under a generous TimeBudget, so a regression fails with
// BudgetExceeded instead of running for hours (the budget is not a speed
// target: today's code runs these in seconds).
#include <gtest/gtest.h>

#include <arb.h>
#include <arb_mat.h>

#include <string>
#include <vector>

#include "uniparam/reparam/all.hpp"
#include "uniparam/core/budget.hpp"
#include "uniparam/reparam/scaling.hpp"

using namespace uniparam;

namespace {

constexpr double kBudgetSeconds = 300;

// C = 77...7 with `digits` decimal digits (exact).
std::string sevens(int digits) { return std::string(static_cast<std::size_t>(digits), '7'); }

}  // namespace

// Must show: (t, C t^2) with a 5000-digit C (a turn of the tangent by
// atan(2C) within 1/C of t = 0) is certified, and matches the closed forms
//   angular:    omega = 2C / (1 + 4C^2 t^2), mu = atan(2C),
//               int omega^2 = C (2C / (1 + 4C^2) + atan(2C));
//   parametric: |p'|^2 = 1 + 4C^2 t^2, int |p'|^2 = 1 + 4C^2 / 3,
//               mu = sqrt(1 + 4C^2) / 2 + asinh(2C) / (4C).
TEST(Scaling, HugeCoefficientParabolaMatchesClosedForms) {
  TimeBudget budget(kBudgetSeconds);
  const std::string c_text = sevens(5000);
  const Curve curve = Curve::parse("(t, " + c_text + "*t^2)");
  const long prec = 256;
  Ball C, two_c, at, one_4c2, tmp;
  fmpz_t cz;
  fmpz_init(cz);
  fmpz_set_str(cz, c_text.c_str(), 10);
  arb_set_fmpz(C.get(), cz);
  fmpz_clear(cz);
  arb_mul_2exp_si(two_c.get(), C.get(), 1);
  arb_atan(at.get(), two_c.get(), prec);
  arb_sqr(one_4c2.get(), two_c.get(), prec);
  arb_add_ui(one_4c2.get(), one_4c2.get(), 1, prec);  // 1 + 4C^2
  Options o;
  {
    const UniformityResult r = uniformity(curve, SpeedKind::Angular, o);
    Ball ms, u;
    arb_div(ms.get(), two_c.get(), one_4c2.get(), prec);
    arb_add(ms.get(), ms.get(), at.get(), prec);
    arb_mul(ms.get(), ms.get(), C.get(), prec);
    arb_sqr(u.get(), at.get(), prec);
    arb_div(u.get(), u.get(), ms.get(), prec);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), at.get())) << r.mu.str(20);
    EXPECT_TRUE(arb_overlaps(r.mean_square.get(), ms.get())) << r.mean_square.str(20);
    EXPECT_TRUE(arb_overlaps(r.u.get(), u.get())) << r.u.str(20) << " vs " << u.str(20);
    for (const Ball* x : {&r.mu, &r.mean_square, &r.u}) EXPECT_TRUE(x->meets_digits(o.digits)) << x->str(20);
  }
  {
    const UniformityResult r = uniformity(curve, SpeedKind::Parametric, o);
    Ball ms, mu, u;
    arb_sqr(ms.get(), two_c.get(), prec);
    arb_div_ui(ms.get(), ms.get(), 3, prec);
    arb_add_ui(ms.get(), ms.get(), 1, prec);
    arb_asinh(tmp.get(), two_c.get(), prec);
    arb_div(tmp.get(), tmp.get(), two_c.get(), prec);
    arb_sqrt(mu.get(), one_4c2.get(), prec);
    arb_add(mu.get(), mu.get(), tmp.get(), prec);
    arb_mul_2exp_si(mu.get(), mu.get(), -1);
    arb_sqr(u.get(), mu.get(), prec);
    arb_div(u.get(), u.get(), ms.get(), prec);
    EXPECT_TRUE(arb_overlaps(r.mu.get(), mu.get())) << r.mu.str(20);
    EXPECT_TRUE(arb_overlaps(r.mean_square.get(), ms.get())) << r.mean_square.str(20);
    EXPECT_TRUE(arb_overlaps(r.u.get(), u.get())) << r.u.str(20);
  }
}

// Must show: the rational quadratic with control points (1,0), (1,1), (0,1)
// and weights 1, 4/5 lambda, lambda^2 (the Moebius reparameterisation of the
// conic with weights 1, 4/5, 1) has int |p'|^2 = lambda I0 + J + I2 / lambda
// exactly (docs/math.md (1.2) with 1/m' = (lambda (1 - s) + s)^2 / lambda), and
// the same arc length mu for every lambda. I0, J, I2 come from lambda = 1,
// 10, 100 (balance() leaves those alone: the ordinary path); lambda = 10^41
// (weights 1, 8e40, 1e82) must agree with the extrapolation, as must the
// mirrored weights 1e82, 8e40, 1.
TEST(Scaling, GeometricWeightsMatchExtrapolation) {
  TimeBudget budget(kBudgetSeconds);
  const char* control = "[[1,0],[1,1],[0,1]]";
  Options o;
  o.digits = 30;
  const long prec = 512;
  auto run = [&](const std::string& weights) {
    const Curve c = BezierCurve::parse(control, weights).to_curve();
    return uniformity(c, SpeedKind::Parametric, o);
  };
  const std::vector<std::string> small = {"[1,4/5,1]", "[1,8,100]", "[1,80,10000]"};
  for (const std::string& w : small)
    EXPECT_FALSE(balance(BezierCurve::parse(control, w).to_curve()).has_value()) << w;
  std::vector<UniformityResult> r;
  for (const std::string& w : small) r.push_back(run(w));
  // S(l) = l I0 + J + I2 / l at l = 1, 10, 100: solve the 3x3 system.
  arb_mat_t A, x, b;
  arb_mat_init(A, 3, 3);
  arb_mat_init(x, 3, 1);
  arb_mat_init(b, 3, 1);
  const long lam[3] = {1, 10, 100};
  for (int i = 0; i < 3; ++i) {
    arb_set_si(arb_mat_entry(A, i, 0), lam[i]);
    arb_one(arb_mat_entry(A, i, 1));
    arb_set_si(arb_mat_entry(A, i, 2), 1);
    arb_div_si(arb_mat_entry(A, i, 2), arb_mat_entry(A, i, 2), lam[i], prec);
    arb_set(arb_mat_entry(b, i, 0), r[static_cast<std::size_t>(i)].mean_square.get());
  }
  ASSERT_TRUE(arb_mat_solve(x, A, b, prec));
  Ball big, small_inv, predicted, mu_ref(r[0].mu), u;
  arb_set_str(big.get(), "1e41", prec);
  arb_inv(small_inv.get(), big.get(), prec);
  arb_mul(predicted.get(), big.get(), arb_mat_entry(x, 0, 0), prec);
  arb_add(predicted.get(), predicted.get(), arb_mat_entry(x, 1, 0), prec);
  arb_addmul(predicted.get(), small_inv.get(), arb_mat_entry(x, 2, 0), prec);
  arb_sqr(u.get(), mu_ref.get(), prec);
  arb_div(u.get(), u.get(), predicted.get(), prec);
  arb_mat_clear(A);
  arb_mat_clear(x);
  arb_mat_clear(b);
  for (const char* w : {"[1,8e40,1e82]", "[1e82,8e40,1]"}) {
    EXPECT_TRUE(balance(BezierCurve::parse(control, w).to_curve()).has_value()) << w;
    const UniformityResult big_r = run(w);
    EXPECT_TRUE(arb_overlaps(big_r.mu.get(), mu_ref.get())) << w << ": " << big_r.mu.str(35);
    EXPECT_TRUE(arb_overlaps(big_r.mean_square.get(), predicted.get()))
        << w << ": " << big_r.mean_square.str(35) << " vs " << predicted.str(35);
    EXPECT_TRUE(arb_overlaps(big_r.u.get(), u.get())) << w << ": " << big_r.u.str(35) << " vs " << u.str(35);
    EXPECT_TRUE(big_r.u.meets_digits(o.digits)) << big_r.u.str(35);
    // The reported exact parts are p's, not the balanced curve's.
    EXPECT_EQ(big_r.speed_squared.str(), Speed(BezierCurve::parse(control, w).to_curve(), SpeedKind::Parametric).squared().str());
  }
}

// Must show: balance() is exact: q = p o m with m(s) = a s / (a s + b (1 - s)),
// checked at rational points s (p(m(s)) == q(s) exactly), for a plane and a
// space curve with separate denominators.
TEST(Scaling, BalancedCurveIsExactComposition) {
  const Curve p = Curve::parse("(1/(1 + 1000000000000000000000000000000*t^3), t/(1 + 1000000000000000000000000000000*t^3), t^2)");
  const auto bal = balance(p);
  ASSERT_TRUE(bal.has_value());
  for (const Rational s : {Rational(1, 3), Rational(5, 7), Rational(0), Rational(1)}) {
    const Rational a(bal->a), b(bal->b);
    const Rational t = a * s / (a * s + b * (Rational(1) - s));
    for (std::size_t i = 0; i < p.dimension(); ++i) {
      const RatFunc& pc = p.components()[i];
      const RatFunc& qc = bal->q.components()[i];
      EXPECT_EQ(pc.num()(t) / pc.den()(t), qc.num()(s) / qc.den()(s)) << i;
    }
  }
  EXPECT_FALSE(balance(Curve::parse("(t, t^2)")).has_value());
  EXPECT_FALSE(balance(Curve::parse("((1-t^2)/(1+t^2), 2t/(1+t^2))")).has_value());
}
