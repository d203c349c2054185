// The curve models (reparam/src/curve_model.hpp): the Bernstein model of a
// random (rational) Bezier curve and the power-basis model of the same
// curve both enclose the exact components and derivatives at rational
// points, on exact, narrow and wide (complex) balls around them; and the
// speed of a Bezier curve (evaluated from its Bernstein form) encloses the
// exact sigma^2.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../../reparam/src/curve_model.hpp"
#include "../../reparam/src/speed_enclosure.hpp"
#include "uniparam/reparam/bezier.hpp"
#include "uniparam/reparam/speed.hpp"

using namespace uniparam;

namespace {

BezierCurve random_bezier(std::mt19937& rng, bool rational) {
  std::uniform_int_distribution<long> deg(2, 9), coord(-30, 30), den(1, 5), weight(1, 9);
  const long n = deg(rng);
  std::vector<std::vector<Rational>> pts;
  std::vector<Rational> w;
  for (long k = 0; k <= n; ++k) {
    pts.push_back({Rational(coord(rng), den(rng)), Rational(coord(rng), den(rng)), Rational(coord(rng), 1)});
    if (rational) w.emplace_back(weight(rng), den(rng));
  }
  return BezierCurve(pts, w);
}

// Three balls around t: exact, a narrow real ball, a wide complex ball.
std::vector<AcbBox> balls_around(const Rational& t) {
  std::vector<AcbBox> z(3);
  acb_set_fmpq(z[0], t.get(), 256);
  acb_set_fmpq(z[1], t.get(), 256);
  arb_add_error_2exp_si(acb_realref(z[1].get()), -40);
  acb_set_fmpq(z[2], t.get(), 256);
  arb_add_error_2exp_si(acb_realref(z[2].get()), -4);
  arb_add_error_2exp_si(acb_imagref(z[2].get()), -4);
  return z;
}

bool holds(const AcbBox& x, const Rational& v) {
  return arb_contains_fmpq(acb_realref(x.get()), v.get()) && arb_contains_zero(acb_imagref(x.get()));
}

// x_i, x_i', x_i'' from a model's N, Q and derivatives (quotient rule in
// Arb's balls).
void model_values(const CurveModel& m, std::size_t i, const acb_t z, long prec, AcbBox out[3]) {
  AcbBox n[3], q[3], v, t;
  m.eval_num(i, n[0], n[1], n[2], z, prec);
  m.eval_den(i, q[0], q[1], q[2], z, prec);
  acb_div(out[0], n[0], q[0], prec);
  // x' = (N' - x Q') / Q, x'' = (N'' - 2 x' Q' - x Q'') / Q
  acb_mul(t, out[0], q[1], prec);
  acb_sub(t, n[1], t, prec);
  acb_div(out[1], t, q[0], prec);
  acb_mul(t, out[1], q[1], prec);
  acb_mul_2exp_si(t, t, 1);
  acb_sub(v, n[2], t, prec);
  acb_mul(t, out[0], q[2], prec);
  acb_sub(v, v, t, prec);
  acb_div(out[2], v, q[0], prec);
}

}  // namespace

TEST(CurveModel, BernsteinAndPowerModelsEncloseTheExactComponents) {
  std::mt19937 rng(35);
  int checked = 0;
  for (int round = 0; round < 40; ++round) {
    const BezierCurve b = random_bezier(rng, round % 2 == 1);
    const Curve c = b.to_curve();
    ASSERT_NE(c.bernstein(), nullptr);
    const auto bern = bernstein_curve_model(*c.bernstein());
    std::vector<PowerComponent> pc;
    for (std::size_t i = 0; i < c.dimension(); ++i)
      pc.push_back(PowerComponent{LocalPoly(c.components()[i].num()), LocalPoly(c.components()[i].den()),
                                  c.components()[i].den() == Poly(1), i});
    const auto power = power_curve_model(pc);
    ASSERT_EQ(bern->size(), c.dimension());
    for (int p = 0; p < 5; ++p) {
      const Rational t(static_cast<long>(rng() % 1000), 999);
      for (std::size_t i = 0; i < c.dimension(); ++i) {
        const RatFunc& x = c.components()[i];
        const RatFunc x1 = x.derivative(), x2 = x1.derivative();
        const Rational exact[3] = {x(t), x1(t), x2(t)};
        for (const AcbBox& z : balls_around(t))
          for (const CurveModel* m : {bern.get(), power.get()}) {
            AcbBox v[3];
            model_values(*m, i, z, 128, v);
            for (int j = 0; j < 3; ++j) {
              EXPECT_TRUE(holds(v[j], exact[j])) << "round " << round << " component " << i << " derivative " << j;
              ++checked;
            }
          }
        // tight on the exact point: the Bernstein model loses few bits
        AcbBox v[3];
        model_values(*bern, i, balls_around(t)[0], 128, v);
        for (int j = 0; j < 3; ++j)
          EXPECT_TRUE(exact[j] == Rational(0) || acb_rel_accuracy_bits(v[j].get()) > 100) << round;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(CurveModel, BezierSpeedFromTheBernsteinFormEnclosesTheExactSquare) {
  std::mt19937 rng(36);
  for (int round = 0; round < 12; ++round) {
    const BezierCurve b = random_bezier(rng, round % 2 == 1);
    const Curve c = b.to_curve();
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      std::unique_ptr<Speed> s;
      try {
        s = std::make_unique<Speed>(c, kind);
      } catch (const std::exception&) {
        continue;  // a parametric speed with a pole in [0, 1] (not regular)
      }
      if (s->identically_zero()) continue;
      for (int p = 0; p < 6; ++p) {
        const Rational t(static_cast<long>(rng() % 997) + 1, 999);
        const Rational exact = s->squared()(t);
        for (const AcbBox& z : balls_around(t)) {
          AcbBox out;
          s->eval_squared(out, z, 128, false);
          if (acb_is_finite(out)) EXPECT_TRUE(holds(out, exact)) << "round " << round << " t = " << t.str();
        }
        AcbBox out;
        s->eval_squared(out, balls_around(t)[0], 128, false);
        EXPECT_TRUE(acb_is_finite(out)) << "round " << round;
      }
    }
  }
}
