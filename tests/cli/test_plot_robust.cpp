// `uniparam plot` under hostile conditions: the rsvg-convert child and any
// temporary file do not outlive the command (timeout, SIGTERM, SIGINT,
// SIGKILL), an unwritable output is refused before computing, tick labels
// stay short at extreme scales, title lines fit the page, and the grey trace
// follows the curve's geometry however the parameter is distributed.
#include <gtest/gtest.h>

#include <dirent.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/run.hpp"
#include "support/svg.hpp"
#include "uniparam/reparam/all.hpp"

extern char** environ;

using uniparam::test_support::group;
using uniparam::test_support::run_uniparam;

namespace {

std::string read_all(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

bool exists(const std::string& path) {
  struct stat st;
  return lstat(path.c_str(), &st) == 0;
}

std::vector<std::string> entries(const std::string& dir) {
  std::vector<std::string> v;
  if (DIR* d = opendir(dir.c_str())) {
    while (const dirent* e = readdir(d))
      if (std::strcmp(e->d_name, ".") && std::strcmp(e->d_name, "..")) v.push_back(e->d_name);
    closedir(d);
  }
  return v;
}

// A private directory, removed with its contents at the end of the scope.
struct ScratchDir {
  std::string path;
  ScratchDir() {
    char name[] = "/tmp/uniparam_plot_robust_XXXXXX";
    path = mkdtemp(name) ? name : "";
  }
  ~ScratchDir() {
    if (!path.empty()) std::system(("rm -rf " + uniparam::test_support::shell_quote(path)).c_str());
  }
};

// True while process `pid` exists and is not a zombie.
bool running(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/stat");
  std::string line;
  if (!std::getline(f, line)) return false;
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

// A stand-in for rsvg-convert in `dir`/bin: records its arguments and pid,
// then blocks on the FIFO `dir`/go until released, then writes its output
// like rsvg-convert does (to --output FILE, else to stdout).
void install_fake_rsvg(const std::string& dir) {
  mkdir((dir + "/bin").c_str(), 0755);
  mkfifo((dir + "/go").c_str(), 0600);
  const std::string script = dir + "/bin/rsvg-convert";
  std::ofstream f(script);
  f << "#!/bin/sh\n"
    << "for a in \"$@\"; do printf '%s\\n' \"$a\"; done > '" << dir << "/args'\n"
    << "echo $$ > '" << dir << "/pid.tmp' && mv '" << dir << "/pid.tmp' '" << dir << "/pid'\n"
    << "read line < '" << dir << "/go'\n"
    << "out=; prev=\n"
    << "for a in \"$@\"; do [ \"$prev\" = --output ] && out=\"$a\"; prev=\"$a\"; done\n"
    << "if [ -n \"$out\" ]; then printf 'PNG' > \"$out\"; else cat > /dev/null; printf 'PNG'; fi\n";
  f.close();
  chmod(script.c_str(), 0755);
}

// Starts `uniparam plot ...` with PATH led by the fake rsvg-convert and
// TMPDIR private; stdin from /dev/null, stdout and stderr into files.
pid_t start_plot(const std::string& dir, const std::vector<std::string>& args) {
  const char* bin = std::getenv("UNIPARAM_BIN");
  std::vector<std::string> argv_s = {bin ? bin : "uniparam", "plot"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::vector<std::string> env_s;
  for (char** e = environ; *e; ++e) {
    const std::string kv = *e;
    if (kv.rfind("PATH=", 0) == 0 || kv.rfind("TMPDIR=", 0) == 0) continue;
    env_s.push_back(kv);
  }
  const char* path = std::getenv("PATH");
  env_s.push_back("PATH=" + dir + "/bin:" + (path ? path : "/usr/bin:/bin"));
  env_s.push_back("TMPDIR=" + dir + "/tmp");
  mkdir((dir + "/tmp").c_str(), 0700);
  std::vector<char*> envp;
  for (auto& e : env_s) envp.push_back(e.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, (dir + "/stdout").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&fa, 2, (dir + "/stderr").c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  pid_t pid = -1;
  if (posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), envp.data()) != 0) pid = -1;
  posix_spawn_file_actions_destroy(&fa);
  return pid;
}

// The pid the fake rsvg-convert recorded, waiting for it while `plot` runs
// (0 if `plot` ended first: it never started the child).
pid_t wait_for_fake(const std::string& dir, pid_t plot, int& plot_status, bool& plot_ended) {
  plot_ended = false;
  for (int i = 0; i < 240 * 50; ++i) {  // a generous bound, not a speed test
    if (exists(dir + "/pid")) return static_cast<pid_t>(std::atol(read_all(dir + "/pid").c_str()));
    if (waitpid(plot, &plot_status, WNOHANG) == plot) {
      plot_ended = true;
      return exists(dir + "/pid") ? static_cast<pid_t>(std::atol(read_all(dir + "/pid").c_str())) : 0;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return 0;
}

// After `plot` has ended: lets a surviving fake child go on (as a surviving
// rsvg-convert would) and waits for it to finish, so that nothing is left
// running and a late output file shows.
void release_survivor(const std::string& dir, pid_t fake) {
  if (fake <= 0 || !running(fake)) return;
  const int fd = open((dir + "/go").c_str(), O_WRONLY | O_NONBLOCK);
  if (fd >= 0) {
    const ssize_t n = write(fd, "go\n", 3);
    (void)n;
    close(fd);
  }
  for (int i = 0; i < 60 * 50 && running(fake); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

// The SVG files a fake rsvg-convert was handed as arguments (temporary files).
std::vector<std::string> svg_arguments(const std::string& dir) {
  std::vector<std::string> v;
  std::istringstream in(read_all(dir + "/args"));
  for (std::string a; std::getline(in, a);)
    if (a.size() > 4 && a.compare(a.size() - 4, 4, ".svg") == 0) v.push_back(a);
  return v;
}

enum class Ending { Timeout, Sigterm, Sigint, Sigkill };

void check_plot_ends_cleanly(Ending how) {
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  install_fake_rsvg(d.path);
  const std::string png = d.path + "/x.png";
  std::vector<std::string> args = {"(t, t^2)", "--points", "10", "-o", png};
  if (how == Ending::Timeout) args.insert(args.end(), {"--timeout", "4"});
  const pid_t plot = start_plot(d.path, args);
  ASSERT_GT(plot, 0);
  int status = 0;
  bool ended = false;
  const pid_t fake = wait_for_fake(d.path, plot, status, ended);
  if (how != Ending::Timeout && !ended) {
    const int sig = how == Ending::Sigterm ? SIGTERM : how == Ending::Sigint ? SIGINT : SIGKILL;
    kill(plot, sig);
  }
  if (!ended) waitpid(plot, &status, 0);
  const std::vector<std::string> temps = svg_arguments(d.path);
  // After SIGKILL the child gets its parent-death signal asynchronously: give
  // it a bounded moment to go (a survivor blocks on its FIFO and never does).
  if (how == Ending::Sigkill)
    for (int i = 0; i < 5 * 50 && fake > 0 && running(fake); ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const bool survived = fake > 0 && running(fake);
  release_survivor(d.path, fake);
  std::vector<std::string> left;
  for (const auto& t : temps)
    if (exists(t)) left.push_back(t);
  for (const auto& t : left) std::remove(t.c_str());  // tidy up after a failing binary
  ASSERT_GT(fake, 0) << "rsvg-convert was never started: " << read_all(d.path + "/stderr");
  if (how == Ending::Timeout) {
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 4) << status;
    EXPECT_NE(read_all(d.path + "/stderr").find("--timeout"), std::string::npos) << read_all(d.path + "/stderr");
  } else {
    const int sig = how == Ending::Sigterm ? SIGTERM : how == Ending::Sigint ? SIGINT : SIGKILL;
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
  }
  EXPECT_FALSE(survived) << "rsvg-convert (pid " << fake << ") outlived the command";
  EXPECT_TRUE(entries(d.path + "/tmp").empty()) << "files left in TMPDIR";
  for (const auto& t : left) ADD_FAILURE() << "temporary file left: " << t;
  EXPECT_FALSE(exists(png)) << "the output was written after the command ended";
}

}  // namespace

// ---- The rsvg-convert child and temporary files ---------------------------

TEST(PlotRobust, TimeoutKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Timeout); }
TEST(PlotRobust, SigtermKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Sigterm); }
TEST(PlotRobust, SigintKillsRsvgConvertAndLeavesNothing) { check_plot_ends_cleanly(Ending::Sigint); }
TEST(PlotRobust, SigkillTakesRsvgConvertAlong) { check_plot_ends_cleanly(Ending::Sigkill); }

TEST(PlotRobust, PngWithoutTemporaryFilesWhenRsvgConvertWorks) {
  if (std::system("command -v rsvg-convert >/dev/null 2>&1") != 0) GTEST_SKIP() << "no rsvg-convert";
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  mkdir((d.path + "/tmp").c_str(), 0700);
  const std::string png = d.path + "/x.png";
  const char* old = std::getenv("TMPDIR");
  const std::string saved = old ? old : "";
  setenv("TMPDIR", (d.path + "/tmp").c_str(), 1);
  const auto r = run_uniparam({"plot", "(t, t^3)", "-o", png});
  if (old) setenv("TMPDIR", saved.c_str(), 1);
  else unsetenv("TMPDIR");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string bytes = read_all(png);
  ASSERT_GT(bytes.size(), 8u);
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_TRUE(entries(d.path + "/tmp").empty());
}

// ---- The output file: checked before computing ----------------------------

TEST(PlotRobust, UnwritableOutputIsRefusedBeforeComputingWithTheReason) {
  ScratchDir d;
  ASSERT_FALSE(d.path.empty());
  std::ofstream(d.path + "/file") << "x";
  mkdir((d.path + "/dir.svg").c_str(), 0755);
  struct Case {
    std::string path;
    int err;
  };
  const Case cases[] = {
      {d.path + "/missing/x.svg", ENOENT},
      {d.path + "/missing/x.png", ENOENT},
      {d.path + "/file/x.svg", ENOTDIR},
      {d.path + "/dir.svg", EISDIR},
  };
  // The curve has a pole in [0, 1] (exit 3 once the curve is read): the
  // output must be refused before that.
  for (const auto& c : cases) {
    const auto r = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", c.path});
    EXPECT_EQ(r.exit_code, 2) << c.path << ": " << r.err;
    const std::string want = "cannot write " + c.path + ": " + std::strerror(c.err);
    EXPECT_NE(r.err.find(want), std::string::npos) << "want '" << want << "', got: " << r.err;
  }
  // A writable new path: not created by the check (the command then fails
  // on the curve).
  const std::string fresh = d.path + "/fresh.svg";
  const auto r = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", fresh});
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_FALSE(exists(fresh));
  // An existing file is left as it is when the command fails.
  std::ofstream(d.path + "/old.svg") << "keep";
  const auto r2 = run_uniparam({"plot", "(1/(t-1/2), t)", "-o", d.path + "/old.svg"});
  EXPECT_EQ(r2.exit_code, 3) << r2.err;
  EXPECT_EQ(read_all(d.path + "/old.svg"), "keep");
}

// ---- SVG reading helpers ---------------------------------------------------

namespace {


std::string attr(const std::string& tag, const std::string& name) {
  const std::size_t a = tag.find(" " + name + "=\"");
  if (a == std::string::npos) return "";
  const std::size_t b = a + name.size() + 3;
  return tag.substr(b, tag.find('"', b) - b);
}

struct Text {
  double x, y, size;
  std::string anchor, text;
  bool bold;
};

// Every <text> of a fragment, with its visible text (tags dropped).
std::vector<Text> texts(const std::string& frag) {
  std::vector<Text> v;
  for (std::size_t i = frag.find("<text "); i != std::string::npos; i = frag.find("<text ", i + 1)) {
    const std::size_t open_end = frag.find('>', i);
    const std::size_t close = frag.find("</text>", open_end);
    const std::string tag = frag.substr(i, open_end - i);
    std::string body, raw = frag.substr(open_end + 1, close - open_end - 1);
    bool in_tag = false;
    for (char c : raw) {
      if (c == '<') in_tag = true;
      else if (c == '>') in_tag = false;
      else if (!in_tag) body += c;
    }
    for (const auto& [e, ch] : std::vector<std::pair<std::string, std::string>>{
             {"&lt;", "<"}, {"&gt;", ">"}, {"&quot;", "\""}, {"&apos;", "'"}, {"&amp;", "&"}})
      for (std::size_t k; (k = body.find(e)) != std::string::npos;) body.replace(k, e.size(), ch);
    v.push_back({std::stod(attr(tag, "x")), std::stod(attr(tag, "y")), std::stod(attr(tag, "font-size")),
                 attr(tag, "text-anchor"), body, attr(tag, "font-weight") == "bold"});
  }
  return v;
}

std::vector<unsigned> code_points(const std::string& s) {
  std::vector<unsigned> v;
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i++]);
    int more = c < 0x80 ? 0 : c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : 1;
    unsigned cp = more ? c & (0x3F >> more) : c;
    while (more-- > 0 && i < s.size()) cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
    v.push_back(cp);
  }
  return v;
}

// Advance width in em of a character in DejaVu Sans (the plots' first font,
// wider than the usual fallbacks), from the font's metrics; 1 em for
// characters not listed (an over-estimate).
double dejavu_em(unsigned cp) {
  if (cp >= '0' && cp <= '9') return 0.636;
  const std::string lower = "abcdefghijklmnopqrstuvwxyz";
  static const double lw[26] = {0.613, 0.635, 0.550, 0.635, 0.615, 0.352, 0.635, 0.634, 0.278, 0.278, 0.579, 0.278, 0.974,
                                0.634, 0.612, 0.635, 0.635, 0.411, 0.521, 0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525};
  if (cp >= 'a' && cp <= 'z') return lw[cp - 'a'];
  if (cp >= 'A' && cp <= 'Z') return 0.863;  // the widest capitals but W
  switch (cp) {
    case ' ': case ',': case '.': case ':': return 0.318;
    case '(': case ')': return 0.390;
    case '/': return 0.337;
    case '-': return 0.361;
    case '+': case '=': case 0x2212: case 0x00d7: case 0x2218: case 0x2192: return 0.838;
    case 0x00b9: case 0x00b2: case 0x00b3: case 0x207b: return 0.401;
    case 0x2026: return 1.0;
    default: break;
  }
  if (cp >= 0x2070 && cp <= 0x2079) return 0.401;
  return 1.0;
}

double width_px(const Text& t) {
  double em = 0;
  for (unsigned cp : code_points(t.text)) em += dejavu_em(cp);
  return em * t.size * (t.bold ? 1.1 : 1.0);
}

struct Rect {
  double x, y, w, h;
};

// The frame of each <g class="axes"> (its last <rect>), in document order.
std::vector<std::pair<Rect, std::string>> axes_groups(const std::string& svg) {
  std::vector<std::pair<Rect, std::string>> v;
  for (std::size_t i = svg.find("<g class=\"axes\">"); i != std::string::npos;
       i = svg.find("<g class=\"axes\">", i + 1)) {
    const std::string g = group(svg, "axes", i);
    const std::size_t r = g.rfind("<rect ");
    const std::string tag = g.substr(r, g.find('>', r) - r);
    v.push_back({{std::stod(attr(tag, "x")), std::stod(attr(tag, "y")), std::stod(attr(tag, "width")),
                  std::stod(attr(tag, "height"))},
                 g});
  }
  return v;
}

long long parse_label(const std::string& s) {
  std::string t = s;
  const std::string minus = "\u2212";
  bool neg = false;
  if (t.compare(0, minus.size(), minus) == 0) {
    neg = true;
    t = t.substr(minus.size());
  }
  return neg ? -std::stoll(t) : std::stoll(t);
}

int parse_superscript(const std::string& s, std::size_t& i) {
  static const std::vector<std::string> digits = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                                  "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  int sign = 1, v = 0;
  if (s.compare(i, 3, "\u207b") == 0) { sign = -1; i += 3; }
  for (bool more = true; more;) {
    more = false;
    for (int d = 0; d < 10; ++d)
      if (s.compare(i, digits[d].size(), digits[d]) == 0) {
        v = 10 * v + d;
        i += digits[d].size();
        more = true;
        break;
      }
  }
  return sign * v;
}

// The value of a tick label under an axis note "×10ᴱ [± m×10ˣ]" (the note
// may be empty: plain decimals).
double tick_value(const std::string& label, const std::string& note) {
  if (note.empty()) {
    std::string t = label;
    const std::string minus = "\u2212";
    if (t.compare(0, minus.size(), minus) == 0) t = "-" + t.substr(minus.size());
    return std::stod(t);
  }
  const std::string times = "\u00d710";
  std::size_t i = 0;
  int E = 0;
  if (note.compare(0, times.size(), times) == 0) {
    i = times.size();
    E = parse_superscript(note, i);
  }
  double offset = 0;
  const std::size_t plus = note.find("+ ", i), minus = note.find("\u2212 ", i);
  if (plus != std::string::npos || minus != std::string::npos) {
    const bool neg = minus != std::string::npos && (plus == std::string::npos || minus < plus);
    std::size_t j = neg ? minus + std::string("\u2212 ").size() : plus + 2;
    std::size_t k = j;
    while (k < note.size() && (std::isdigit(static_cast<unsigned char>(note[k])) || note[k] == '.')) ++k;
    double m = std::stod(note.substr(j, k - j));
    if (note.compare(k, times.size(), times) == 0) {
      k += times.size();
      m *= std::pow(10.0, parse_superscript(note, k));
    }
    offset = neg ? -m : m;
  }
  return static_cast<double>(parse_label(label)) * std::pow(10.0, E) + offset;
}

struct Axis {
  std::vector<double> pixel, value;  // tick positions and their values
  // value at a pixel position, from the first and last ticks
  double at(double px) const {
    return value.front() + (px - pixel.front()) * (value.back() - value.front()) / (pixel.back() - pixel.front());
  }
  double per_pixel() const { return (value.back() - value.front()) / (pixel.back() - pixel.front()); }
};

// The two axes of an axes group: x ticks (anchored middle, below the frame),
// y ticks (anchored end, left of it) and the notes (font size 11).
std::pair<Axis, Axis> read_axes(const Rect& frame, const std::string& g, std::vector<Text>* labels = nullptr) {
  const auto ts = texts(g);
  std::string xnote, ynote;
  for (const auto& t : ts)
    if (t.size == 11) (t.y < frame.y ? ynote : xnote) = t.text;
  Axis x, y;
  for (const auto& t : ts) {
    if (t.size != 12) continue;
    if (labels) labels->push_back(t);
    if (t.anchor == "middle") {
      x.pixel.push_back(t.x);
      x.value.push_back(tick_value(t.text, xnote));
    } else if (t.anchor == "end") {
      y.pixel.push_back(t.y - 4);
      y.value.push_back(tick_value(t.text, ynote));
    }
  }
  return {x, y};
}

// Each tick's value agrees with the affine map through the first and last.
::testing::AssertionResult affine(const Axis& a) {
  if (a.pixel.size() < 2) return ::testing::AssertionFailure() << "fewer than 2 ticks";
  const double span = std::fabs(a.value.back() - a.value.front());
  if (!(span > 0)) return ::testing::AssertionFailure() << "ticks without a span";
  for (std::size_t i = 0; i < a.pixel.size(); ++i)
    if (std::fabs(a.at(a.pixel[i]) - a.value[i]) > 1e-3 * span)
      return ::testing::AssertionFailure() << "tick " << i << " = " << a.value[i] << " is off the axis' map ("
                                           << a.at(a.pixel[i]) << ")";
  return ::testing::AssertionSuccess();
}

std::string plot_svg(const std::vector<std::string>& args) {
  std::vector<std::string> a = {"plot"};
  a.insert(a.end(), args.begin(), args.end());
  a.insert(a.end(), {"-o", "-"});
  const auto r = run_uniparam(a);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

}  // namespace

// ---- Ticks at extreme scales ----------------------------------------------

TEST(PlotRobust, TickLabelsStayShortCorrectAndInsideTheirPanelAtExtremeScales) {
  struct Case {
    std::vector<std::string> args;
    double x0, x1, y0, y1;  // the curve's extent in the curve panels
  };
  const Case cases[] = {
      {{"(t*10^40, t^2*10^40)"}, 0, 1e40, 0, 1e40},
      {{"(t/10^30, t^3/10^30)"}, 0, 1e-30, 0, 1e-30},
      {{"(10^10 + t, t^2)"}, 1e10, 1e10 + 1, 0, 1},
      {{"(-10^20 - t*10^14, t*10^14)"}, -1e20 - 1e14, -1e20, 0, 1e14},
      {{"(t/10^9, 1 + t^2/10^9)"}, 0, 1e-9, 1, 1 + 1e-9},
      {{"(t, t^3)"}, 0, 1, 0, 1},
      // the speed panel's y axis reaches 1.2e41
      {{"--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,8e40,1e82]"}, 0, 1, 0, 1},
  };
  for (const auto& c : cases) {
    const std::string svg = plot_svg(c.args);
    const auto groups = axes_groups(svg);
    ASSERT_EQ(groups.size(), 3u) << c.args[0];
    for (std::size_t k = 0; k < groups.size(); ++k) {
      const auto& [frame, g] = groups[k];
      std::vector<Text> labels;
      const auto [x, y] = read_axes(frame, g, &labels);
      for (const auto& t : labels) {
        EXPECT_LE(code_points(t.text).size(), 6u) << c.args[0] << ": tick label '" << t.text << "'";
        if (k > 0 && t.anchor == "end")  // clear of the panel on the left
          EXPECT_GT(t.x - width_px(t), groups[k - 1].first.x + groups[k - 1].first.w)
              << c.args[0] << ": '" << t.text << "'";
      }
      EXPECT_TRUE(affine(x)) << c.args[0] << " panel " << k << " x";
      EXPECT_TRUE(affine(y)) << c.args[0] << " panel " << k << " y";
      if (k < 2 && x.pixel.size() >= 2 && y.pixel.size() >= 2) {
        // the frame shows the curve's extent, not much more (equal aspect
        // and 6% padding: at most 1.4 x the larger side)
        const double fx0 = x.at(frame.x), fx1 = x.at(frame.x + frame.w);
        const double fy0 = y.at(frame.y + frame.h), fy1 = y.at(frame.y);
        const double side = std::max(c.x1 - c.x0, c.y1 - c.y0);
        EXPECT_LE(fx0, c.x0 + 1e-6 * side) << c.args[0];
        EXPECT_GE(fx1, c.x1 - 1e-6 * side) << c.args[0];
        EXPECT_LE(fy0, c.y0 + 1e-6 * side) << c.args[0];
        EXPECT_GE(fy1, c.y1 - 1e-6 * side) << c.args[0];
        EXPECT_LE(fx1 - fx0, 1.4 * side) << c.args[0];
        EXPECT_LE(fy1 - fy0, 1.4 * side) << c.args[0];
      }
      // the y axis label (rotated; reaches about 10 px left of its x) is clear
      // of the left panel too
      if (k > 0) {
        const auto ts = texts(g);
        for (const auto& t : ts)
          if (t.size == 13 && t.anchor == "middle" && t.x < frame.x)
            EXPECT_GT(t.x - 0.8 * t.size, groups[k - 1].first.x + groups[k - 1].first.w) << c.args[0];
      }
    }
  }
}

// ---- Titles ------------------------------------------------------------------

TEST(PlotRobust, TitleLinesFitThePage) {
  const std::string zeros(300, '0');
  const std::string slide = "((t^3-6t^2+9t-2)/(2t^4-16t^3+40t^2-32t+9), (t^2-4t+4)/(2t^4-16t^3+40t^2-32t+9))";
  struct Case {
    std::vector<std::string> args;
    std::string title_start, title_end;  // a long number: its start and end stay visible
  };
  const Case cases[] = {
      {{"--control", "[[1,0],[1,1],[0,1]]", "--weights", "[1,8e40,1e82]"}, "", ""},
      {{slide, "--method", "c1", "--target", "0.99" + zeros + "1"}, "0.9900000", "0001reached"},
      {{"(t, t^3)"}, "", ""},
  };
  for (const auto& c : cases) {
    const std::string svg = plot_svg(c.args);
    const double W = std::stod(attr(svg.substr(svg.find("<svg "), 400), "width"));
    const auto ts = texts(group(svg, "title"));
    ASSERT_FALSE(ts.empty());
    std::string all;
    for (const auto& t : ts) {
      const double w = width_px(t);
      EXPECT_LE(t.x - w / 2, W) << "'" << t.text << "'";  // anchored middle at W / 2
      EXPECT_LE(w, W - 20) << "'" << t.text << "' (" << w << " px of " << W << ")";
      if (t.bold) all += t.text;
    }
    if (!c.title_start.empty()) {
      std::string compact;
      for (char ch : all)
        if (ch != ' ') compact += ch;
      EXPECT_NE(compact.find(c.title_start), std::string::npos) << all;
      EXPECT_NE(compact.find(c.title_end), std::string::npos) << all;
    }
    // the subtitle starts with the curve's start and ends with its end
    bool start = false;
    for (const auto& t : ts) start = start || t.text.rfind("p(t) = (", 0) == 0;
    EXPECT_TRUE(start);
  }
}

// ---- The trace ---------------------------------------------------------------

namespace {

struct Pt {
  double x, y;
};

// The grey trace of a curve panel, in data coordinates (through the axes).
std::vector<Pt> trace_of(const std::string& svg, const std::string& panel) {
  const std::string g = group(svg, panel);
  const auto axes = axes_groups(g);
  EXPECT_EQ(axes.size(), 1u);
  if (axes.size() != 1) return {};
  const auto [x, y] = read_axes(axes[0].first, axes[0].second);
  const std::size_t p = g.find("<polyline points=\"");
  EXPECT_NE(p, std::string::npos);
  EXPECT_NE(g.substr(p, g.find('>', p) - p).find("#b8b8b8"), std::string::npos) << "the first polyline is the trace";
  const std::string pts = attr(g.substr(p, g.find('>', p) - p), "points");
  std::vector<Pt> v;
  std::istringstream in(pts);
  for (std::string pair; in >> pair;) {
    const std::size_t comma = pair.find(',');
    v.push_back({x.at(std::stod(pair.substr(0, comma))), y.at(std::stod(pair.substr(comma + 1)))});
  }
  return v;
}

double data_per_pixel(const std::string& svg, const std::string& panel) {
  const std::string g = group(svg, panel);
  const auto axes = axes_groups(g);
  return std::fabs(read_axes(axes[0].first, axes[0].second).first.per_pixel());
}

double segment_distance(Pt p, Pt a, Pt b) {
  const double dx = b.x - a.x, dy = b.y - a.y, l2 = dx * dx + dy * dy;
  const double u = l2 > 0 ? std::min(1.0, std::max(0.0, ((p.x - a.x) * dx + (p.y - a.y) * dy) / l2)) : 0;
  return std::hypot(p.x - a.x - u * dx, p.y - a.y - u * dy);
}

}  // namespace

// The quarter circle x = (1-u²)/(1+u²), y = 2u/(1+u²) with u = t/(t + k(1-t)):
// for k = 10^6 the arc lies at t within about 10^-4 of 1 (between two of
// the equal steps of a dense sampling), for k = 10^-40 at t below 10^-38.
// The trace's vertices and the midpoints of its segments lie within a pixel
// of the unit circle, and it runs from (1, 0) to (0, 1).
TEST(PlotRobust, TraceFollowsACircleWhoseArcIsCrowdedIntoATinyRangeOfT) {
  for (const std::string k : {"10^6", "1/10^40"}) {
    const std::string D = "(" + k + " + (1 - " + k + ")*t)";
    const std::string curve = "((" + D + "^2 - t^2)/(" + D + "^2 + t^2), 2*t*" + D + "/(" + D + "^2 + t^2))";
    const std::string svg = plot_svg({curve});
    for (const std::string panel : {"panel before", "panel after"}) {
      const auto tr = trace_of(svg, panel);
      const double px = data_per_pixel(svg, panel);
      ASSERT_GE(tr.size(), 2u);
      EXPECT_LT(std::hypot(tr.front().x - 1, tr.front().y), 2 * px) << k;
      EXPECT_LT(std::hypot(tr.back().x, tr.back().y - 1), 2 * px) << k;
      double worst_vertex = 0, worst_mid = 0;
      for (std::size_t i = 0; i < tr.size(); ++i) {
        worst_vertex = std::max(worst_vertex, std::fabs(std::hypot(tr[i].x, tr[i].y) - 1));
        if (i > 0) {
          const Pt m{(tr[i - 1].x + tr[i].x) / 2, (tr[i - 1].y + tr[i].y) / 2};
          worst_mid = std::max(worst_mid, std::fabs(std::hypot(m.x, m.y) - 1));
        }
      }
      EXPECT_LT(worst_vertex, px) << k << " " << panel;
      EXPECT_LT(worst_mid, px) << k << " " << panel << ": a segment cuts across the arc";
    }
  }
}

// The rational quadratic Bezier curve of the issue: weights [1, 8e40, 1e82]
// put its arc at t ~ 1e-41. Points of the curve there (evaluated exactly by
// the library) lie within a pixel and a half of the trace.
TEST(PlotRobust, TraceCoversTheArcOfAHugeWeightBezierCurve) {
  const std::string control = "[[1,0],[1,1],[0,1]]", weights = "[1,8e40,1e82]";
  const std::string svg = plot_svg({"--control", control, "--weights", weights});
  const uniparam::Curve c = uniparam::BezierCurve::parse(control, weights).to_curve();
  for (const std::string panel : {"panel before", "panel after"}) {
    const auto tr = trace_of(svg, panel);
    const double px = data_per_pixel(svg, panel);
    ASSERT_GE(tr.size(), 2u);
    for (int e = -46; e <= -36; ++e)
      for (int m : {1, 2, 5}) {
        const uniparam::Rational t = uniparam::Rational::parse(std::to_string(m) + "e" + std::to_string(e));
        const auto p = c.eval(uniparam::Ball(t, 512), 512);
        const Pt q{uniparam::mid_double(p[0]), uniparam::mid_double(p[1])};
        double best = HUGE_VAL;
        for (std::size_t i = 1; i < tr.size(); ++i) best = std::min(best, segment_distance(q, tr[i - 1], tr[i]));
        EXPECT_LT(best, 1.5 * px) << panel << ": p(" << m << "e" << e << ") = (" << q.x << ", " << q.y
                                  << ") is off the trace";
      }
  }
}

// An ordinary curve: the trace stays on y = x^3 (vertices and segment
// midpoints within a pixel).
TEST(PlotRobust, TraceOfAnOrdinaryCurveStaysOnIt) {
  const std::string svg = plot_svg({"(t, t^3)"});
  const auto tr = trace_of(svg, "panel before");
  const double px = data_per_pixel(svg, "panel before");
  ASSERT_GE(tr.size(), 2u);
  for (std::size_t i = 0; i < tr.size(); ++i) {
    EXPECT_LT(std::fabs(tr[i].y - tr[i].x * tr[i].x * tr[i].x), px);
    if (i > 0) {
      const double mx = (tr[i - 1].x + tr[i].x) / 2, my = (tr[i - 1].y + tr[i].y) / 2;
      EXPECT_LT(std::fabs(my - mx * mx * mx), px);
    }
  }
}
