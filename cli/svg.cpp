#include "svg.hpp"

#include <fcntl.h>
#include <limits.h>
#include <poll.h>
#include <pthread.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#ifdef __linux__
#include <sys/prctl.h>
#endif

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include "uniparam/core/budget.hpp"

extern char** environ;

namespace uniparam::cli::svg {

std::string escape(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      case '\'': o += "&apos;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string num(double x) {
  if (!std::isfinite(x)) x = 0;
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f", x);
  std::string s = buf;
  // strip trailing zeros and a trailing dot; "-0" -> "0"
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  if (s == "-0") s = "0";
  return s;
}

namespace {

std::string style_attrs(const Style& st) {
  std::string a = " stroke=\"" + st.stroke + "\" fill=\"" + st.fill + "\"";
  if (st.stroke != "none") a += " stroke-width=\"" + num(st.width) + "\"";
  if (!st.dash.empty()) a += " stroke-dasharray=\"" + st.dash + "\"";
  if (st.opacity < 1) a += " opacity=\"" + num(st.opacity) + "\"";
  return a;
}

}  // namespace

Document::Document(double width, double height) : w_(width), h_(height) {}

void Document::line(Point a, Point b, const Style& st) {
  body_ += "<line x1=\"" + num(a.first) + "\" y1=\"" + num(a.second) + "\" x2=\"" + num(b.first) + "\" y2=\"" +
           num(b.second) + "\"" + style_attrs(st) + "/>\n";
}

void Document::polyline(const std::vector<Point>& pts, const Style& st) {
  if (pts.size() < 2) return;
  std::string p;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    if (i) p += ' ';
    p += num(pts[i].first) + "," + num(pts[i].second);
  }
  body_ += "<polyline points=\"" + p + "\"" + style_attrs(st) + " stroke-linejoin=\"round\"/>\n";
}

void Document::rect(double x, double y, double w, double h, const Style& st) {
  body_ += "<rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) + "\"" +
           style_attrs(st) + "/>\n";
}

void Document::circle(Point c, double r, const Style& st) {
  body_ += "<circle cx=\"" + num(c.first) + "\" cy=\"" + num(c.second) + "\" r=\"" + num(r) + "\"" +
           style_attrs(st) + "/>\n";
}

void Document::diamond(Point c, double r, const Style& st) {
  const double x = c.first, y = c.second;
  body_ += "<polygon points=\"" + num(x) + "," + num(y - r) + " " + num(x + r) + "," + num(y) + " " + num(x) + "," +
           num(y + r) + " " + num(x - r) + "," + num(y) + "\"" + style_attrs(st) + "/>\n";
}

void Document::text(Point at, const std::string& s, double size, Anchor anchor, const std::string& color, bool bold,
                    double rotate) {
  const char* a = anchor == Anchor::Start ? "start" : anchor == Anchor::Middle ? "middle" : "end";
  body_ += "<text x=\"" + num(at.first) + "\" y=\"" + num(at.second) + "\" font-size=\"" + num(size) +
           "\" text-anchor=\"" + a + "\" fill=\"" + color + "\" xml:space=\"preserve\"";
  if (bold) body_ += " font-weight=\"bold\"";
  if (rotate != 0)
    body_ += " transform=\"rotate(" + num(rotate) + " " + num(at.first) + " " + num(at.second) + ")\"";
  body_ += ">";
  // "_{...}" is a subscript: a smaller tspan shifted down, the rest shifted back.
  const std::string dy = num(0.3 * size), small = num(0.75 * size);
  auto restore = [&](const std::string& t) {
    return "<tspan dy=\"-" + dy + "\">" + escape(t) + "</tspan>";
  };
  std::size_t i = 0;
  bool shifted = false;
  while (i < s.size()) {
    const std::size_t open = s.find("_{", i);
    const std::size_t close = open == std::string::npos ? open : s.find('}', open);
    if (open == std::string::npos || close == std::string::npos) {
      body_ += shifted ? restore(s.substr(i)) : escape(s.substr(i));
      break;
    }
    if (open > i)
      body_ += shifted ? restore(s.substr(i, open - i)) : escape(s.substr(i, open - i));
    if (shifted && open == i) body_ += "<tspan dy=\"-" + dy + "\"></tspan>";
    body_ += "<tspan dy=\"" + dy + "\" font-size=\"" + small + "\">" + escape(s.substr(open + 2, close - open - 2)) +
             "</tspan>";
    shifted = true;
    i = close + 1;
  }
  body_ += "</text>\n";
}

