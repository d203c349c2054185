// The advertised limits work with the default options: --digits up to its
// advertised maximum, curves up to the default --max-degree (sparse and
// dense) finish, and huge coefficients or weights are certified. "Finishes"
// is checked with a generous --timeout and exit 0, never by timing; each
// result must contain an independent closed-form value.
#include <gtest/gtest.h>

#include <arb.h>

#include <regex>
#include <string>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Ball;
using uniparam::test_support::json_ball;
using uniparam::test_support::encloses;
using uniparam::test_support::run_uniparam;

namespace {

// The default of `option` printed by `uniparam uniformity --help`.
long help_default(const std::string& option) {
  const auto h = run_uniparam({"uniformity", "--help"});
  std::smatch m;
  const std::regex re("--" + option + " [A-Z]+[^\\n]*\\(default: ([0-9]+)");
  if (!std::regex_search(h.out, m, re)) return -1;
  return std::stol(m[1]);
}


}  // namespace

// The largest --digits that `uniformity --help` advertises ("D, 1 to N").
long help_max_digits() {
  const auto h = run_uniparam({"uniformity", "--help"});
  std::smatch m;
  if (!std::regex_search(h.out, m, std::regex("--digits D [^\\n]*1 to ([0-9]+)"))) return -1;
  return std::stol(m[1]);
}

// Must show: the advertised maximum of --digits is accepted with the default
// --max-prec, and met on a curve whose integrals need the quadrature's
// highest rules: (t, t^3) turns its tangent by atan(3) in all (y'' >= 0), so
// mu = atan(3) under the angular speed. One digit more is refused as an
// invalid option, and an explicit --max-prec below what the digits need is
// refused at once.
TEST(CliLimits, AdvertisedMaxDigitsAcceptedByDefault) {
  const long digits = help_max_digits();
  ASSERT_GE(digits, 1000);
  const std::string ds = std::to_string(digits);
  auto r = run_uniparam({"uniformity", "(t, t^3)", "--digits", ds, "--json", "--timeout", "300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // atan(3) to digits + 40 digits, read exactly with that slack.
  Ball ref;
  arb_set_si(ref.get(), 3);
  arb_atan(ref.get(), ref.get(), 4 * digits + 256);
  char* text = arb_get_str(ref.get(), digits + 40, ARB_STR_NO_RADIUS);
  const std::string ref_text(text);
  flint_free(text);
  const std::string slack = "1e-" + std::to_string(digits + 38);
  EXPECT_TRUE(encloses(r.out, "mu", ref_text.c_str(), slack.c_str(), digits));

  auto over = run_uniparam({"uniformity", "(t, t^3)", "--digits", std::to_string(digits + 1)});
  EXPECT_EQ(over.exit_code, 2) << over.err;
  EXPECT_NE(over.err.find("--digits must be between 1 and " + ds), std::string::npos) << over.err;
  auto low = run_uniparam({"uniformity", "(t, t^3)", "--digits", ds, "--max-prec", "4096"});
  EXPECT_EQ(low.exit_code, 4);
  EXPECT_NE(low.err.find("--max-prec"), std::string::npos) << low.err;
}

// Must show: curves of the default --max-degree N finish under the default
// options, sparse (t, t^N) and dense (t, (1+t)^N), and their mean angular
// speed is the total turning of the tangent, atan(y'(1)) - atan(y'(0)):
// atan(N) and atan(N 2^(N-1)) - atan(N) (y'' >= 0 on [0, 1]: the tangent
// turns one way).
TEST(CliLimits, DefaultMaxDegreeFinishes) {
  const long n = help_default("max-degree");
  ASSERT_GT(n, 2);
  const std::string ns = std::to_string(n);
  const long prec = 128;
  for (bool dense : {false, true}) {
    const std::string curve = dense ? "(t, (1+t)^" + ns + ")" : "(t, t^" + ns + ")";
    auto r = run_uniparam({"uniformity", curve, "--json", "--timeout", "300"});
    ASSERT_EQ(r.exit_code, 0) << curve << ": " << r.err;
    Ball mu, ref, a0, a1;
    ASSERT_TRUE(json_ball(r.out, "mu", mu)) << r.out;
    arb_set_si(a0.get(), n);
    arb_atan(a0.get(), a0.get(), prec);
    if (dense) {
      arb_set_si(a1.get(), n);
      arb_mul_2exp_si(a1.get(), a1.get(), n - 1);
      arb_atan(a1.get(), a1.get(), prec);
      arb_sub(ref.get(), a1.get(), a0.get(), prec);
    } else {
      arb_set(ref.get(), a0.get());
    }
    EXPECT_TRUE(arb_overlaps(mu.get(), ref.get())) << curve << ": " << mu.str(20) << " vs " << ref.str(20);
  }
}

// Must show: the huge numbers of the reliability issue are certified within
// a generous --timeout: (t, C t^2) with a 5000-digit C (mu = atan(2C) under
// the angular speed) and the conic with weights 1, 8e40, 1e82 under the
// parametric speed, whose arc length is that of weights 1, 4/5, 1 (the same
// arc, reparameterized by a Moebius map).
TEST(CliLimits, HugeCoefficientsAndWeightsAreCertified) {
  const std::string c(5000, '7');
  auto r = run_uniparam({"uniformity", "(t, " + c + "*t^2)", "--json", "--timeout", "300"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  Ball mu, ref;
  ASSERT_TRUE(json_ball(r.out, "mu", mu));
  arb_set_str(ref.get(), c.c_str(), 20000);
  arb_mul_2exp_si(ref.get(), ref.get(), 1);
  arb_atan(ref.get(), ref.get(), 128);
  EXPECT_TRUE(arb_overlaps(mu.get(), ref.get())) << mu.str(20);

  const char* control = "[[1,0],[1,1],[0,1]]";
  auto big = run_uniparam({"uniformity", "--control", control, "--weights", "[1,8e40,1e82]", "--speed", "parametric",
                           "--json", "--timeout", "300"});
  ASSERT_EQ(big.exit_code, 0) << big.err;
  auto std_form = run_uniparam({"uniformity", "--control", control, "--weights", "[1,4/5,1]", "--speed",
                                "parametric", "--json"});
  ASSERT_EQ(std_form.exit_code, 0) << std_form.err;
  Ball mu_big, mu_std;
  ASSERT_TRUE(json_ball(big.out, "mu", mu_big));
  ASSERT_TRUE(json_ball(std_form.out, "mu", mu_std));
  EXPECT_TRUE(arb_overlaps(mu_big.get(), mu_std.get())) << mu_big.str(20) << " vs " << mu_std.str(20);
}
