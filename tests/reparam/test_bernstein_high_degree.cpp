// The Bernstein curve model (reparam/src/curve_model.hpp) at high degree
// (random Bezier and rational Bezier curves of degree 20-150): its
// enclosures of the components, their derivatives and the speed's square
// contain the exact values (exact rational arithmetic at rational points)
// on exact, narrow and wide, real and complex balls; at an exact point they
// are as tight as the power-basis model's; Speed takes the Bernstein
// model exactly up to kBernsteinMaxDegree; and the double-word tier at the
// quadrature's nodes, from the Bernstein sums, serves Bezier curves of
// degree 20-150 with enclosures of the exact sigma and sigma^2.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../../reparam/src/curve_model.hpp"
#include "../../reparam/src/speed_enclosure.hpp"
#include "../../reparam/src/speed_formula.hpp"
#include "uniparam/core/dd_ball.hpp"
#include "uniparam/reparam/bezier.hpp"
#include "uniparam/reparam/speed.hpp"

using namespace uniparam;

namespace {

// A random Bezier curve of degree n, dimension 2 or 3, control points with
// small denominators, positive rational weights when rational.
BezierCurve random_bezier(std::mt19937& rng, long n, std::size_t dim, bool rational) {
  std::uniform_int_distribution<long> coord(-60, 60), den(1, 4), weight(1, 9);
  std::vector<std::vector<Rational>> pts;
  std::vector<Rational> w;
  for (long k = 0; k <= n; ++k) {
    std::vector<Rational> p;
    for (std::size_t i = 0; i < dim; ++i) p.emplace_back(coord(rng), den(rng));
    pts.push_back(std::move(p));
    if (rational) w.emplace_back(weight(rng), den(rng));
  }
  return BezierCurve(pts, w);
}

// Balls around t: exact, narrow real, narrow complex, wide real, wide complex.
std::vector<AcbBox> balls_around(const Rational& t) {
  std::vector<AcbBox> z(5);
  for (AcbBox& b : z) acb_set_fmpq(b, t.get(), 512);
  arb_add_error_2exp_si(acb_realref(z[1].get()), -40);
  arb_add_error_2exp_si(acb_realref(z[2].get()), -40);
  arb_add_error_2exp_si(acb_imagref(z[2].get()), -40);
  arb_add_error_2exp_si(acb_realref(z[3].get()), -8);
  arb_add_error_2exp_si(acb_realref(z[4].get()), -8);
  arb_add_error_2exp_si(acb_imagref(z[4].get()), -8);
  return z;
}

bool holds(const AcbBox& x, const Rational& v) {
  return arb_contains_fmpq(acb_realref(x.get()), v.get()) && arb_contains_zero(acb_imagref(x.get()));
}

// sigma^2 on the ball z from a model's N_i, Q (one denominator): A_i, B_i,
// S, F and speed_formula's speed_squared, as Speed::eval_components.
void model_sigma2(const CurveModel& m, SpeedKind kind, AcbBox& out, const acb_t z, long prec) {
  using namespace speed_formula;
  const AcbArith ar{prec};
  const std::size_t n = m.size();
  std::vector<AcbBox> A(n), B(n);
  AcbBox v, v1, v2, q, q1, q2, S, F, L2;
  m.eval_den(0, q, q1, q2, z, prec);
  for (std::size_t i = 0; i < n; ++i) {
    m.eval_num(i, v, v1, v2, z, prec);
    scaled_derivatives(ar, A[i], &B[i], v, v1, &v2, q, q1, &q2);
  }
  sum_of_squares(ar, S, n, [&A](std::size_t i) -> const AcbBox& { return A[i]; });
  if (kind == SpeedKind::Angular) {
    cross_terms(ar, F, A.data(), B.data(), n);
    speed_squared(ar, out, S, F, n == 2 ? Form::Plane : Form::Space, nullptr);
  } else {
    ar.mul(L2, q, q);
    speed_squared(ar, out, S, F, Form::Parametric, &L2);
  }
}

// The exact sigma^2 at t from the exact x_i'(t), x_i''(t): angular
// |x' x x''|^2 / |x'|^4 (sum of the squared 2x2 minors), parametric |x'|^2.
// \pre x'(t) != 0 for the angular speed.
Rational exact_sigma2(const std::vector<Rational>& d1, const std::vector<Rational>& d2, SpeedKind kind) {
  Rational s(0), f(0);
  for (std::size_t i = 0; i < d1.size(); ++i) {
    s = s + d1[i] * d1[i];
    for (std::size_t j = i + 1; j < d1.size(); ++j) {
      const Rational c = d1[i] * d2[j] - d1[j] * d2[i];
      f = f + c * c;
    }
  }
  return kind == SpeedKind::Parametric ? s : f / (s * s);
}

// sum_k c_k binom(n, k) t^k (1 - t)^(n - k) in the power basis, exactly:
// its t^k coefficient is binom(n, k) (Delta^k c)_0.
Poly power_basis(std::vector<Integer> c) {
  const long n = static_cast<long>(c.size()) - 1;
  std::vector<Integer> out;
  for (long k = 0; k <= n; ++k) {
    Integer b;
    fmpz_bin_uiui(b.get(), static_cast<ulong>(n), static_cast<ulong>(k));
    out.push_back(b * c[0]);
    for (long j = 0; j < n - k; ++j) c[static_cast<std::size_t>(j)] = c[static_cast<std::size_t>(j) + 1] - c[static_cast<std::size_t>(j)];
  }
  return Poly(out);
}

struct Counts {
  int bernstein = 0, power = 0, tight = 0;
};

void check_curve(const BezierCurve& b, std::mt19937& rng, int points, Counts& counts) {
  const Curve c = b.to_curve();
  ASSERT_NE(c.bernstein(), nullptr);
  const auto bern = bernstein_curve_model(*c.bernstein());
  // the power-basis model of the same N_i, Q (one common Q, as the
  // Bernstein model's)
  const LocalPoly Q(power_basis(c.bernstein()->den));
  std::vector<PowerComponent> pc;
  for (const auto& row : c.bernstein()->num) pc.push_back(PowerComponent{LocalPoly(power_basis(row)), Q, false, 0});
  const auto power = power_curve_model(pc);
  std::vector<RatFunc> x1, x2;
  for (const RatFunc& x : c.components()) {
    x1.push_back(x.derivative());
    x2.push_back(x1.back().derivative());
  }
  for (int p = 0; p < points; ++p) {
    const Rational t(static_cast<long>(rng() % 1999) + 1, 2000);
    std::vector<Rational> d1, d2;
    bool regular = false;
    for (std::size_t i = 0; i < x1.size(); ++i) {
      d1.push_back(x1[i](t));
      d2.push_back(x2[i](t));
      regular = regular || d1.back() != Rational(0);
    }
    if (!regular) continue;
    for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
      const Rational exact = exact_sigma2(d1, d2, kind);
      for (const long prec : {64L, 128L}) {
        const std::vector<AcbBox> z = balls_around(t);
        for (std::size_t k = 0; k < z.size(); ++k) {
          AcbBox sb, sp;
          model_sigma2(*bern, kind, sb, z[k], prec);
          model_sigma2(*power, kind, sp, z[k], prec);
          if (acb_is_finite(sb)) {
            EXPECT_TRUE(holds(sb, exact)) << "degree " << b.degree() << " t = " << t.str() << " ball " << k;
            ++counts.bernstein;
          }
          if (acb_is_finite(sp)) {
            EXPECT_TRUE(holds(sp, exact)) << "degree " << b.degree() << " t = " << t.str() << " ball " << k;
            ++counts.power;
          }
          // at the exact point and on narrow real balls both are finite and
          // the Bernstein sum keeps within 16 bits of the local expansions
          if (k == 0 && exact != Rational(0)) {
            ASSERT_TRUE(acb_is_finite(sb) && acb_is_finite(sp)) << "degree " << b.degree();
            const long ab = acb_rel_accuracy_bits(sb), ap = acb_rel_accuracy_bits(sp);
            EXPECT_GE(ab, ap - 16) << "degree " << b.degree() << " t = " << t.str() << " prec " << prec;
            EXPECT_GE(ab, prec / 2) << "degree " << b.degree() << " t = " << t.str() << " prec " << prec;
            ++counts.tight;
          }
        }
      }
    }
  }
}

}  // namespace