void Document::begin_group(const std::string& cls) {
  body_ += "<g class=\"" + escape(cls) + "\">\n";
  ++depth_;
}

void Document::end_group() {
  if (depth_ == 0) throw std::logic_error("svg: end_group without begin_group");
  body_ += "</g>\n";
  --depth_;
}

void Document::begin_clip(double x, double y, double w, double h) {
  const std::string id = "clip" + std::to_string(++clips_);
  body_ += "<clipPath id=\"" + id + "\"><rect x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) +
           "\" height=\"" + num(h) + "\"/></clipPath>\n<g clip-path=\"url(#" + id + ")\">\n";
  ++depth_;
}

void Document::end_clip() { end_group(); }

void Document::comment(const std::string& s) {
  std::string c = s;
  for (std::size_t i; (i = c.find("--")) != std::string::npos;) c.replace(i, 2, "- -");
  body_ += "<!-- " + c + " -->\n";
}

std::string Document::str() const {
  if (depth_ != 0) throw std::logic_error("svg: unclosed group");
  std::string s = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  s += "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + num(w_) + "\" height=\"" + num(h_) +
       "\" viewBox=\"0 0 " + num(w_) + " " + num(h_) +
       "\" font-family=\"DejaVu Sans, Helvetica, Arial, sans-serif\">\n";
  s += "<rect x=\"0\" y=\"0\" width=\"" + num(w_) + "\" height=\"" + num(h_) + "\" fill=\"#ffffff\"/>\n";
  s += body_;
  s += "</svg>\n";
  return s;
}

Ticks nice_ticks(double lo, double hi, int target) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) {
    lo = std::isfinite(lo) ? lo : 0;
    hi = lo;
  }
  if (!(hi > lo)) {
    // a point: a range of width 1 around it, or a relative width where 1 is
    // below its resolution
    const double half = std::max(0.5, std::fabs(lo) * 1e-12);
    hi = lo + half;
    lo = lo - half;
  }
  if (target < 2) target = 2;
  // (hi - lo) / target without overflow; at least 10^-15 of the magnitude so
  // that the ticks are distinct doubles with mantissas below 10^16
  double raw = (hi - lo) / target;
  if (!std::isfinite(raw)) raw = hi / target - lo / target;
  raw = std::max({raw, std::max(std::fabs(lo), std::fabs(hi)) * 1e-15, 1e-300});
  const double lg = std::floor(std::log10(raw));
  const double mag = std::pow(10.0, lg);
  const double norm = raw / mag;
  const int f = norm < 1.5 ? 1 : norm < 3.5 ? 2 : norm < 7.5 ? 5 : 10;
  Ticks t;
  t.step = f * mag;
  t.exponent = static_cast<int>(lg);
  const double eps = t.step * 1e-9;
  const double first = std::ceil((lo - eps) / t.step);
  const double last = std::floor((hi + eps) / t.step);
  for (double k = first; k <= last && t.values.size() < static_cast<std::size_t>(2 * target + 2); ++k) {
    t.values.push_back(k * t.step);
    t.mantissas.push_back(static_cast<long long>(k) * f);
  }
  const int e = static_cast<int>(std::floor(std::log10(t.step) + 1e-9));
  t.decimals = e < 0 ? -e : 0;
  return t;
}

std::string tick_label(double v, int decimals) {
  char buf[512];
  std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 330), v);
  std::string s = buf;
  bool zero = true;
  for (char c : s)
    if (c >= '1' && c <= '9') zero = false;
  if (zero) {
    std::snprintf(buf, sizeof buf, "%.*f", std::min(decimals, 330), 0.0);
    s = buf;
  }
  if (!s.empty() && s[0] == '-') s.replace(0, 1, "\u2212");  // a proper minus sign
  return s;
}

