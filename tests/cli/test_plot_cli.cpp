// `uniparam plot` and `uniparam sample`: the SVG is well-formed and has the
// three panels, K samples in each curve panel, the breakpoints and joints of
// the method's result, captions with the certified uniformities; PNG through
// rsvg-convert (or a clear error naming librsvg2-bin); CSV and JSON samples
// agree with each other and with the curve.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/run.hpp"
#include "support/svg.hpp"
#include "uniparam/reparam/all.hpp"

using uniparam::Rational;
using uniparam::test_support::group;
using uniparam::test_support::run_uniparam;

namespace {

const char* kCubic = "(t, t^3)";
const char* kSlide = "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";
const char* kSpace = "((1-t^2)/(1+t^2), 2t/(1+t^2), t)";

std::string temp_path(const std::string& ext) {
  char name[] = "/tmp/uniparam_plot_test_XXXXXX";
  const int fd = mkstemp(name);
  if (fd >= 0) close(fd);
  std::remove(name);
  return std::string(name) + ext;
}

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

std::size_t count(const std::string& hay, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t i = hay.find(needle); i != std::string::npos; i = hay.find(needle, i + needle.size())) ++n;
  return n;
}

// A small XML well-formedness check: one root element, every tag closed in
// order, attribute values quoted, no raw '<' or stray '&' in text.
// True when x[i] starts an XML entity: &amp; &lt; &gt; &quot; &apos; &#123; &#x1F;
bool entity_at(const std::string& x, std::size_t i) {
  const std::size_t semi = x.find(';', i);
  if (semi == std::string::npos || semi - i > 12) return false;
  const std::string e = x.substr(i + 1, semi - i - 1);
  if (e == "amp" || e == "lt" || e == "gt" || e == "quot" || e == "apos") return true;
  if (e.size() >= 2 && e[0] == '#') {
    const bool hex = e[1] == 'x';
    const std::string digits = e.substr(hex ? 2 : 1);
    if (digits.empty()) return false;
    for (char c : digits)
      if (!(hex ? std::isxdigit(static_cast<unsigned char>(c)) : std::isdigit(static_cast<unsigned char>(c))))
        return false;
    return true;
  }
  return false;
}

// Length of ` name="value"` at x[j] (whitespace, a name, =, a quoted value
// without '<'), or 0 if there is none.
std::size_t attribute_length(const std::string& x, std::size_t j) {
  std::size_t k = j;
  while (k < x.size() && std::isspace(static_cast<unsigned char>(x[k]))) ++k;
  if (k == j || k >= x.size()) return 0;
  const auto name_start = [](char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == ':'; };
  const auto name_char = [&](char c) {
    return name_start(c) || std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '.';
  };
  if (!name_start(x[k])) return 0;
  while (k < x.size() && name_char(x[k])) ++k;
  if (k + 1 >= x.size() || x[k] != '=' || x[k + 1] != '"') return 0;
  const std::size_t close = x.find('"', k + 2);
  if (close == std::string::npos) return 0;
  if (x.find('<', k + 2) < close) return 0;
  return close + 1 - j;
}

