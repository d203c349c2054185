// Commands that evaluate a map or the exactly uniform parameterization at
// points (sample with every method, radical --at, locate, plot) on curves
// whose speed is concentrated within 1/C of one end: (t, C t^2) with a
// 2000-digit C (and a 15-digit one for the maps), whose angular speed 2C / (1 + 4 C^2 t^2) has a peak of
// width 1/(2C) at t = 0, and a conic whose weights grow like 2^600. Each
// runs on the exactly balanced curve q = p o m (reparam/scaling.hpp).
// "Finishes" is a generous --timeout and exit 0, never a timing; every
// printed point is checked against an independent value: the curve itself
// at the printed t (x = t, y = C t^2), and for the exactly uniform points
// the closed form of the turning angle, atan(2 C t) = fraction * pi / 2.
#include <gtest/gtest.h>

#include <arb.h>

#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Ball;
using uniparam::Rational;
using uniparam::test_support::ball_of;
using uniparam::test_support::json_ball;
using uniparam::test_support::run_uniparam;

namespace {

const char* kTimeout = "120";  // generous: each command takes well under a second
constexpr long kPrec = 16000;  // C^2 t^2 with C of 2000 digits, exactly enough

// The coefficients C: 2000 digits, and 15 digits (2^47: the balanced curve
// then has a component pole within 2^-47 of s = 1, where double evaluations
// are noisy, which the C1 draft's float quadrature must survive).
const std::string& big_c() {
  static const std::string c(2000, '7');
  return c;
}
const std::vector<std::string>& all_c() {
  static const std::vector<std::string> c{big_c(), "129141777631706"};
  return c;
}

std::string curve(const std::string& c = big_c()) { return "(t, " + c + "*t^2)"; }

Ball c_ball(const std::string& c = big_c()) {
  Ball b;
  arb_set_str(b.get(), c.c_str(), kPrec);
  return b;
}

// Every {"mid", "rad"} ball of the JSON text, in order.
std::vector<Ball> balls_in(const std::string& text) {
  std::vector<Ball> out;
  const std::regex re("\"mid\": \"([^\"]+)\",\\s*\"rad\": \"([^\"]+)\"");
  for (std::sregex_iterator it(text.begin(), text.end(), re), last; it != last; ++it)
    out.push_back(ball_of((*it)[1], (*it)[2]));
  return out;
}

// The samples of `sample --json`: per row the balls s, t, x, y, speed.
std::vector<std::vector<Ball>> sample_rows(const std::string& json) {
  std::vector<std::vector<Ball>> rows;
  const std::size_t at = json.find("\"samples\"");
  if (at == std::string::npos) return rows;
  std::size_t pos = json.find('{', at);
  while (pos != std::string::npos) {
    const std::size_t end = json.find("\"at_joint\"", pos);
    if (end == std::string::npos) break;
    rows.push_back(balls_in(json.substr(pos, end - pos)));
    pos = json.find('{', json.find('}', end));
  }
  return rows;
}

// The point (x, y) is the curve's at t: x overlaps t, y overlaps C t^2.
::testing::AssertionResult on_curve(const Ball& t, const Ball& x, const Ball& y, const std::string& c = big_c()) {
  Ball cy;
  arb_sqr(cy.get(), t.get(), kPrec);
  arb_mul(cy.get(), cy.get(), c_ball(c).get(), kPrec);
  if (!arb_overlaps(x.get(), t.get())) return ::testing::AssertionFailure() << "x " << x.str(20) << " vs t " << t.str(20);
  if (!arb_overlaps(y.get(), cy.get())) return ::testing::AssertionFailure() << "y " << y.str(20) << " vs C t^2 " << cy.str(20);
  return ::testing::AssertionSuccess();
}

// Every row of `sample --json` passes `point` (given the row's balls s, t,
// x, y, speed) and has its t above the previous row's.
template <class Point>
void expect_rows(const std::vector<std::vector<Ball>>& rows, Point point) {
  Ball prev(-1);
  for (const auto& row : rows) {
    ASSERT_GE(row.size(), 4u);
    point(row);
    EXPECT_TRUE(arb_gt(row[1].get(), prev.get())) << row[1].str(20) << " after " << prev.str(20);
    prev = row[1];
  }
}

// t with atan(2 C t) = f pi / 2: tan(f pi / 2) / (2 C), for 0 < f < 1.
Ball uniform_t(const Rational& f) {
  Ball a, c = c_ball();
  arb_const_pi(a.get(), kPrec);
  arb_mul_fmpz(a.get(), a.get(), f.num().get(), kPrec);
  arb_div_fmpz(a.get(), a.get(), f.den().get(), kPrec);
  arb_mul_2exp_si(a.get(), a.get(), -1);
  arb_tan(a.get(), a.get(), kPrec);
  arb_mul_2exp_si(c.get(), c.get(), 1);
  arb_div(a.get(), a.get(), c.get(), kPrec);
  return a;
}

}  // namespace