std::size_t glyphs(const std::string& s) {
  std::size_t n = 0;
  for (char c : s)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
}

namespace {

std::string superscript(long long k) {
  static const char* sup[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                              "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string o = k < 0 ? "\u207b" : "";
  for (char c : std::to_string(k < 0 ? -k : k)) o += sup[c - '0'];
  return o;
}

// m x 10^e (m > 0) as "d.ddd×10ˣ" with the trailing zeros of m removed.
std::string scientific(long long m, int e) {
  while (m % 10 == 0) { m /= 10; ++e; }
  const std::string ds = std::to_string(m);
  const long long x = e + static_cast<long long>(ds.size()) - 1;
  std::string o = ds.substr(0, 1);
  if (ds.size() > 1) o += "." + ds.substr(1);
  if (x != 0) o += "\u00d710" + superscript(x);
  return o;
}

std::string signed_integer(long long v) { return (v < 0 ? "\u2212" : "") + std::to_string(v < 0 ? -v : v); }

}  // namespace

AxisLabels axis_labels(const Ticks& t) {
  AxisLabels a;
  bool fits = true;
  for (double v : t.values) {
    a.labels.push_back(tick_label(v, t.decimals));
    if (glyphs(a.labels.back()) > static_cast<std::size_t>(kMaxTickGlyphs)) fits = false;
  }
  if (fits || t.mantissas.size() != t.values.size()) return a;
  a.labels.clear();
  // value_i = n_i 10^e: drop the trailing zeros all n_i share
  std::vector<long long> n = t.mantissas;
  int e = t.exponent;
  auto all_tens = [&] {
    bool nonzero = false;
    for (long long v : n) {
      if (v % 10 != 0) return false;
      nonzero = nonzero || v != 0;
    }
    return nonzero;
  };
  while (all_tens()) {
    for (auto& v : n) v /= 10;
    ++e;
  }
  long long big = 0;
  for (long long v : n) big = std::max(big, v < 0 ? -v : v);
  // More than three digits: the values are far from 0 compared with the
  // step, so the labels count from an offset, a multiple of 100 next to the
  // middle tick (|n_i - offset| <= 50 + the tick span, at most 4 digits).
  long long offset = 0;
  if (big >= 1000) {
    const long long mid = n[n.size() / 2];
    long long q = mid / 100;
    const long long r = mid % 100;
    if (r >= 50) ++q;
    if (r <= -50) --q;
    offset = q * 100;
  }
  for (long long v : n) a.labels.push_back(signed_integer(v - offset));
  if (e != 0) a.note = "\u00d710" + superscript(e);
  if (offset != 0)
    a.note += std::string(a.note.empty() ? "" : " ") + (offset > 0 ? "+ " : "\u2212 ") +
              scientific(offset > 0 ? offset : -offset, e);
  return a;
}

namespace {

// Advance widths of DejaVu Sans in em (units / 2048), for the characters of
// the plots; other characters get a generous 0.8 em.
double char_em(unsigned cp) {
  if (cp >= '0' && cp <= '9') return 0.636;
  if (cp >= 'a' && cp <= 'z') {
    static const double lower[26] = {0.613, 0.635, 0.550, 0.635, 0.615, 0.352, 0.635, 0.634, 0.278,
                                     0.278, 0.579, 0.278, 0.974, 0.634, 0.612, 0.635, 0.635, 0.411,
                                     0.521, 0.392, 0.634, 0.592, 0.818, 0.592, 0.592, 0.525};
    return lower[cp - 'a'];
  }
  if (cp >= 'A' && cp <= 'Z') return cp == 'M' ? 0.863 : cp == 'W' ? 0.989 : cp == 'I' || cp == 'J' ? 0.4 : 0.77;
  switch (cp) {
    case ' ': case ',': case '.': case ':': case ';': return 0.318;
    case '(': case ')': case '[': case ']': return 0.390;
    case '{': case '}': return 0.636;
    case '/': case '\\': return 0.337;
    case '-': return 0.361;
    case '_': return 0.5;
    case '*': return 0.5;
    case '\'': return 0.275;
    case '"': return 0.46;
    case '|': return 0.337;
    case '!': return 0.4;
    case '?': return 0.531;
    case '%': return 0.950;
    case '&': return 0.780;
    case '@': return 1.0;
    case '#': return 0.838;
    case '$': return 0.636;
    case '+': case '=': case '<': case '>': case '^': case '~': return 0.838;
    case 0x2212: case 0x00d7: case 0x2192: case 0x2218: return 0.838;  // − × → ∘
    case 0x2026: return 1.0;                                           // …
    case 0x2032: return 0.3;                                           // ′
    case 0x221a: return 0.64;                                          // √
    default: break;
  }
  if ((cp >= 0x2070 && cp <= 0x2079) || cp == 0x00b9 || cp == 0x00b2 || cp == 0x00b3 || cp == 0x207b)
    return 0.401;  // superscripts
  if (cp >= 0x0370 && cp <= 0x03ff) return 0.7;  // Greek
  return 0.8;
}

// The code point starting at s[i] (advancing i past it).
unsigned next_code_point(const std::string& s, std::size_t& i) {
  const unsigned char c = static_cast<unsigned char>(s[i++]);
  if (c < 0x80) return c;
  int more = c >= 0xF0 ? 3 : c >= 0xE0 ? 2 : 1;
  unsigned cp = c & (0x3F >> more);
  while (more-- > 0 && i < s.size() && (static_cast<unsigned char>(s[i]) & 0xC0) == 0x80)
    cp = (cp << 6) | (static_cast<unsigned char>(s[i++]) & 0x3F);
  return cp;
}

// The units of text for breaking: a code point, or a whole "_{...}" subscript.
std::vector<std::string> units(const std::string& s) {
  std::vector<std::string> u;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s.compare(i, 2, "_{") == 0) {
      const std::size_t close = s.find('}', i);
      if (close != std::string::npos) {
        u.push_back(s.substr(i, close + 1 - i));
        i = close + 1;
        continue;
      }
    }
    const std::size_t a = i;
    next_code_point(s, i);
    u.push_back(s.substr(a, i - a));
  }
  return u;
}

}  // namespace

