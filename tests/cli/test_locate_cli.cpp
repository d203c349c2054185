// `uniparam locate`: the printed balls contain independent values (closed
// forms evaluated with Arb at 400 bits), and bad requests fail clearly.
#include <gtest/gtest.h>

#include <arb.h>

#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::certified_real;
using uniparam::test_support::run_uniparam;

namespace {

constexpr long kPrec = 400;

// The ball [mid - rad, mid + rad] of a JSON certified real, read exactly:
// the index-th occurrence of key (0 = first).
Ball json_ball_at(const std::string& json, const std::string& key, std::size_t index = 0) {
  std::size_t pos = json.find("\"" + key + "\": {");
  for (std::size_t i = 0; i < index && pos != std::string::npos; ++i) pos = json.find("\"" + key + "\": {", pos + 1);
  std::string mid, rad;
  if (pos == std::string::npos || !certified_real(json.substr(pos), key, mid, rad)) {
    ADD_FAILURE() << "no certified real " << key << " #" << index << " in " << json;
    return Ball(0);
  }
  Ball b(Rational::parse(mid), kPrec), r(Rational::parse(rad), kPrec);
  arb_add_error(b.get(), r.get());
  return b;
}

// The i-th ball of the "point" array.
Ball point_component(const std::string& json, std::size_t i) {
  std::size_t pos = json.find("\"point\"");
  for (std::size_t k = 0; k < i; ++k) pos = json.find('}', pos) + 1;
  std::string mid, rad;
  const std::string rest = "{\"c\": " + json.substr(json.find('{', pos));
  if (!certified_real(rest, "c", mid, rad)) {
    ADD_FAILURE() << "no point component " << i;
    return Ball(0);
  }
  Ball b(Rational::parse(mid), kPrec), r(Rational::parse(rad), kPrec);
  arb_add_error(b.get(), r.get());
  return b;
}

bool radius_meets(const Ball& b, long digits) {
  // rad <= 10^-digits for values in [-1, 1] (t and the points below)
  Ball bound;
  arb_set_ui(bound.get(), 10);
  arb_pow_ui(bound.get(), bound.get(), static_cast<ulong>(digits), kPrec);
  arb_inv(bound.get(), bound.get(), kPrec);
  Ball r;
  arf_set_mag(arb_midref(r.get()), arb_radref(b.get()));
  arb_sub(r.get(), bound.get(), r.get(), kPrec);
  return !r.certainly_negative();
}

// (asinh(2t) + 2t sqrt(1 + 4t^2)) / 4, the arc length of (t, t^2) from 0.
Ball parabola_length(const Ball& t) {
  Ball a, b, r;
  arb_mul_2exp_si(a.get(), t.get(), 1);
  arb_asinh(r.get(), a.get(), kPrec);
  arb_mul(b.get(), a.get(), a.get(), kPrec);
  arb_add_ui(b.get(), b.get(), 1, kPrec);
  arb_sqrt(b.get(), b.get(), kPrec);
  arb_mul(b.get(), b.get(), a.get(), kPrec);
  arb_add(r.get(), r.get(), b.get(), kPrec);
  arb_mul_2exp_si(r.get(), r.get(), -2);
  return r;
}

// Its inverse at y by 300 bisection steps on certified signs.
Ball parabola_inverse(const Ball& y) {
  Ball lo(0), hi(1);
  for (int i = 0; i < 300; ++i) {
    Ball m, d;
    arb_add(m.get(), lo.get(), hi.get(), kPrec);
    arb_mul_2exp_si(m.get(), m.get(), -1);
    arb_sub(d.get(), parabola_length(m).get(), y.get(), kPrec);
    if (d.certainly_negative()) lo = m;
    else if (d.certainly_positive()) hi = m;
    else break;
  }
  Ball u;
  arb_union(u.get(), lo.get(), hi.get(), kPrec);
  return u;
}

}  // namespace

