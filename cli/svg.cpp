#include "svg.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

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
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) {
    if (!std::isfinite(lo)) lo = 0;
    hi = lo + 0.5;
    lo = lo - 0.5;
  }
  if (target < 2) target = 2;
  const double raw = (hi - lo) / target;
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  const double norm = raw / mag;
  double f = norm < 1.5 ? 1 : norm < 3.5 ? 2 : norm < 7.5 ? 5 : 10;
  Ticks t;
  t.step = f * mag;
  const double eps = t.step * 1e-9;
  const long first = static_cast<long>(std::ceil((lo - eps) / t.step));
  const long last = static_cast<long>(std::floor((hi + eps) / t.step));
  for (long k = first; k <= last; ++k) t.values.push_back(static_cast<double>(k) * t.step);
  const int e = static_cast<int>(std::floor(std::log10(t.step) + 1e-9));
  t.decimals = e < 0 ? -e : 0;
  return t;
}

std::string tick_label(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  std::string s = buf;
  bool zero = true;
  for (char c : s)
    if (c >= '1' && c <= '9') zero = false;
  if (zero) {
    std::snprintf(buf, sizeof buf, "%.*f", decimals, 0.0);
    s = buf;
  }
  if (!s.empty() && s[0] == '-') s.replace(0, 1, "\u2212");  // a proper minus sign
  return s;
}

Point Panel::map(double x, double y) const {
  return {left + (x - x0) / (x1 - x0) * width, top + height - (y - y0) / (y1 - y0) * height};
}

void draw_axes(Document& d, const Panel& p, const Ticks& xt, const Ticks& yt, const std::string& xlabel,
               const std::string& ylabel) {
  d.begin_group("axes");
  const Style grid{"#e3e3e3", "none", 1, "", 1};
  const Style tick{"#444", "none", 1, "", 1};
  for (double x : xt.values) {
    if (x < p.x0 || x > p.x1) continue;
    const double px = p.map(x, p.y0).first;
    d.line({px, p.top}, {px, p.top + p.height}, grid);
    d.line({px, p.top + p.height}, {px, p.top + p.height + 5}, tick);
    d.text({px, p.top + p.height + 19}, tick_label(x, xt.decimals), 12, Anchor::Middle, "#333");
  }
  for (double y : yt.values) {
    if (y < p.y0 || y > p.y1) continue;
    const double py = p.map(p.x0, y).second;
    d.line({p.left, py}, {p.left + p.width, py}, grid);
    d.line({p.left - 5, py}, {p.left, py}, tick);
    d.text({p.left - 8, py + 4}, tick_label(y, yt.decimals), 12, Anchor::End, "#333");
  }
  d.rect(p.left, p.top, p.width, p.height, Style{"#444", "none", 1, "", 1});
  d.text({p.left + p.width / 2, p.top + p.height + 38}, xlabel, 13, Anchor::Middle, "#222");
  d.text({p.left - 46, p.top + p.height / 2}, ylabel, 13, Anchor::Middle, "#222", false, -90);
  d.end_group();
}

void write_png(const std::string& svg_text, const std::string& png_path, double zoom) {
  char tmpl[] = "/tmp/uniparam_plot_XXXXXX.svg";
  const int fd = mkstemps(tmpl, 4);
  if (fd < 0) throw std::runtime_error(std::string("cannot create a temporary file: ") + std::strerror(errno));
  close(fd);
  {
    std::ofstream f(tmpl, std::ios::binary);
    f << svg_text;
    if (!f) {
      std::remove(tmpl);
      throw std::runtime_error(std::string("cannot write the temporary file ") + tmpl);
    }
  }
  char errname[] = "/tmp/uniparam_rsvg_err_XXXXXX";
  const int efd = mkstemp(errname);
  const std::string z = num(zoom);
  std::vector<std::string> args = {"rsvg-convert", "--format", "png", "--zoom", z, "--output", png_path, tmpl};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  if (efd >= 0) posix_spawn_file_actions_adddup2(&fa, efd, 2);
  pid_t pid;
  const int rc = posix_spawnp(&pid, "rsvg-convert", &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  auto cleanup = [&] {
    std::remove(tmpl);
    if (efd >= 0) { close(efd); std::remove(errname); }
  };
  if (rc != 0) {
    cleanup();
    if (rc == ENOENT)
      throw std::runtime_error(
          "PNG output needs the program rsvg-convert, which is not installed: install the Debian "
          "package librsvg2-bin (apt-get install librsvg2-bin), or write SVG with -o FILE.svg");
    throw std::runtime_error(std::string("cannot run rsvg-convert: ") + std::strerror(rc));
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  std::string err;
  if (efd >= 0) {
    std::ifstream f(errname);
    std::stringstream ss;
    ss << f.rdbuf();
    err = ss.str();
  }
  cleanup();
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    // posix_spawnp may report a missing program through exit status 127
    if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
      throw std::runtime_error(
          "PNG output needs the program rsvg-convert, which is not installed: install the Debian "
          "package librsvg2-bin (apt-get install librsvg2-bin), or write SVG with -o FILE.svg");
    throw std::runtime_error("rsvg-convert failed writing " + png_path + (err.empty() ? "" : ": " + err));
  }
}

}  // namespace uniparam::cli::svg