double text_width(const std::string& s, double size, bool bold) {
  double em = 0;
  std::size_t i = 0;
  while (i < s.size()) {
    if (s.compare(i, 2, "_{") == 0) {
      const std::size_t close = s.find('}', i);
      if (close != std::string::npos) {
        std::size_t j = i + 2;
        while (j < close) em += 0.75 * char_em(next_code_point(s, j));
        i = close + 1;
        continue;
      }
    }
    em += char_em(next_code_point(s, i));
  }
  return em * size * (bold ? 1.1 : 1.0);
}

std::vector<std::string> wrap_text(const std::string& s, double size, double max_width, bool bold,
                                   std::size_t max_lines) {
  if (max_lines < 1) max_lines = 1;
  const auto width = [&](const std::string& t) { return text_width(t, size, bold); };
  std::vector<std::string> lines;
  std::string line;
  // words with the spaces that follow them, so that the text is kept exactly
  std::vector<std::string> words;
  for (std::size_t i = 0; i < s.size();) {
    std::size_t j = s.find(' ', i);
    j = j == std::string::npos ? s.size() : s.find_first_not_of(' ', j);
    if (j == std::string::npos) j = s.size();
    words.push_back(s.substr(i, j - i));
    i = j;
  }
  auto trimmed = [](std::string t) {
    while (!t.empty() && t.back() == ' ') t.pop_back();
    return t;
  };
  for (const auto& w : words) {
    if (width(trimmed(line + w)) <= max_width) {
      line += w;
      continue;
    }
    if (!line.empty()) {
      lines.push_back(trimmed(line));
      line.clear();
    }
    if (width(trimmed(w)) <= max_width) {
      line = w;
      continue;
    }
    // a word wider than a line: broken between characters
    for (const auto& u : units(w)) {
      if (!line.empty() && width(trimmed(line + u)) > max_width) {
        lines.push_back(trimmed(line));
        line.clear();
      }
      line += u;
    }
  }
  if (!trimmed(line).empty() || lines.empty()) lines.push_back(trimmed(line));
  if (lines.size() <= max_lines) return lines;
  // Too many lines: the last one shows the start of the rest and the end of
  // the text around " … ".
  std::string rest;
  for (std::size_t k = max_lines - 1; k < lines.size(); ++k) rest += (rest.empty() ? "" : " ") + lines[k];
  lines.resize(max_lines - 1);
  const std::vector<std::string> u = units(rest);
  const double half = (max_width - width(" \u2026 ")) / 2;
  std::string head, tail;
  std::size_t a = 0, b = u.size();
  while (a < b && width(head + u[a]) <= half) head += u[a++];
  while (b > a && width(u[b - 1] + tail) <= half) tail = u[--b] + tail;
  lines.push_back(trimmed(head) + " \u2026 " + tail);
  return lines;
}

