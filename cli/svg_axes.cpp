// Axes of the plots: nice tick values, their labels (with a common power
// of ten and offset where they would be too long), the panel's data to
// pixel map, and the drawn axes.
#include "svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace uniparam::cli::svg {

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

}  // namespace uniparam::cli::svg
