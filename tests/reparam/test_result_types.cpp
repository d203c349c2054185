// The engine's result types are typed: a MoebiusResult carries its optimiser,
// target, exact data and balancing as optionals set by the method that made
// it (a RadicalResult its balancing), and one overloaded eval_r / eval_speed /
// eval_point evaluates either kind of map.
#include <gtest/gtest.h>

#include <optional>
#include <type_traits>

#include "uniparam/core/error.hpp"
#include "uniparam/reparam/moebius.hpp"
#include "uniparam/reparam/radical.hpp"
#include "uniparam/reparam/sample.hpp"

namespace uniparam {
namespace {

static_assert(std::is_same_v<decltype(MoebiusResult::optimiser), std::optional<MoebiusResult::Optimiser>>);
static_assert(std::is_same_v<decltype(MoebiusResult::target), std::optional<MoebiusResult::Target>>);
static_assert(std::is_same_v<decltype(MoebiusResult::exact), std::optional<MoebiusResult::Exact>>);
static_assert(std::is_same_v<decltype(MoebiusResult::balanced), std::optional<MoebiusResult::Balanced>>);
static_assert(std::is_same_v<decltype(RadicalResult::balanced), std::optional<RadicalResult::Balanced>>);

const Curve& cubic() {
  static const Curve c = Curve::parse("(t, t^3 - t/2)");
  return c;
}

TEST(ResultTypes, EachMethodSetsItsOwnPart) {
  Options opt;
  opt.digits = 10;
  const MoebiusResult c0 = moebius_c0(cubic(), SpeedKind::Parametric, {RealAlgebraic(0), RealAlgebraic(1)}, opt);
  EXPECT_FALSE(c0.optimiser || c0.target || c0.exact);
  const MoebiusResult n3 = reparam_c0(cubic(), SpeedKind::Parametric, 3, opt);
  ASSERT_TRUE(n3.optimiser);
  EXPECT_FALSE(n3.target || n3.exact);
  EXPECT_FALSE(n3.optimiser->phi.certainly_negative());
  const MoebiusResult c1 = reparam_c1(cubic(), SpeedKind::Parametric, Rational(9, 10), opt);
  ASSERT_TRUE(c1.target);
  EXPECT_FALSE(c1.optimiser || c1.exact);
  EXPECT_EQ(c1.target->value, Rational(9, 10));
  const MoebiusResult q = make_rational(cubic(), n3, 6, opt);
  ASSERT_TRUE(q.exact);
  EXPECT_TRUE(q.optimiser);  // kept from n3
  ASSERT_EQ(q.exact->T.size(), q.pieces() + 1);
  ASSERT_EQ(q.exact->S.size(), q.pieces() + 1);
  ASSERT_EQ(q.exact->alpha.size(), q.pieces());
  for (std::size_t i = 0; i <= q.pieces(); ++i) {
    EXPECT_TRUE(q.T[i].t.is_rational() && q.T[i].t.rational() == q.exact->T[i]);
    EXPECT_TRUE(q.S[i].contains(q.exact->S[i]));
  }
}

TEST(ResultTypes, OneOverloadedEvaluationForEveryMap) {
  Options opt;
  opt.digits = 12;
  const long prec = 128;
  const Speed sp(cubic(), SpeedKind::Parametric);
  const MoebiusResult m = reparam_c0(cubic(), SpeedKind::Parametric, 2, opt);
  const RadicalResult r = radical(cubic(), SpeedKind::Parametric, opt);
  const Reparameterization rm(m), rr(r);
  for (long k = 0; k <= 8; ++k) {
    const Ball s(Rational(k, 8), prec);
    // the free functions and the Reparameterization agree bit for bit
    EXPECT_TRUE(arb_equal(eval_r(m, s, prec).get(), rm.eval_r(s, prec).get())) << k;
    EXPECT_TRUE(arb_equal(eval_r(r, s, prec).get(), rr.eval_r(s, prec).get())) << k;
    EXPECT_TRUE(arb_equal(eval_speed(m, sp, s, prec).get(), rm.eval_speed(sp, s, prec).get())) << k;
    EXPECT_TRUE(arb_equal(eval_speed(r, sp, s, prec).get(), rr.eval_speed(sp, s, prec).get())) << k;
    const std::vector<Ball> pm = eval_point(cubic(), m, s, prec), pr = eval_point(cubic(), r, s, prec);
    ASSERT_EQ(pm.size(), 2u);
    ASSERT_EQ(pr.size(), 2u);
    // both maps fix 0 and 1 exactly
    if (k == 0 || k == 8) {
      EXPECT_TRUE(eval_r(m, s, prec).contains(Rational(k, 8)) && eval_r(m, s, prec).is_exact());
      EXPECT_TRUE(eval_r(r, s, prec).contains(Rational(k, 8)) && eval_r(r, s, prec).is_exact());
    }
  }
  EXPECT_THROW(eval_r(m, Ball(2), prec), InvalidArgument);
  EXPECT_THROW(eval_r(r, Ball(2), prec), InvalidArgument);
}

}  // namespace
}  // namespace uniparam