TEST(LocateCli, CircleAngleGivesTanOfHalfAngleAndCosSin) {
  const auto r = run_uniparam({"locate", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "--angle", "1/2", "--digits", "30",
                               "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  Ball half(Rational(1, 4), kPrec), tref, c, s;
  arb_tan(tref.get(), half.get(), kPrec);
  const Ball t = json_ball_at(r.out, "t");
  EXPECT_TRUE(t.contains(tref)) << r.out;
  EXPECT_TRUE(radius_meets(t, 30)) << r.out;
  Ball a(Rational(1, 2), kPrec);
  arb_sin_cos(s.get(), c.get(), a.get(), kPrec);
  EXPECT_TRUE(point_component(r.out, 0).contains(c)) << r.out;
  EXPECT_TRUE(point_component(r.out, 1).contains(s)) << r.out;
}

TEST(LocateCli, ParabolaLengthAndFractionWithArclengthSpeed) {
  {
    const auto r = run_uniparam({"locate", "(t, t^2)", "--length", "1/2", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Ball t = json_ball_at(r.out, "t");
    EXPECT_TRUE(t.contains(parabola_inverse(Ball(Rational(1, 2), kPrec)))) << r.out;
    EXPECT_TRUE(radius_meets(t, 15));
  }
  {
    const auto r = run_uniparam({"locate", "(t, t^2)", "--fraction", "1/3", "--speed", "arclength", "--json",
                                 "--digits", "25"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    Ball y = parabola_length(Ball(1));
    arb_div_ui(y.get(), y.get(), 3, kPrec);
    const Ball t = json_ball_at(r.out, "t");
    EXPECT_TRUE(t.contains(parabola_inverse(y))) << r.out;
    EXPECT_TRUE(radius_meets(t, 25));
    EXPECT_NE(r.out.find("\"speed\": \"parametric\""), std::string::npos) << r.out;
  }
}

// Half the length of a cusp curve is reached at the cusp, a zero of sigma.
TEST(LocateCli, CuspHalfLengthIsTheCusp) {
  const auto r = run_uniparam({"locate", "((2t-1)^2, (2t-1)^3)", "--fraction", "1/2", "--speed", "parametric",
                               "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(json_ball_at(r.out, "t").contains(Rational(1, 2))) << r.out;
  EXPECT_TRUE(radius_meets(json_ball_at(r.out, "t"), 15));
}

// (t, t^3): the angular speed vanishes at t = 0; angle atan(3 t^2).
TEST(LocateCli, AngleFromAnInflection) {
  const auto r = run_uniparam({"locate", "(t, t^3)", "--angle", "1/4", "--json", "--digits", "20"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Ball ref(Rational(1, 4), kPrec);
  arb_tan(ref.get(), ref.get(), kPrec);
  arb_div_ui(ref.get(), ref.get(), 3, kPrec);
  arb_sqrt(ref.get(), ref.get(), kPrec);
  EXPECT_TRUE(json_ball_at(r.out, "t").contains(ref)) << r.out;
}

TEST(LocateCli, BadRequestsFailClearly) {
  struct Case {
    std::vector<std::string> args;
    int code;
    const char* says;
  };
  const Case cases[] = {
      {{"locate", "(t, t^2)", "--length", "2"}, 2, "mu ="},  // beyond the length 1.4789...
      {{"locate", "(t, t^2)", "--length", "-1/10"}, 2, "--length"},
      {{"locate", "(t, t^2)", "--fraction", "3/2"}, 2, "[0, 1]"},
      {{"locate", "(t, t^2)", "--angle", "1/2", "--speed", "parametric"}, 2, "--angle"},
      {{"locate", "(t, t^2)", "--angle", "1/2", "--speed", "arclength"}, 2, "--angle"},
      {{"locate", "(t, t^2)", "--length", "1/2", "--speed", "angular"}, 2, "--length"},
      {{"locate", "(t, t^2)"}, 2, "exactly one"},
      {{"locate", "(t, t^2)", "--length", "1", "--fraction", "1/2"}, 2, "exactly one"},
      {{"locate", "(t, t^2)", "--length", "abc"}, 2, "--length"},
      {{"locate", "(t, t^2)", "--fraction", "1/2", "--speed", "curvy"}, 2, "arclength"},
      {{"locate", "(t, 2t)", "--fraction", "1/2"}, 3, "straight line"},
      {{"locate", "(t, 2t)", "--angle", "0"}, 3, "straight line"},
  };
  for (const Case& c : cases) {
    const auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args[1] << " " << c.args.back() << ": " << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

// --speed arclength is the parametric speed for every command.
TEST(LocateCli, ArclengthIsParametricEverywhere) {
  const auto a = run_uniparam({"uniformity", "(t, t^2)", "--speed", "arclength"});
  const auto p = run_uniparam({"uniformity", "(t, t^2)", "--speed", "parametric"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  EXPECT_EQ(a.out, p.out);
}

// sample --method exact: row k's t contains the parabola's inverse arc
// length at k mu / (K - 1), computed independently.
TEST(SampleExactCli, ParabolaRowsAtEqualArcLength) {
  const long K = 9;
  const auto r = run_uniparam({"sample", "(t, t^2)", "--method", "exact", "--speed", "arclength", "--points",
                               std::to_string(K), "--json", "--digits", "20"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  const Ball mu = parabola_length(Ball(1));
  EXPECT_TRUE(json_ball_at(r.out, "mu").contains(mu)) << r.out;
  for (long k = 0; k < K; ++k) {
    Ball y;
    arb_mul_si(y.get(), mu.get(), k, kPrec);
    arb_div_si(y.get(), y.get(), K - 1, kPrec);
    const Ball t = json_ball_at(r.out, "t", static_cast<std::size_t>(k));
    const Ball ref = parabola_inverse(y);
    if (k == 0 || k == K - 1) EXPECT_TRUE(arb_overlaps(t.get(), ref.get())) << k;
    else EXPECT_TRUE(t.contains(ref)) << k << " " << r.out;
    EXPECT_TRUE(radius_meets(t, 20)) << k;
  }
}

// The circle's turning angle: t_k = tan(k (pi/2) / (K - 1) / 2).
TEST(SampleExactCli, CircleRowsAtEqualTurningAngle) {
  const long K = 5;
  const auto r = run_uniparam({"sample", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "--method", "exact", "--points",
                               std::to_string(K), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (long k = 1; k + 1 < K; ++k) {
    Ball ref;
    arb_const_pi(ref.get(), kPrec);
    arb_mul_si(ref.get(), ref.get(), k, kPrec);
    arb_div_si(ref.get(), ref.get(), 4 * (K - 1), kPrec);
    arb_tan(ref.get(), ref.get(), kPrec);
    EXPECT_TRUE(json_ball_at(r.out, "t", static_cast<std::size_t>(k)).contains(ref)) << k;
  }
}

// --deviation of the identity map (--method none) of the circle: row k sits
// at fraction (4/pi) atan(s) of the length, so its deviation is
// |(4/pi) atan(s) - s|; the CSV column is an upper bound of it.
TEST(SampleExactCli, DeviationOfTheIdentityMatchesAtan) {
  const long K = 5;
  const std::vector<std::string> base = {"sample", "((1-t^2)/(1+t^2), 2t/(1+t^2))", "--method", "none", "--speed",
                                         "arclength", "--points", std::to_string(K), "--deviation"};
  auto json_args = base;
  json_args.push_back("--json");
  const auto j = run_uniparam(json_args);
  const auto c = run_uniparam(base);
  ASSERT_EQ(j.exit_code, 0) << j.err;
  ASSERT_EQ(c.exit_code, 0) << c.err;
  Ball pi, worst(0);
  arb_const_pi(pi.get(), kPrec);
  std::size_t line_start = c.out.find('\n') + 1;
  for (long k = 0; k < K; ++k) {
    Ball s(Rational(k, K - 1), kPrec), d;
    arb_atan(d.get(), s.get(), kPrec);
    arb_mul_ui(d.get(), d.get(), 4, kPrec);
    arb_div(d.get(), d.get(), pi.get(), kPrec);
    arb_sub(d.get(), d.get(), s.get(), kPrec);
    arb_abs(d.get(), d.get());
    arb_max(worst.get(), worst.get(), d.get(), kPrec);
    EXPECT_TRUE(json_ball_at(j.out, "deviation", static_cast<std::size_t>(k)).contains(d)) << k;
    const std::size_t eol = c.out.find('\n', line_start);
    const std::string line = c.out.substr(line_start, eol - line_start);
    line_start = eol + 1;
    const Ball bound(Rational::parse(line.substr(line.rfind(',') + 1)), kPrec);
    Ball diff;
    arb_sub(diff.get(), bound.get(), d.get(), kPrec);
    EXPECT_FALSE(diff.certainly_negative()) << line;
  }
  EXPECT_TRUE(json_ball_at(j.out, "max_deviation").contains(worst)) << j.out;
  EXPECT_NE(c.out.find(",speed,deviation\n"), std::string::npos) << c.out;
}

TEST(SampleExactCli, BadCombinationsFailClearly) {
  struct Case {
    std::vector<std::string> args;
    int code;
    const char* says;
  };
  const Case cases[] = {
      {{"sample", "(t, t^2)", "--method", "exact", "--deviation"}, 2, "--deviation"},
      {{"sample", "(t, t^2)", "--method", "exact", "--pieces", "3"}, 2, "--pieces"},
      {{"sample", "(t, 2t)", "--method", "exact"}, 3, "straight line"},
      {{"sample", "(t, 2t)", "--method", "radical", "--deviation", "--speed", "angular"}, 3, "straight line"},
  };
  for (const Case& c : cases) {
    const auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, c.code) << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
  }
  const auto h = run_uniparam({"sample", "--help"});
  EXPECT_NE(h.out.find("--method exact --speed arclength"), std::string::npos) << h.out;
}