TEST(BernsteinHighDegree, EnclosuresOfTheSpeedHoldTheExactValueFromDegree20To150) {
  std::mt19937 rng(3636);
  Counts counts;
  const long degrees[] = {20, 37, 64, 101, 150};
  for (const long n : degrees)
    for (int kind = 0; kind < 2; ++kind) {
      // plane integral and space rational curves
      const BezierCurve b = random_bezier(rng, n, kind == 0 ? 2 : 3, kind == 1);
      check_curve(b, rng, n >= 100 ? 3 : 5, counts);
    }
  EXPECT_GT(counts.bernstein, 300);
  EXPECT_GT(counts.power, 300);
  EXPECT_GT(counts.tight, 60);
}

TEST(BernsteinHighDegree, SpeedTakesTheBernsteinModelUpToItsDegreeLimit) {
  std::mt19937 rng(3637);
  int bern = 0, pow = 0;
  for (long n = 2; n <= 150; n += 7) {
    const Curve c = random_bezier(rng, n, 2, n % 2 == 1).to_curve();
    ASSERT_NE(c.bernstein(), nullptr);
    const bool serves = bernstein_model_serves(*c.bernstein());
    EXPECT_EQ(serves, n <= kBernsteinMaxDegree) << "degree " << n;
    (serves ? bern : pow)++;
  }
  EXPECT_EQ(bern, 3);  // degrees 2, 9, 16
  EXPECT_EQ(pow, 19);
}

