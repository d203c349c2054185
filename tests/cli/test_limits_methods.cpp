// The methods that integrate pieces (radical, moebius, reparam --pieces)
// on a curve with a huge coefficient: (t, C t^2) with a 5000-digit C, whose
// angular speed K / (1 + K^2 t^2) (K = 2 C) has a peak of width 1 / K at 0
// and is about 2^-6650 times smaller on the rest of [0, 1]. "Finishes" is
// checked with a generous --timeout and exit 0, never by timing; each
// result must contain an independent closed-form value.
#include <gtest/gtest.h>

#include <arb.h>

#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/reference.hpp"
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


// u = mu^2 / int sigma^2 of the angular speed K / (1 + K^2 t^2) on [0, 1]:
// mu = atan K, int sigma^2 = (K / 2) (atan K + K / (1 + K^2)).
Ball angular_u(const std::string& c) {
  Ball b;
  arb_set_str(b.get(), c.c_str(), kPrec);
  return uniparam::test_support::parabola_angular(b, kPrec).u;
}

}  // namespace

// Must show: radical, moebius and reparam --pieces 3 certify (t, C t^2) with
// a 5000-digit C under the angular speed: u before (from the pieces'
// integrals) contains the closed form above, and u after is at least u
// before and at most 1.
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
  }
}

// Must show: reparam --target on the same curve reaches the target: it runs
// on the balanced curve q = p o m (reparam/scaling.hpp), whose integrals
// its floating-point breakpoint search can represent; u before contains the
// closed form and u after is at least 0.99.
TEST(CliLimitsMethods, HugeCoefficientTargetIsReached) {
  const std::string c(5000, '7');
  auto r = run_uniparam({"reparam", "(t, " + c + "*t^2)", "--target", "0.99", "--json", "--timeout", "120"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Ball before, after;
  ASSERT_TRUE(json_ball(r.out, "u_before", before)) << r.out.substr(0, 400);
  ASSERT_TRUE(json_ball(r.out, "u_after", after));
  const Ball ref = angular_u(c);
  EXPECT_TRUE(arb_overlaps(before.get(), ref.get())) << before.str(20) << " vs " << ref.str(20);
  EXPECT_TRUE(arb_ge(after.get(), Ball(Rational(99, 100), 64).get())) << after.str(20);
}
