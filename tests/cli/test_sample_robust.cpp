// Robust evaluation in the CLI: --rational with an optimal alpha near 0 or 1,
// `radical --at` and `sample` on an ill-conditioned but well-posed map (their
// values contain a reference computed to far more digits), exact ends, and
// the streamed output of `sample` (complete documents, write errors).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include "support/json.hpp"
#include "support/run.hpp"
#include "uniparam/reparam/all.hpp"

using namespace uniparam;
using uniparam::test_support::encloses;
using uniparam::test_support::run_uniparam;
using uniparam::test_support::shell_quote;

namespace {

const char* kSteep = "(t, 10000000000*(t-1/2)^3)";
const char* kEndsAtOrigin = "(t^2 - t, t^3 - 1)";  // p(1) = (0, 0)

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// The decimal text of a ball's midpoint as an exact rational, and its radius.
std::string mid_text(const Ball& b) { return mid_rational(b).str(); }

}  // namespace

TEST(SampleRobust, RationalAlphaNearZeroOrOneIsInsideTheUnitInterval) {
  for (const char* curve : {"(t, 1/(t - 1 - 1/1000000000))", "(t, 1/(t + 1/1000000000))"}) {
    SCOPED_TRACE(curve);
    auto r = run_uniparam({"moebius", curve, "--speed", "parametric", "--rational"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex("alpha = ([0-9]+)/([0-9]+)"))) << r.out;
    const Rational a = Rational::parse(m[1].str() + "/" + m[2].str());
    EXPECT_GT(a, Rational(0));
    EXPECT_LT(a, Rational(1));
  }
}

TEST(SampleRobust, RadicalAtOnAnIllConditionedMap) {
  // The map's data must be refined beyond the report's digits; the values
  // contain those of the same map computed to 60 digits.
  const Curve c = Curve::parse(kSteep);
  Options o;
  o.digits = 60;
  const RadicalResult fine = radical(c, SpeedKind::Angular, o);
  const Speed sp(c, SpeedKind::Angular);
  for (const char* z : {"1/10", "1/3", "9/10"}) {
    SCOPED_TRACE(z);
    for (long digits : {15L, 30L}) {
      auto r = run_uniparam({"radical", kSteep, "--at", z, "--json", "--digits", std::to_string(digits)});
      ASSERT_EQ(r.exit_code, 0) << r.err;
      const std::string at = r.out.substr(r.out.find("\"at\""));
      const Ball zb(Rational::parse(z), 600);
      const Ball t = eval_r(fine, zb, 600);
      const Ball v = eval_speed(fine, sp, zb, 600);
      ASSERT_TRUE(t.meets_digits(45) && v.meets_digits(45));
      EXPECT_TRUE(encloses(at, "r", mid_text(t).c_str(), t.rad_decimal().c_str(), digits));
      EXPECT_TRUE(encloses(at, "speed", mid_text(v).c_str(), v.rad_decimal().c_str(), digits));
    }
  }
}

TEST(SampleRobust, SampleOfAnIllConditionedMapSucceeds) {
  for (const char* method : {"radical", "c0"}) {
    SCOPED_TRACE(method);
    auto r = run_uniparam({"sample", kSteep, "--method", method, "--points", "11", "--digits", "20"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(count(r.out, "\n"), 12u);
  }
}

TEST(SampleRobust, ExactEndsPrintExactValues) {
  // r(1) = 1 exactly and p(1) = (0, 0): exact zeros, not balls around 1e-27.
  for (const char* method : {"radical", "c0", "c1"}) {
    SCOPED_TRACE(method);
    auto r = run_uniparam({"sample", kEndsAtOrigin, "--method", method, "--points", "2", "--json"});
    ASSERT_EQ(r.exit_code == 0 || r.exit_code == 4, true) << r.err;  // c1 may miss its target
    const std::string last = r.out.substr(r.out.rfind("\"s\": {"));
    EXPECT_NE(last.find("\"t\": {\n        \"mid\": \"1\",\n        \"rad\": \"0\""), std::string::npos) << last;
    EXPECT_EQ(count(last, "\"mid\": \"0\",\n          \"rad\": \"0\""), 2u) << last;
  }
  auto at = run_uniparam({"radical", kEndsAtOrigin, "--at", "1"});
  ASSERT_EQ(at.exit_code, 0) << at.err;
  EXPECT_NE(at.out.find("r(z) = 1\n  p(r(z)) = (0, 0)"), std::string::npos) << at.out;
}

TEST(SampleRobust, StreamedJsonIsOneCompleteDocument) {
  const long K = 7;
  auto r = run_uniparam({"sample", kEndsAtOrigin, "--points", std::to_string(K), "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(count(r.out, "\"at_joint\""), static_cast<std::size_t>(K));
  EXPECT_EQ(r.out.substr(0, 2), "{\n");
  EXPECT_EQ(r.out.substr(r.out.size() - 8), "}\n  ]\n}\n");
  EXPECT_EQ(count(r.out, "{"), count(r.out, "}"));
  EXPECT_EQ(count(r.out, "["), count(r.out, "]"));
}

TEST(SampleRobust, WriteErrorIsReported) {
  // /dev/full refuses every write: the command must not report success.
  const char* bin = std::getenv("UNIPARAM_BIN");
  char errname[] = "/tmp/uniparam_test_full_XXXXXX";
  const int fd = mkstemp(errname);
  ASSERT_GE(fd, 0);
  close(fd);
  for (const char* fmt : {"csv", "json"}) {
    SCOPED_TRACE(fmt);
    const std::string cmd = shell_quote(bin ? bin : "uniparam") + " sample " + shell_quote(kEndsAtOrigin) +
                            " --points 2000 --format " + fmt + " >/dev/full 2>" + errname;
    const int status = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_NE(WEXITSTATUS(status), 0);
    std::ifstream f(errname);
    std::stringstream ss;
    ss << f.rdbuf();
    EXPECT_NE(ss.str().find("cannot write"), std::string::npos) << ss.str();
  }
  std::remove(errname);
}