TEST(BernsteinHighDegree, DoubleWordNodesFromTheBernsteinSumsHoldTheExactSpeed) {
  std::mt19937 rng(3638);
  int tried = 0, served = 0;
  const long degrees[] = {20, 33, 50, 64, 101, 150};
  for (const long n : degrees) {
    const int tried_before = tried, served_before = served;
    for (int shape = 0; shape < 3; ++shape) {
      // plane integral, plane rational, space rational
      const Curve c = random_bezier(rng, n, shape == 2 ? 3 : 2, shape > 0).to_curve();
      std::vector<RatFunc> x1, x2;
      for (const RatFunc& x : c.components()) {
        x1.push_back(x.derivative());
        x2.push_back(x1.back().derivative());
      }
      for (SpeedKind kind : {SpeedKind::Angular, SpeedKind::Parametric}) {
        std::unique_ptr<Speed> s;
        try {
          s = std::make_unique<Speed>(c, kind);
        } catch (const std::exception&) {
          continue;  // not regular on [0, 1]
        }
        for (int p = 0; p < 8; ++p) {
          const Rational t(static_cast<long>(rng() % 1999) + 1, 2000);
          std::vector<Rational> d1, d2;
          for (std::size_t i = 0; i < x1.size(); ++i) {
            d1.push_back(x1[i](t));
            d2.push_back(x2[i](t));
          }
          Rational s2(0);
          for (const Rational& v : d1) s2 = s2 + v * v;
          if (s2 == Rational(0)) continue;
          const Rational exact2 = exact_sigma2(d1, d2, kind);
          for (const long prec : {64L, 90L}) {
            // a node: a narrow real ball around t
            Ball tb;
            arb_set_fmpq(tb.get(), t.get(), 256);
            arb_add_error_2exp_si(tb.get(), -prec - 4);
            DDBall x, out;
            ASSERT_TRUE(dd_set_arb(x, tb.get()));
            ++tried;
            if (!s->eval_dd(out, x, Speed::PieceSigns{}, true, prec)) continue;
            ++served;
            Ball r;
            dd_get_arb(r.get(), out);
            EXPECT_TRUE(arb_contains_fmpq(r.get(), exact2.get())) << "degree " << n << " t = " << t.str();
            // sigma itself: a plane curve's signed angular speed
            // (x'y'' - x''y') / |x'|^2 with the sign +1, else sqrt(sigma^2)
            if (s->eval_dd(out, x, Speed::PieceSigns{}, false, prec)) {
              dd_get_arb(r.get(), out);
              if (kind == SpeedKind::Angular && d1.size() == 2) {
                const Rational signed_speed = (d1[0] * d2[1] - d2[0] * d1[1]) / s2;
                EXPECT_TRUE(arb_contains_fmpq(r.get(), signed_speed.get())) << "degree " << n;
              } else {
                arb_mul(r.get(), r.get(), r.get(), 2 * prec);
                EXPECT_TRUE(arb_contains_fmpq(r.get(), exact2.get())) << "degree " << n;
              }
            }
          }
        }
      }
    }
    EXPECT_GT(2 * (served - served_before), tried - tried_before) << "degree " << n;
  }
  EXPECT_GT(tried, 450);
  EXPECT_GT(served, tried * 3 / 4) << "served " << served << " of " << tried;
}
