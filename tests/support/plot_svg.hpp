// Reading the text, frames and axes of the SVG that `uniparam plot` writes
// (tick values with their common power of ten and offset, DejaVu Sans text
// widths), for the CLI tests of the plot's layout and trace.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "support/run.hpp"
#include "support/svg.hpp"

namespace uniparam::test_support {

inline std::string attr(const std::string& tag, const std::string& name) {
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
inline std::vector<Text> texts(const std::string& frag) {
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

inline std::vector<unsigned> code_points(const std::string& s) {
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
inline double dejavu_em(unsigned cp) {
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

inline double width_px(const Text& t) {
  double em = 0;
  for (unsigned cp : code_points(t.text)) em += dejavu_em(cp);
  return em * t.size * (t.bold ? 1.1 : 1.0);
}

struct Rect {
  double x, y, w, h;
};

// The frame of each <g class="axes"> (its last <rect>), in document order.
inline std::vector<std::pair<Rect, std::string>> axes_groups(const std::string& svg) {
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

inline long long parse_label(const std::string& s) {
  std::string t = s;
  const std::string minus = "\u2212";
  bool neg = false;
  if (t.compare(0, minus.size(), minus) == 0) {
    neg = true;
    t = t.substr(minus.size());
  }
  return neg ? -std::stoll(t) : std::stoll(t);
}

inline int parse_superscript(const std::string& s, std::size_t& i) {
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
inline double tick_value(const std::string& label, const std::string& note) {
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
inline std::pair<Axis, Axis> read_axes(const Rect& frame, const std::string& g,
                                       std::vector<Text>* labels = nullptr) {
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
inline ::testing::AssertionResult affine(const Axis& a) {
  if (a.pixel.size() < 2) return ::testing::AssertionFailure() << "fewer than 2 ticks";
  const double span = std::fabs(a.value.back() - a.value.front());
  if (!(span > 0)) return ::testing::AssertionFailure() << "ticks without a span";
  for (std::size_t i = 0; i < a.pixel.size(); ++i)
    if (std::fabs(a.at(a.pixel[i]) - a.value[i]) > 1e-3 * span)
      return ::testing::AssertionFailure() << "tick " << i << " = " << a.value[i] << " is off the axis' map ("
                                           << a.at(a.pixel[i]) << ")";
  return ::testing::AssertionSuccess();
}

inline std::string plot_svg(const std::vector<std::string>& args) {
  std::vector<std::string> a = {"plot"};
  a.insert(a.end(), args.begin(), args.end());
  a.insert(a.end(), {"-o", "-"});
  const auto r = run_uniparam(a);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.out;
}

}  // namespace uniparam::test_support