// Must show: sample with the maps (radical, c0, c1) on (t, C t^2) finishes
// with exit 0, K rows whose t increase in [0, 1] and meet the digits, each
// point on the curve at its t, and a finite positive speed; s = 0 and 1
// give t = 0 and 1. Both sizes of C and both speeds (with the 15-digit C,
// angular c1 ran to the time limit: its draft bisected the noise of the
// double evaluation next to s = 1 in every candidate piece; with the
// 2000-digit C, parametric c1 exited 4: its draft's integrals, about C^2,
// were beyond double's range).
TEST(HugeCoeffCli, SampleMapsFinishWithPointsOnTheCurve) {
  for (const std::string& c : all_c())
    for (const char* speed : {"angular", "parametric"})
      for (const char* method : {"radical", "c0", "c1"}) {
        SCOPED_TRACE(std::string(method) + ", " + speed + ", C of " + std::to_string(c.size()) + " digits");
        const auto r = run_uniparam({"sample", curve(c), "--method", method, "--speed", speed, "--points", "5",
                                     "--json", "--timeout", kTimeout});
        ASSERT_EQ(r.exit_code, 0) << r.err;
        const auto rows = sample_rows(r.out);
        ASSERT_EQ(rows.size(), 5u) << r.out.substr(0, 600);
        expect_rows(rows, [&c](const std::vector<Ball>& row) {
          const Ball& t = row[1];
          EXPECT_TRUE(on_curve(t, row[2], row[3], c));
          EXPECT_TRUE(t.meets_digits(15)) << t.str(20);
          EXPECT_TRUE((arb_is_positive(t.get()) || arb_contains_si(t.get(), 0)) &&
                      (arb_lt(t.get(), Ball(1).get()) || arb_contains_si(t.get(), 1)))
              << t.str(20);
          if (row.size() >= 5) EXPECT_TRUE(row[4].is_finite() && arb_is_positive(row[4].get())) << row[4].str(20);
        });
        EXPECT_TRUE(arb_is_zero(rows.front()[1].get())) << rows.front()[1].str(20);  // read back exactly
        EXPECT_TRUE(arb_contains_si(rows.back()[1].get(), 1)) << rows.back()[1].str(20);
      }
}

// Must show: the exactly uniform points (sample --method exact, angular)
// and locate --fraction 1/3 contain the closed form tan(f pi / 2) / (2 C)
// of their t, with the points on the curve.
TEST(HugeCoeffCli, ExactPointsAndLocateMatchTheClosedForm) {
  const long K = 5;
  const auto r = run_uniparam({"sample", curve(), "--method", "exact", "--points", std::to_string(K), "--json",
                               "--timeout", kTimeout});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = sample_rows(r.out);
  ASSERT_EQ(rows.size(), static_cast<std::size_t>(K)) << r.out.substr(0, 600);
  for (long k = 1; k + 1 < K; ++k) {
    const auto& row = rows[static_cast<std::size_t>(k)];
    ASSERT_GE(row.size(), 4u);
    const Ball ref = uniform_t(Rational(k, K - 1));
    EXPECT_TRUE(arb_overlaps(row[1].get(), ref.get())) << k << ": " << row[1].str(20) << " vs " << ref.str(20);
    EXPECT_TRUE(row[1].meets_digits(15)) << row[1].str(20);
    EXPECT_TRUE(on_curve(row[1], row[2], row[3])) << k;
  }
  const auto l = run_uniparam({"locate", curve(), "--fraction", "1/3", "--json", "--timeout", kTimeout});
  ASSERT_EQ(l.exit_code, 0) << l.err;
  Ball t;
  ASSERT_TRUE(json_ball(l.out, "t", t)) << l.out.substr(0, 400);
  const Ball ref = uniform_t(Rational(1, 3));
  EXPECT_TRUE(arb_overlaps(t.get(), ref.get())) << t.str(20) << " vs " << ref.str(20);
  EXPECT_TRUE(t.meets_digits(15)) << t.str(20);
}