Point Panel::map(double x, double y) const {
  return {left + (x - x0) / (x1 - x0) * width, top + height - (y - y0) / (y1 - y0) * height};
}

void draw_axes(Document& d, const Panel& p, const Ticks& xt, const Ticks& yt, const std::string& xlabel,
               const std::string& ylabel) {
  d.begin_group("axes");
  const Style grid{"#e3e3e3", "none", 1, "", 1};
  const Style tick{"#444", "none", 1, "", 1};
  const AxisLabels xl = axis_labels(xt), yl = axis_labels(yt);
  for (std::size_t i = 0; i < xt.values.size(); ++i) {
    const double x = xt.values[i];
    if (x < p.x0 || x > p.x1) continue;
    const double px = p.map(x, p.y0).first;
    d.line({px, p.top}, {px, p.top + p.height}, grid);
    d.line({px, p.top + p.height}, {px, p.top + p.height + 5}, tick);
    d.text({px, p.top + p.height + 19}, xl.labels[i], 12, Anchor::Middle, "#333");
  }
  double widest = 0;
  for (std::size_t i = 0; i < yt.values.size(); ++i) {
    const double y = yt.values[i];
    if (y < p.y0 || y > p.y1) continue;
    const double py = p.map(p.x0, y).second;
    d.line({p.left, py}, {p.left + p.width, py}, grid);
    d.line({p.left - 5, py}, {p.left, py}, tick);
    d.text({p.left - 8, py + 4}, yl.labels[i], 12, Anchor::End, "#333");
    widest = std::max(widest, text_width(yl.labels[i], 12));
  }
  d.rect(p.left, p.top, p.width, p.height, Style{"#444", "none", 1, "", 1});
  if (!xl.note.empty()) d.text({p.left + p.width, p.top + p.height + 38}, xl.note, 11, Anchor::End, "#333");
  if (!yl.note.empty()) d.text({p.left, p.top - 6}, yl.note, 11, Anchor::Start, "#333");
  d.text({p.left + p.width / 2, p.top + p.height + 38}, xlabel, 13, Anchor::Middle, "#222");
  // the rotated label reaches 10 px left of its x and 3 px right of it
  const double ylabel_x = p.left - std::max(46.0, 8 + widest + 2 + 3);
  d.text({ylabel_x, p.top + p.height / 2}, ylabel, 13, Anchor::Middle, "#222", false, -90);
  d.end_group();
}

// ---- Output files and the rsvg-convert child ----------------------------
//
// While a file is written or rsvg-convert runs, SIGINT, SIGTERM, SIGHUP and
// SIGQUIT are caught: the handler kills and reaps the child, removes a file
// this process created but did not finish, and re-raises the signal with its
// default action (so the exit status still tells the signal). It uses only
// async-signal-safe calls and the three variables below.

