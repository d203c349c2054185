// The Moebius, reparam and radical commands on rational Bezier curves whose
// weights grow geometrically (the issue's quarter circle's control points
// with weights 1, 8e40, 1e82; circle arcs with weights 2^600 apart): each
// finishes with exit 0 under a generous --timeout (the issue's commands ran
// into the time limit before), and what it prints is consistent: mu and
// u_before agree with `uniformity`, 0 < u_after <= 1 and u_after >= u_before,
// the sample points p(r(s)) of every method lie on the circle, and the
// exact NURBS of p o r is written.
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::json_ball;
using uniparam::test_support::run_uniparam;

namespace {

const char* kTimeout = "300";  // generous: each command takes well under a second

const std::vector<std::string> kIssue{"--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,8e40,1e82]"};

// The arc of angle 2 atan(4/3) on the unit circle with weights 1, 3/5 L, L^2
// (L = 2^e, or reversed): x^2 + y^2 = 1 exactly.
std::vector<std::string> arc(long e, bool falling) {
  Rational L(1);
  for (long i = 0; i < e; ++i) L = L * Rational(2);
  // weights times 5: 5, 3 L, 5 L^2 (a common factor does not change the curve)
  const std::string w0 = "5", w1 = (Rational(3) * L).str(), w2 = (Rational(5) * L * L).str();
  const std::string weights = falling ? "[" + w2 + "," + w1 + "," + w0 + "]" : "[" + w0 + "," + w1 + "," + w2 + "]";
  return {"--control", "[[1,0],[1,4/3],[-7/25,24/25]]", "--weights", weights};
}

std::vector<std::string> cat(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

}  // namespace

// Must show: the issue's commands (moebius, reparam --pieces 3, reparam
// --target 0.99, radical; both speeds) exit 0, and their mu and u_before
// agree with `uniformity`, with 0 < u_before <= u_after <= 1.
TEST(BalancedCli, IssueCommandsFinishConsistently) {
  for (const char* speed : {"parametric", "angular"}) {
    const auto u = run_uniparam(cat({"uniformity", "--json", "--speed", speed, "--timeout", kTimeout}, kIssue));
    ASSERT_EQ(u.exit_code, 0) << u.err;
    Ball mu, ub;
    ASSERT_TRUE(json_ball(u.out, "mu", mu));
    ASSERT_TRUE(json_ball(u.out, "u", ub));
    for (const std::vector<std::string>& cmd : std::vector<std::vector<std::string>>{
             {"moebius"}, {"reparam", "--pieces", "3"}, {"reparam", "--target", "0.99"}, {"radical"}}) {
      SCOPED_TRACE(cmd[0] + (cmd.size() > 1 ? " " + cmd[1] : std::string()) + ", " + speed);
      const auto r = run_uniparam(cat(cat(cmd, {"--json", "--speed", speed, "--timeout", kTimeout}), kIssue));
      ASSERT_EQ(r.exit_code, 0) << r.err;
      Ball m, before, after;
      ASSERT_TRUE(json_ball(r.out, "mu", m));
      ASSERT_TRUE(json_ball(r.out, "u_before", before));
      ASSERT_TRUE(json_ball(r.out, "u_after", after));
      EXPECT_TRUE(arb_overlaps(m.get(), mu.get())) << m.str(20) << " vs " << mu.str(20);
      EXPECT_TRUE(arb_overlaps(before.get(), ub.get())) << before.str(20) << " vs " << ub.str(20);
      Ball one(1);
      EXPECT_TRUE(arb_is_positive(after.get()));
      EXPECT_FALSE(arb_gt(after.get(), one.get()));
      EXPECT_FALSE(arb_lt(after.get(), before.get()));
    }
  }
}

// Must show: on circle arcs with weights 2^600 apart (rising and falling),
// the points p(r(s)) that `sample` prints for every method lie on the unit
// circle, and the exact rational map's NURBS (--rational --output nurbs) and
// the C1 map's ball NURBS are written (exit 0).
TEST(BalancedCli, SamplesLieOnTheCircleAndNurbsIsWritten) {
  for (bool falling : {false, true}) {
    const std::vector<std::string> curve = arc(600, falling);
    for (const char* speed : {"parametric", "angular"}) {
      for (const char* method : {"radical", "c0", "c1"}) {
        SCOPED_TRACE(std::string(method) + ", " + speed + (falling ? ", falling" : ", rising"));
        const auto r = run_uniparam(
            cat({"sample", "--method", method, "--points", "9", "--speed", speed, "--timeout", kTimeout}, curve));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        std::istringstream in(r.out);
        std::string line;
        std::getline(in, line);
        EXPECT_EQ(line, "s,t,x,y,speed");
        int rows = 0;
        while (std::getline(in, line)) {
          double v[5];
          // the speed is empty at a joint where the map is only C0
          ASSERT_GE(std::sscanf(line.c_str(), "%lf,%lf,%lf,%lf,%lf", &v[0], &v[1], &v[2], &v[3], &v[4]), 4) << line;
          EXPECT_NEAR(v[2] * v[2] + v[3] * v[3], 1.0, 1e-12) << line;
          EXPECT_TRUE(v[1] >= 0 && v[1] <= 1) << line;
          ++rows;
        }
        EXPECT_EQ(rows, 9);
      }
      for (const std::vector<std::string>& cmd : std::vector<std::vector<std::string>>{
               {"reparam", "--pieces", "3", "--rational", "--output", "nurbs"},
               {"reparam", "--target", "0.99", "--output", "nurbs"}}) {
        SCOPED_TRACE(cmd[1] + ", " + speed);
        const auto r = run_uniparam(cat(cat(cmd, {"--speed", speed, "--timeout", kTimeout}), curve));
        ASSERT_EQ(r.exit_code, 0) << r.err;
        EXPECT_NE(r.out.find("\"type\": \"nurbs\""), std::string::npos);
      }
    }
  }
}
