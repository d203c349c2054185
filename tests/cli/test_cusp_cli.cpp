// `uniparam` on cusp curves (p'(c) = 0 at a rational c inside [0, 1] or at an
// end; the angular speed is finite and nonzero there after cancellation):
// every command succeeds (exit 0, nothing on stderr) with either speed, from a
// formula or from Bezier control points, and the C1 target finishes and is
// certified.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Rational;
using uniparam::test_support::certified_real;
using uniparam::test_support::run_uniparam;

namespace {

// Cusps inside and at the ends, plane and space, of orders 1 to 3.
const std::vector<std::string> kCusps = {
    "((t-1/2)^2, (t-1/2)^3)",
    "((t-1/3)^3, (t-1/3)^4 + (t-1/3)^5)",
    "((t-1)^2, (t-1)^3)",
    "((t-1)^3, (t-1)^4)",
    "((t-5/7)^4, (t-5/7)^5)",
    "((t-1)^2, (t-1)^3, (t-1)^4)",
    "((t-3/8)^2, (t-3/8)^3, (t-3/8)^4)",
};

// (t - 1/2)^2 and (t - 1/2)^3 in the cubic Bernstein basis, times 24.
const char* kBezierCusp = "[[6,-3],[-2,3],[-2,-3],[6,3]]";

// mid - rad of the certified real `key`, exactly.
Rational lower_bound(const std::string& json, const std::string& key) {
  std::string mid, rad;
  if (!certified_real(json, key, mid, rad)) return Rational(-1);
  return Rational::parse(mid) - Rational::parse(rad);
}

}  // namespace

TEST(CliCusp, EveryCommandSucceedsOnCuspsWithEitherSpeed) {
  const std::vector<std::vector<std::string>> commands = {
      {"uniformity"}, {"radical"}, {"moebius"}, {"moebius", "--breakpoints", "0,1/2,1"},
      {"reparam", "--pieces", "3"}, {"sample", "--points", "5"}, {"sample", "--points", "5", "--method", "c0"}};
  for (const std::string& c : kCusps)
    for (const char* speed : {"angular", "parametric"})
      for (const auto& cmd : commands) {
        std::vector<std::string> args = cmd;
        args.insert(args.begin() + 1, c);
        for (const char* a : {"--speed", speed, "--timeout", "120"}) args.push_back(a);
        const auto r = run_uniparam(args);
        EXPECT_EQ(r.exit_code, 0) << cmd[0] << " " << c << " " << speed << ": " << r.err;
        EXPECT_TRUE(r.err.empty()) << cmd[0] << " " << c << " " << speed << ": " << r.err;
      }
}

TEST(CliCusp, PlotSucceedsOnACusp) {
  char name[] = "/tmp/uniparam_cusp_plot_XXXXXX";
  const int fd = mkstemp(name);
  ASSERT_GE(fd, 0);
  close(fd);
  const std::string path = std::string(name) + ".svg";
  const auto r = run_uniparam({"plot", "((t-1/2)^2, (t-1/2)^3)", "-o", path, "--timeout", "120"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  std::remove(name);
  std::remove(path.c_str());
}

TEST(CliCusp, EveryCommandSucceedsOnABezierCusp) {
  for (const char* cmd : {"uniformity", "radical", "moebius", "reparam", "sample"}) {
    std::vector<std::string> args{cmd, "--control", kBezierCusp, "--timeout", "120"};
    if (std::string(cmd) == "reparam") {
      args.push_back("--target");
      args.push_back("0.99");
    }
    const auto r = run_uniparam(args);
    EXPECT_EQ(r.exit_code, 0) << cmd << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << cmd << ": " << r.err;
  }
}

// The C1 refinement on cusps (at the right end and inside, rational and
// irrational: the optimiser's double evaluations of the uncancelled speed
// are 0/0 noise near them) finishes and certifies the target, as on
// (t^2, t^3).
TEST(CliCusp, TargetFinishesAndIsCertifiedOnCusps) {
  const std::vector<std::string> curves = {
      "((t-1)^2, (t-1)^3)",        "((t-1)^3, (t-1)^4)",     "((t-1)^2, (t-1)^3, (t-1)^4)",
      "(t^2, t^3)",                "((t-1/2)^2, (t-1/2)^3)", "((t-1/3)^3, (t-1/3)^4 + (t-1/3)^5)",
      "((t-5/7)^4, (t-5/7)^5)",    "((t-3/8)^2, (t-3/8)^3, (t-3/8)^4)", "((t^2-1/2)^2, (t^2-1/2)^3)"};
  for (const std::string& c : curves) {
    for (const char* target : {"0.99", "0.999"}) {
      const auto r = run_uniparam({"reparam", c, "--target", target, "--json", "--timeout", "120"});
      ASSERT_EQ(r.exit_code, 0) << c << " " << target << ": " << r.err;
      EXPECT_NE(r.out.find("\"reached\": true"), std::string::npos) << c;
      EXPECT_GE(lower_bound(r.out, "u_after"), Rational::parse(target)) << c;
    }
  }
}