::testing::AssertionResult well_formed(const std::string& x) {
  std::vector<std::string> stack;
  std::size_t i = 0, roots = 0;
  auto fail = [&](const std::string& why) {
    return ::testing::AssertionFailure() << why << " at offset " << i << ": "
                                         << x.substr(i, std::min<std::size_t>(80, x.size() - i));
  };
  while (i < x.size()) {
    if (x[i] != '<') {
      if (x[i] == '&' && !entity_at(x, i)) return fail("stray &");
      if (stack.empty() && !std::isspace(static_cast<unsigned char>(x[i]))) return fail("text outside the root");
      ++i;
      continue;
    }
    if (x.compare(i, 4, "<!--") == 0) {
      const std::size_t e = x.find("-->", i + 4);
      if (e == std::string::npos) return fail("unclosed comment");
      if (x.substr(i + 4, e - i - 4).find("--") != std::string::npos) return fail("-- inside a comment");
      i = e + 3;
      continue;
    }
    if (x.compare(i, 2, "<?") == 0) {
      const std::size_t e = x.find("?>", i);
      if (e == std::string::npos) return fail("unclosed declaration");
      i = e + 2;
      continue;
    }
    const bool closing = x[i + 1] == '/';
    std::size_t j = i + (closing ? 2 : 1);
    std::string name;
    while (j < x.size() && (std::isalnum(static_cast<unsigned char>(x[j])) || x[j] == '-' || x[j] == ':'))
      name += x[j++];
    if (name.empty()) return fail("tag without a name");
    // attributes: name="value" (scanned by hand: std::regex recurses per
    // character and overflows the stack on long attribute values under ASan)
    while (!closing) {
      const std::size_t n = attribute_length(x, j);
      if (n == 0) break;
      j += n;
    }
    while (j < x.size() && std::isspace(static_cast<unsigned char>(x[j]))) ++j;
    bool empty = false;
    if (x.compare(j, 2, "/>") == 0 && !closing) { empty = true; j += 2; }
    else if (j < x.size() && x[j] == '>') ++j;
    else return fail("malformed tag <" + name);
    if (closing) {
      if (stack.empty() || stack.back() != name) return fail("</" + name + "> closes nothing open");
      stack.pop_back();
    } else if (!empty) {
      if (stack.empty()) ++roots;
      stack.push_back(name);
    } else if (stack.empty()) {
      ++roots;
    }
    i = j;
  }
  if (!stack.empty()) return ::testing::AssertionFailure() << "unclosed <" << stack.back() << ">";
  if (roots != 1) return ::testing::AssertionFailure() << roots << " root elements";
  return ::testing::AssertionSuccess();
}


// The visible text of a fragment (tags dropped, entities left as they are).
std::string text_of(const std::string& frag) {
  std::string out;
  bool in_tag = false;
  for (char c : frag) {
    if (c == '<') in_tag = true;
    else if (c == '>') in_tag = false;
    else if (!in_tag) out += c;
  }
  return out;
}

struct JsonBall {
  Rational mid, rad;
};

// Every {"mid": ..., "rad": ...} in order.
std::vector<JsonBall> balls(const std::string& json) {
  std::vector<JsonBall> v;
  static const std::regex re("\"mid\": \"([^\"]+)\",\\s*\"rad\": \"([^\"]+)\"");
  for (auto it = std::sregex_iterator(json.begin(), json.end(), re); it != std::sregex_iterator(); ++it)
    v.push_back({Rational::parse((*it)[1]), Rational::parse((*it)[2])});
  return v;
}

JsonBall top_level(const std::string& json, const std::string& key) {
  const std::size_t k = json.find("\"" + key + "\":");
  EXPECT_NE(k, std::string::npos) << key;
  return balls(json.substr(k)).at(0);
}

double to_d(const Rational& q) { return std::stod(uniparam::decimal_string(q, 20)); }

struct PlotCase {
  std::string curve;
  std::vector<std::string> method;
  std::size_t dims;
};

// Number of pieces of the method's result, from `uniparam sample --json`.
std::size_t pieces_from_json(const std::string& json) {
  const std::size_t a = json.find("\"joints\""), b = json.find("\"samples\"");
  const std::size_t mids = count(json.substr(a, b - a), "\"mid\"");
  return mids / 2 - 1;  // joints s and t, N + 1 each
}

}  // namespace

