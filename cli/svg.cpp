// The SVG document: escaping, number formatting and the primitives
// (lines, marks, text, groups, clips) of svg::Document. Axes and ticks are
// in svg_axes.cpp, text metrics in svg_text.cpp, files and PNG output in
// svg_files.cpp.
#include "svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

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

}  // namespace uniparam::cli::svg