namespace {

volatile sig_atomic_t g_child = 0;         // pid of the running rsvg-convert, or 0
volatile sig_atomic_t g_remove_armed = 0;  // g_remove_path names a file to remove
char g_remove_path[PATH_MAX];

const int kCaught[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

extern "C" void on_ending_signal(int sig) {
  const pid_t child = g_child;
  if (child > 0) {
    kill(child, SIGKILL);
    while (waitpid(child, nullptr, 0) < 0 && errno == EINTR) {
    }
  }
  if (g_remove_armed) unlink(g_remove_path);
  struct sigaction dfl {};
  dfl.sa_handler = SIG_DFL;
  sigemptyset(&dfl.sa_mask);
  sigaction(sig, &dfl, nullptr);
  raise(sig);  // pending until the handler returns, then the default action
}

// Catches the ending signals for its lifetime (signals the process ignores,
// as under nohup, stay ignored); restores the previous actions after.
class CatchEndingSignals {
 public:
  CatchEndingSignals() {
    for (std::size_t i = 0; i < std::size(kCaught); ++i) {
      sigaction(kCaught[i], nullptr, &old_[i]);
      if (old_[i].sa_handler == SIG_IGN) continue;
      struct sigaction sa {};
      sa.sa_handler = on_ending_signal;
      sigfillset(&sa.sa_mask);
      sigaction(kCaught[i], &sa, nullptr);
    }
  }
  ~CatchEndingSignals() {
    for (std::size_t i = 0; i < std::size(kCaught); ++i) sigaction(kCaught[i], &old_[i], nullptr);
  }
  CatchEndingSignals(const CatchEndingSignals&) = delete;
  CatchEndingSignals& operator=(const CatchEndingSignals&) = delete;

 private:
  struct sigaction old_[std::size(kCaught)];
};

// Blocks every signal in the calling thread for its lifetime (so that the
// handler never sees half-updated state).
class BlockSignals {
 public:
  BlockSignals() {
    sigset_t all;
    sigfillset(&all);
    pthread_sigmask(SIG_BLOCK, &all, &old_);
  }
  ~BlockSignals() { pthread_sigmask(SIG_SETMASK, &old_, nullptr); }
  BlockSignals(const BlockSignals&) = delete;
  BlockSignals& operator=(const BlockSignals&) = delete;
  const sigset_t& old() const { return old_; }

 private:
  sigset_t old_;
};

// Ignores SIGPIPE for its lifetime: a child that stops reading its input
// gives EPIPE, not the end of this process.
class IgnoreSigpipe {
 public:
  IgnoreSigpipe() {
    struct sigaction sa {};
    sa.sa_handler = SIG_IGN;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGPIPE, &sa, &old_);
  }
  ~IgnoreSigpipe() { sigaction(SIGPIPE, &old_, nullptr); }
  IgnoreSigpipe(const IgnoreSigpipe&) = delete;
  IgnoreSigpipe& operator=(const IgnoreSigpipe&) = delete;

 private:
  struct sigaction old_;
};

std::string cannot_write(const std::string& path, int err) {
  return "cannot write " + path + ": " + std::strerror(err);
}

class Fd {
 public:
  Fd() = default;
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() { reset(); }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }
  bool open() const { return fd_ >= 0; }
  void reset(int fd = -1) {
    if (fd_ >= 0) close(fd_);
    fd_ = fd;
  }

 private:
  int fd_ = -1;
};

void make_pipe(Fd& read_end, Fd& write_end) {
  int p[2];
  if (pipe2(p, O_CLOEXEC) != 0) throw std::runtime_error(std::string("cannot create a pipe: ") + std::strerror(errno));
  read_end.reset(p[0]);
  write_end.reset(p[1]);
}

// The running rsvg-convert: killed and reaped at destruction unless reaped
// before (so that every way out of write_png, an exception included, ends it).
class Child {
 public:
  Child() = default;
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      wait_blocking();
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  void set(pid_t pid) { pid_ = pid; }
  pid_t pid() const { return pid_; }
  /// Reaps the child if it has exited; true then (status in status()).
  bool try_reap() {
    BlockSignals b;
    const pid_t r = waitpid(pid_, &status_, WNOHANG);
    if (r == pid_ || (r < 0 && errno == ECHILD)) {
      pid_ = 0;
      g_child = 0;
      return true;
    }
    return false;
  }
  int status() const { return status_; }