TEST(PlotCli, SvgHasThreePanelsSamplesBreakpointsAndUniformities) {
  const long K = 40;
  const PlotCase cases[] = {
      {kCubic, {"--method", "radical"}, 2},
      {kSlide, {"--method", "c0", "--pieces", "3"}, 2},
      {kSpace, {"--method", "c0", "--pieces", "2"}, 3},
      {kSlide, {"--method", "c1", "--target", "0.99"}, 2},
  };
  for (const auto& pc : cases) {
    SCOPED_TRACE(pc.curve);
    const std::string path = temp_path(".svg");
    std::vector<std::string> args = {"plot", pc.curve, "--points", std::to_string(K), "-o", path};
    args.insert(args.end(), pc.method.begin(), pc.method.end());
    auto r = run_uniparam(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string svg = read_all(path);
    std::remove(path.c_str());
    ASSERT_EQ(svg.compare(0, 5, "<?xml"), 0);
    EXPECT_TRUE(well_formed(svg));
    EXPECT_NE(svg.find("<svg xmlns=\"http://www.w3.org/2000/svg\""), std::string::npos);
    EXPECT_EQ(svg.find("href"), std::string::npos) << "must be self-contained";

    // the method's own data, for the expected counts and values
    std::vector<std::string> sargs = {"sample", pc.curve, "--points", "2", "--format", "json"};
    sargs.insert(sargs.end(), pc.method.begin(), pc.method.end());
    auto js = run_uniparam(sargs);
    ASSERT_EQ(js.exit_code, 0) << js.err;
    const std::size_t N = pieces_from_json(js.out);
    ASSERT_GE(N, 1u);

    EXPECT_EQ(count(svg, "<g class=\"panel "), 3u);
    const std::string before = group(svg, "panel before"), after = group(svg, "panel after"),
                      speed = group(svg, "panel speed");
    ASSERT_FALSE(before.empty());
    ASSERT_FALSE(after.empty());
    ASSERT_FALSE(speed.empty());
    EXPECT_EQ(count(group(before, "samples before"), "<circle"), static_cast<std::size_t>(K));
    EXPECT_EQ(count(group(after, "samples after"), "<circle"), static_cast<std::size_t>(K));
    // interior breakpoints p(t_i) in both curve panels and on the speed of p;
    // the joints s_i as lines in the speed panel
    EXPECT_EQ(count(group(before, "breakpoints"), "<polygon"), N - 1);
    EXPECT_EQ(count(group(after, "breakpoints"), "<polygon"), N - 1);
    EXPECT_EQ(count(group(speed, "breakpoints"), "<polygon"), N - 1);
    EXPECT_EQ(count(group(speed, "joints"), "<line"), N - 1);
    // one polyline of p o r's speed per piece (jumps at C0 joints stay visible)
    EXPECT_EQ(count(group(speed, "speed after"), "<polyline"), N);
    EXPECT_EQ(count(group(speed, "speed before"), "<polyline"), 1u);
    // axes with tick labels in each panel
    for (const auto* p : {&before, &after, &speed}) EXPECT_GE(count(group(*p, "axes"), "<text"), 6u);

    // captions: u(p) and u(p o r) agree with the certified values (rounded to
    // at least 4 significant digits)
    const std::string cap_before = text_of(group(before, "caption")), cap_after = text_of(group(after, "caption"));
    std::smatch m;
    ASSERT_TRUE(std::regex_search(cap_before, m, std::regex("u\\(p\\) = ([0-9.]+)"))) << cap_before;
    const double ub = std::stod(m[1]);
    ASSERT_TRUE(std::regex_search(cap_after, m, std::regex("u\\(p\u2218r\\) = ([0-9.]+)"))) << cap_after;
    const double ua = std::stod(m[1]);
    EXPECT_NEAR(ub, to_d(top_level(js.out, "u_before").mid), 5e-5);
    EXPECT_NEAR(ua, to_d(top_level(js.out, "u_after").mid), 5e-5);
    EXPECT_GT(ua, ub);
    // a space curve says which projection it shows
    const std::string title = text_of(group(svg, "title"));
    if (pc.dims > 2) EXPECT_NE(title.find("projection"), std::string::npos) << title;
    else EXPECT_EQ(title.find("projection"), std::string::npos) << title;
  }
}

TEST(PlotCli, OutputIsDeterministicAndStdoutWorks) {
  auto a = run_uniparam({"plot", kCubic, "-o", "-"});
  auto b = run_uniparam({"plot", kCubic, "--output", "-"});
  ASSERT_EQ(a.exit_code, 0) << a.err;
  ASSERT_EQ(b.exit_code, 0) << b.err;
  EXPECT_EQ(a.out, b.out);
  EXPECT_TRUE(well_formed(a.out));
  // the checker itself notices a truncated document and a misnested tag
  EXPECT_FALSE(well_formed(a.out.substr(0, a.out.size() - 7)));
  std::string swapped = a.out;
  const std::size_t g = swapped.find("</g>");
  ASSERT_NE(g, std::string::npos);
  swapped.replace(g, 4, "</text>");
  EXPECT_FALSE(well_formed(swapped));
}

TEST(PlotCli, PngThroughRsvgConvertOrAClearError) {
  const std::string path = temp_path(".png");
  auto r = run_uniparam({"plot", kCubic, "-o", path});
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") == 0) {
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string png = read_all(path);
    ASSERT_GT(png.size(), 8u);
    EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
    std::remove(path.c_str());
  }
  // Without rsvg-convert on PATH: exit 1 and the Debian package named.
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  setenv("PATH", "/nonexistent-uniparam-test", 1);
  auto miss = run_uniparam({"plot", kCubic, "-o", path});
  setenv("PATH", saved.c_str(), 1);
  EXPECT_EQ(miss.exit_code, 1);
  EXPECT_NE(miss.err.find("librsvg2-bin"), std::string::npos) << miss.err;
  std::remove(path.c_str());
}