// Must show: radical --at 1/3 prints r(z) and p(r(z)) on the curve, and
// plot writes its SVG, both with exit 0.
TEST(HugeCoeffCli, RadicalAtAndPlotFinish) {
  const auto r = run_uniparam({"radical", curve(), "--at", "1/3", "--json", "--timeout", kTimeout});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::size_t at = r.out.find("\"at\"");
  ASSERT_NE(at, std::string::npos) << r.out.substr(0, 400);
  const std::vector<Ball> b = balls_in(r.out.substr(at));
  ASSERT_GE(b.size(), 4u);  // z, r, p_r (x, y), speed
  EXPECT_TRUE(on_curve(b[1], b[2], b[3]));
  EXPECT_TRUE(b[1].meets_digits(15)) << b[1].str(20);
  const auto p = run_uniparam({"plot", curve(), "-o", "-", "--timeout", kTimeout});
  ASSERT_EQ(p.exit_code, 0) << p.err;
  EXPECT_NE(p.out.find("<svg"), std::string::npos);
  EXPECT_NE(p.out.find("</svg>"), std::string::npos);
}

// Must show: the exactly uniform points and locate on a conic arc of the
// unit circle whose weights 5, 3 L, 5 L^2 grow like L = 2^600 finish with
// exit 0 (both speeds), their points on the circle and their t increasing.
TEST(HugeCoeffCli, GeometricWeightsExactPointsAndLocate) {
  Rational L(1);
  for (int i = 0; i < 600; ++i) L = L * Rational(2);
  const std::string weights = "[5," + (Rational(3) * L).str() + "," + (Rational(5) * L * L).str() + "]";
  const std::vector<std::string> arc{"--control", "[[1,0],[1,4/3],[-7/25,24/25]]", "--weights", weights};
  auto on_circle = [](const Ball& x, const Ball& y) {
    Ball s, t;
    arb_sqr(s.get(), x.get(), 256);
    arb_sqr(t.get(), y.get(), 256);
    arb_add(s.get(), s.get(), t.get(), 256);
    return arb_contains_si(s.get(), 1) != 0;
  };
  for (const char* speed : {"parametric", "angular"}) {
    SCOPED_TRACE(speed);
    std::vector<std::string> args{"sample", "--method", "exact", "--points", "5", "--json", "--speed", speed,
                                  "--timeout", kTimeout};
    args.insert(args.end(), arc.begin(), arc.end());
    const auto r = run_uniparam(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto rows = sample_rows(r.out);
    ASSERT_EQ(rows.size(), 5u) << r.out.substr(0, 600);
    expect_rows(rows, [&on_circle](const std::vector<Ball>& row) {
      EXPECT_TRUE(on_circle(row[2], row[3])) << row[2].str(20) << ", " << row[3].str(20);
    });
    std::vector<std::string> largs{"locate", "--fraction", "1/3", "--json", "--speed", speed, "--timeout", kTimeout};
    largs.insert(largs.end(), arc.begin(), arc.end());
    const auto l = run_uniparam(largs);
    ASSERT_EQ(l.exit_code, 0) << l.err;
    const std::size_t at = l.out.find("\"point\"");
    ASSERT_NE(at, std::string::npos) << l.out.substr(0, 400);
    const std::vector<Ball> xy = balls_in(l.out.substr(at));
    ASSERT_EQ(xy.size(), 2u);
    EXPECT_TRUE(on_circle(xy[0], xy[1])) << xy[0].str(20) << ", " << xy[1].str(20);
  }
}

// Must show: the C1 method with the parametric speed on (C t, t^3), whose
// speed sqrt(C^2 + 9 t^4) and integrals (about C and C^2) are beyond
// double's range, reaches its target with exit 0.
TEST(HugeCoeffCli, ParametricTargetOnAHugeLine) {
  const auto r = run_uniparam({"reparam", "(" + big_c() + "*t, t^3)", "--speed", "parametric", "--target", "0.99",
                               "--timeout", kTimeout});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("reached with"), std::string::npos) << r.out.substr(0, 600);
  EXPECT_EQ(r.out.find("NOT reached"), std::string::npos);
}