 private:
  void wait_blocking() {
    BlockSignals b;
    while (waitpid(pid_, &status_, 0) < 0 && errno == EINTR) {
    }
    pid_ = 0;
    g_child = 0;
  }
  pid_t pid_ = 0;
  int status_ = 0;
};

const char* kNoRsvg =
    "PNG output needs the program rsvg-convert, which is not installed: install the Debian "
    "package librsvg2-bin (apt-get install librsvg2-bin), or write SVG with -o FILE.svg";

// Milliseconds to the calling thread's deadline (at least 0), capped at `cap`.
int poll_timeout_ms(int cap) {
  const Deadline d = current_deadline();
  if (!d.active) return cap;
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(d.at - std::chrono::steady_clock::now());
  return static_cast<int>(std::max<long long>(0, std::min<long long>(cap, left.count() + 1)));
}

}  // namespace

void check_writable(const std::string& path) {
  int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd >= 0) {
    close(fd);
    unlink(path.c_str());
    return;
  }
  if (errno == EEXIST) {
    // an existing file: opened for writing without truncating it
    fd = open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd >= 0) {
      close(fd);
      return;
    }
  }
  throw std::runtime_error(cannot_write(path, errno));
}

void write_file(const std::string& path, const std::string& bytes) {
  const CatchEndingSignals catching;
  struct stat st;
  const bool existed = stat(path.c_str(), &st) == 0;
  const int fd = open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw std::runtime_error(cannot_write(path, errno));
  if (!existed && path.size() < sizeof g_remove_path) {
    const BlockSignals blocked;
    std::memcpy(g_remove_path, path.c_str(), path.size() + 1);
    g_remove_armed = 1;
  }
  std::size_t off = 0;
  int err = 0;
  while (off < bytes.size()) {
    const ssize_t n = write(fd, bytes.data() + off, bytes.size() - off);
    if (n < 0) {
      if (errno == EINTR) continue;
      err = errno;
      break;
    }
    off += static_cast<std::size_t>(n);
  }
  if (close(fd) != 0 && err == 0) err = errno;
  const BlockSignals blocked;
  if (err != 0 && !existed) unlink(path.c_str());
  g_remove_armed = 0;
  if (err != 0) throw std::runtime_error(cannot_write(path, err));
}

