// The methods that integrate pieces (radical, moebius, reparam --pieces)
// on a curve with a huge coefficient: (t, C t^2) with a 5000-digit C, whose
// angular speed K / (1 + K^2 t^2) (K = 2 C) has a peak of width 1 / K at 0
// and is about 2^-6650 times smaller on the rest of [0, 1]. "Finishes" is
// checked with a generous --timeout and exit 0, never by timing; each
// result must contain an independent closed-form value.
#include <gtest/gtest.h>

#include <arb.h>

#include <regex>
#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Ball;
using uniparam::Rational;
using uniparam::test_support::ball_of;
using uniparam::test_support::certified_real;
using uniparam::test_support::json_ball;
using uniparam::test_support::run_uniparam;

namespace {

constexpr long kPrec = 20000;  // enough for K^2 with K of 5000 digits


// Every certified real of the JSON array `key`.
std::vector<Ball> json_balls(const std::string& json, const std::string& key) {
  std::vector<Ball> out;
  const std::size_t at = json.find("\"" + key + "\": [");
  if (at == std::string::npos) return out;
  const std::size_t end = json.find(']', at);
  const std::string body = json.substr(at, end - at);
  const std::regex re("\"mid\": \"([^\"]+)\",\\s*\"rad\": \"([^\"]+)\"");
  for (std::sregex_iterator it(body.begin(), body.end(), re), last; it != last; ++it)
    out.push_back(ball_of((*it)[1], (*it)[2]));
  return out;
}

// u = mu^2 / int sigma^2 of the angular speed K / (1 + K^2 t^2) on [0, 1]:
// mu = atan K, int sigma^2 = (K / 2) (atan K + K / (1 + K^2)).
Ball angular_u(const std::string& c) {
  Ball k, at, t, sq, u;
  arb_set_str(k.get(), c.c_str(), kPrec);
  arb_mul_2exp_si(k.get(), k.get(), 1);
  arb_atan(at.get(), k.get(), kPrec);
  arb_sqr(t.get(), k.get(), kPrec);
  arb_add_ui(t.get(), t.get(), 1, kPrec);
  arb_div(t.get(), k.get(), t.get(), kPrec);
  arb_add(sq.get(), at.get(), t.get(), kPrec);
  arb_mul(sq.get(), sq.get(), k.get(), kPrec);
  arb_mul_2exp_si(sq.get(), sq.get(), -1);
  arb_sqr(u.get(), at.get(), kPrec);
  arb_div(u.get(), u.get(), sq.get(), kPrec);
  return u;
}

// x contains v up to slack 10^-1000.
bool near(const Ball& x, const Rational& v) {
  Ball w(v, 256), s;
  arb_set_str(s.get(), "1e-1000", 256);
  arb_add_error(w.get(), s.get());
  return arb_overlaps(x.get(), w.get());
}

}  // namespace

// Must show: radical, moebius and reparam --pieces 3 certify (t, C t^2) with
// a 5000-digit C under the angular speed: u before (from the pieces'
// integrals) contains the closed form above, u after is at least u before,
// and on the pieces [1/3, 2/3] and [2/3, 1] of reparam --pieces 3, where
// sigma = 1 / (K t^2) (1 + O(1 / K^2)), the optimal alpha is that of 1 / t^2,
// b / (a + b) (the Moebius map that makes 1 / t^2 uniform), up to
// O(1 / K^2) = 10^-10000: 2/3 and 3/5.
TEST(CliLimitsMethods, HugeCoefficientPiecesAreCertified) {
  const std::string c(5000, '7');
  const std::string curve = "(t, " + c + "*t^2)";
  const Ball ref = angular_u(c);
  for (const std::vector<std::string>& cmd : std::vector<std::vector<std::string>>{
           {"radical"}, {"moebius"}, {"reparam", "--pieces", "3"}}) {
    std::vector<std::string> args = cmd;
    for (const char* a : {"--json", "--timeout", "120"}) args.push_back(a);
    args.insert(args.begin() + 1, curve);
    auto r = run_uniparam(args);
    ASSERT_EQ(r.exit_code, 0) << cmd[0] << ": " << r.err;
    Ball before, after;
    ASSERT_TRUE(json_ball(r.out, "u_before", before)) << r.out.substr(0, 400);
    ASSERT_TRUE(json_ball(r.out, "u_after", after));
    EXPECT_TRUE(arb_overlaps(before.get(), ref.get())) << cmd[0] << ": " << before.str(20) << " vs " << ref.str(20);
    EXPECT_TRUE(arb_ge(after.get(), before.get())) << cmd[0] << ": " << after.str(20);
    EXPECT_TRUE(arb_le(after.get(), Ball(1).get()) || arb_contains_si(after.get(), 1)) << cmd[0];
    if (cmd.size() == 3) {
      const std::vector<Ball> alpha = json_balls(r.out, "alpha");
      ASSERT_EQ(alpha.size(), 3u) << r.out.substr(0, 400);
      EXPECT_TRUE(near(alpha[1], Rational(2, 3))) << alpha[1].str(20);
      EXPECT_TRUE(near(alpha[2], Rational(3, 5))) << alpha[2].str(20);
    }
  }
}

// Must show: reparam --target on the same curve ends with a certified map
// instead of running out of time: its floating-point search for breakpoints
// cannot represent integrals of 2^6650, so it stops, says so, and prints the
// best map (exit 4: target not reached), whose u before contains the closed
// form and whose u after is at least u before.
TEST(CliLimitsMethods, HugeCoefficientTargetEndsWithCertifiedMap) {
  const std::string c(5000, '7');
  auto r = run_uniparam({"reparam", "(t, " + c + "*t^2)", "--target", "0.99", "--json", "--timeout", "120"});
  ASSERT_EQ(r.exit_code, 4) << r.err;
  EXPECT_EQ(r.err.find("time limit"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("double's range"), std::string::npos) << r.err;
  Ball before, after;
  ASSERT_TRUE(json_ball(r.out, "u_before", before)) << r.out.substr(0, 400);
  ASSERT_TRUE(json_ball(r.out, "u_after", after));
  const Ball ref = angular_u(c);
  EXPECT_TRUE(arb_overlaps(before.get(), ref.get())) << before.str(20) << " vs " << ref.str(20);
  EXPECT_TRUE(arb_ge(after.get(), before.get())) << after.str(20);
}