TEST(PlotCli, BadRequestsAreRefusedClearly) {
  struct Bad {
    std::vector<std::string> args;
    int code;
    const char* message;
  };
  const Bad cases[] = {
      {{"plot", kCubic}, 2, "-o FILE.svg"},
      {{"plot", kCubic, "-o", "x.pdf"}, 2, ".svg or .png"},
      {{"plot", kCubic, "--method", "spline", "-o", "-"}, 2, "unknown method"},
      {{"plot", kCubic, "--method", "none", "-o", "-"}, 2, "unknown method"},
      {{"plot", kCubic, "--pieces", "3", "-o", "-"}, 2, "--pieces applies to --method c0"},
      {{"plot", kCubic, "--projection", "iso", "-o", "-"}, 2, "at least 3 components"},
      {{"plot", kSpace, "--projection", "1,4", "-o", "-"}, 2, "--projection"},
      {{"plot", kCubic, "--points", "1", "-o", "-"}, 2, "--points"},
      {{"sample", kCubic, "--format", "xml"}, 2, "unknown format"},
      {{"sample", kCubic, "--method", "c1", "--target", "1.5"}, 2, "--target"},
      {{"sample", kCubic, "--max-pieces", "3"}, 2, "--max-pieces applies to --method c1"},
  };
  for (const auto& c : cases) {
    auto r = run_uniparam(c.args);
    EXPECT_EQ(r.exit_code, c.code) << c.args[0] << " " << c.message;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
  }
}