std::string find_rsvg_convert() {
  const char* env = std::getenv("PATH");
  const std::string path = env && *env ? env : "/usr/local/bin:/usr/bin:/bin";
  for (std::size_t i = 0; i <= path.size();) {
    std::size_t j = path.find(':', i);
    if (j == std::string::npos) j = path.size();
    const std::string dir = j == i ? "." : path.substr(i, j - i);
    const std::string candidate = dir + "/rsvg-convert";
    struct stat st;
    if (stat(candidate.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(candidate.c_str(), X_OK) == 0)
      return candidate;
    i = j + 1;
  }
  throw std::runtime_error(kNoRsvg);
}

void write_png(const std::string& svg_text, const std::string& png_path, double zoom) {
  check_time_budget();
  const std::string program = find_rsvg_convert();
  const std::string z = num(zoom);
  std::vector<std::string> args = {"rsvg-convert", "--format", "png", "--zoom", z};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  const CatchEndingSignals catching;
  const IgnoreSigpipe no_sigpipe;
  Fd in_r, in_w, out_r, out_w, err_r, err_w, exec_r, exec_w;
  make_pipe(in_r, in_w);
  make_pipe(out_r, out_w);
  make_pipe(err_r, err_w);
  make_pipe(exec_r, exec_w);  // carries errno if exec fails; closed by a successful exec
  Child child;
  {
    const BlockSignals blocked;
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid == 0) {
      // The child: only async-signal-safe calls until exec.
#ifdef __linux__
      prctl(PR_SET_PDEATHSIG, SIGKILL);
#endif
      if (getppid() != parent) _exit(127);
      struct sigaction dfl {};
      dfl.sa_handler = SIG_DFL;
      sigemptyset(&dfl.sa_mask);
      sigaction(SIGPIPE, &dfl, nullptr);
      auto move = [](int from, int to) {
        if (from == to) return fcntl(to, F_SETFD, 0) == 0;
        return dup2(from, to) == to;
      };
      if (move(in_r.get(), 0) && move(out_w.get(), 1) && move(err_w.get(), 2)) {
        sigset_t none;
        sigemptyset(&none);
        pthread_sigmask(SIG_SETMASK, &none, nullptr);
        execve(program.c_str(), argv.data(), environ);
      }
      const int e = errno;
      ssize_t ignored = write(exec_w.get(), &e, sizeof e);
      (void)ignored;
      _exit(127);
    }
    if (pid < 0) throw std::runtime_error(std::string("cannot run rsvg-convert: ") + std::strerror(errno));
    child.set(pid);
    g_child = pid;
  }
  in_r.reset();
  out_w.reset();
  err_w.reset();
  exec_w.reset();
  int exec_errno = 0;
  for (;;) {
    const ssize_t n = read(exec_r.get(), &exec_errno, sizeof exec_errno);
    if (n < 0 && errno == EINTR) continue;
    if (n != static_cast<ssize_t>(sizeof exec_errno)) exec_errno = 0;
    break;
  }
  if (exec_errno != 0) {
    if (exec_errno == ENOENT) throw std::runtime_error(kNoRsvg);
    throw std::runtime_error("cannot run " + program + ": " + std::strerror(exec_errno));
  }

  // Feed the SVG, collect the PNG and the messages, until the child closes
  // its output or the time budget runs out (then ~Child kills it).
  fcntl(in_w.get(), F_SETFL, fcntl(in_w.get(), F_GETFL) | O_NONBLOCK);
  std::string png, err;
  std::size_t sent = 0;
  if (svg_text.empty()) in_w.reset();
  char buf[65536];
  while (out_r.open() || err_r.open()) {
    check_time_budget();
    pollfd fds[3];
    int n = 0, iin = -1, iout = -1, ierr = -1;
    if (in_w.open()) { fds[n] = {in_w.get(), POLLOUT, 0}; iin = n++; }
    if (out_r.open()) { fds[n] = {out_r.get(), POLLIN, 0}; iout = n++; }
    if (err_r.open()) { fds[n] = {err_r.get(), POLLIN, 0}; ierr = n++; }
    const int r = poll(fds, static_cast<nfds_t>(n), poll_timeout_ms(250));
    if (r < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(std::string("waiting for rsvg-convert: ") + std::strerror(errno));
    }
    if (iin >= 0 && fds[iin].revents) {
      const ssize_t w = write(in_w.get(), svg_text.data() + sent, std::min<std::size_t>(svg_text.size() - sent, 65536));
      if (w > 0) sent += static_cast<std::size_t>(w);
      if ((w < 0 && errno != EINTR && errno != EAGAIN) || sent == svg_text.size()) in_w.reset();
    }
    auto drain = [&](int i, Fd& fd, std::string& to, std::size_t cap) {
      if (i < 0 || !fds[i].revents) return;
      const ssize_t k = read(fd.get(), buf, sizeof buf);
      if (k > 0) {
        if (to.size() < cap) to.append(buf, static_cast<std::size_t>(std::min<std::size_t>(k, cap - to.size())));
      } else if (k == 0 || (errno != EINTR && errno != EAGAIN)) {
        fd.reset();
      }
    };
    drain(iout, out_r, png, static_cast<std::size_t>(-1));
    drain(ierr, err_r, err, 65536);
  }
  in_w.reset();
  while (!child.try_reap()) {
    check_time_budget();
    poll(nullptr, 0, std::min(20, poll_timeout_ms(20)));
  }
  const int status = child.status();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
    throw std::runtime_error("rsvg-convert failed writing " + png_path + (err.empty() ? "" : ": " + err));
  }
  write_file(png_path, png);
}

}  // namespace uniparam::cli::svg