TEST(SampleCli, CsvAndJsonAgreeAndFollowTheCurve) {
  const long K = 9, D = 12;
  for (const char* method : {"radical", "c0", "none"}) {
    SCOPED_TRACE(method);
    auto csv = run_uniparam({"sample", kCubic, "--method", method, "--points", std::to_string(K), "--digits",
                             std::to_string(D)});
    auto json = run_uniparam({"sample", kCubic, "--method", method, "--points", std::to_string(K), "--digits",
                              std::to_string(D), "--format", "json"});
    ASSERT_EQ(csv.exit_code, 0) << csv.err;
    ASSERT_EQ(json.exit_code, 0) << json.err;
    std::istringstream lines(csv.out);
    std::string line;
    std::getline(lines, line);
    EXPECT_EQ(line, "s,t,x,y,speed");
    std::vector<std::vector<std::string>> rows;
    while (std::getline(lines, line)) {
      std::vector<std::string> f;
      std::stringstream ls(line);
      std::string cell;
      while (std::getline(ls, cell, ',')) f.push_back(cell);
      if (!line.empty() && line.back() == ',') f.push_back("");
      rows.push_back(f);
    }
    ASSERT_EQ(rows.size(), static_cast<std::size_t>(K));
    EXPECT_EQ(rows.front()[0], "0");
    EXPECT_EQ(rows.back()[0], "1");

    const std::string samples = json.out.substr(json.out.find("\"samples\""));
    const std::vector<JsonBall> b = balls(samples);
    ASSERT_EQ(b.size(), static_cast<std::size_t>(5 * K));  // s, t, x, y, speed per sample
    const Rational tol_digits = Rational::parse("1e-" + std::to_string(D - 1));
    for (long k = 0; k < K; ++k) {
      SCOPED_TRACE(k);
      ASSERT_EQ(rows[k].size(), 5u);
      // s is exactly k/(K-1)
      EXPECT_NE(samples.find("\"exact\": \"" + Rational(k, K - 1).str() + "\""), std::string::npos);
      for (int col = 0; col < 5; ++col) {
        const JsonBall& x = b[static_cast<std::size_t>(5 * k + col)];
        // the JSON ball meets the digits
        const Rational abs_mid = x.mid < Rational(0) ? -x.mid : x.mid;
        const Rational scale = abs_mid > Rational(1) ? abs_mid : Rational(1);
        if (col > 0) EXPECT_LE(x.rad, Rational::parse("1e-" + std::to_string(D)) * scale);
        if (rows[k][col].empty()) continue;  // speed at a joint
        // the CSV decimal is the same number rounded to D significant digits
        const Rational v = Rational::parse(rows[k][col]);
        const Rational diff = v > x.mid ? v - x.mid : x.mid - v;
        EXPECT_LE(diff, x.rad + tol_digits * scale) << rows[k][col] << " vs " << to_d(x.mid);
      }
      // the point is (t, t^3) at the certified t: exact interval arithmetic
      const JsonBall &t = b[5 * k + 1], &px = b[5 * k + 2], &py = b[5 * k + 3];
      const Rational tlo = t.mid - t.rad, thi = t.mid + t.rad;
      EXPECT_FALSE(px.mid + px.rad < tlo || px.mid - px.rad > thi);
      EXPECT_FALSE(py.mid + py.rad < tlo * tlo * tlo || py.mid - py.rad > thi * thi * thi);
    }
    // u before/after in the JSON: none keeps u
    const JsonBall ub = top_level(json.out, "u_before"), ua = top_level(json.out, "u_after");
    if (std::string(method) == "none") EXPECT_EQ(ub.mid, ua.mid);
    else EXPECT_GT(ua.mid, ub.mid);
  }
}

TEST(SampleCli, CsvOfASpaceCurveHasItsCoordinates) {
  auto r = run_uniparam({"sample", kSpace, "--method", "none", "--points", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out.substr(0, r.out.find('\n')), "s,t,x,y,z,speed");
  // t = 1/2 on the circle-helix: (3/5, 4/5, 1/2)
  EXPECT_NE(r.out.find("0.5,0.5,0.6,0.8,0.5,"), std::string::npos) << r.out;
}

TEST(PlotCli, C1TargetReachedOrExitFour) {
  // ImUp's slides: the slide curve reaches 0.99 with a C1 map.
  auto ok = run_uniparam({"plot", kSlide, "--method", "c1", "--target", "0.99", "-o", "-"});
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(text_of(group(ok.out, "title")).find("0.99 reached"), std::string::npos);
  // Too few pieces for 0.999: the best map is still drawn, the title says
  // so, and the exit status is 4 (as 'uniparam reparam --target').
  auto low = run_uniparam({"plot", kSlide, "--method", "c1", "--target", "0.999", "--max-pieces", "2", "-o", "-"});
  EXPECT_EQ(low.exit_code, 4);
  EXPECT_NE(low.err.find("not reached"), std::string::npos) << low.err;
  EXPECT_TRUE(well_formed(low.out));
  EXPECT_NE(text_of(group(low.out, "title")).find("NOT reached"), std::string::npos);
  auto smp = run_uniparam({"sample", kSlide, "--method", "c1", "--target", "0.999", "--max-pieces", "2"});
  EXPECT_EQ(smp.exit_code, 4);
  EXPECT_EQ(count(smp.out, "\n"), 41u);  // header and 40 rows all the same
}
