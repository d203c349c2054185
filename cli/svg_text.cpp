// Text metrics of the plots: glyph counts, advance widths of DejaVu Sans
// (with the sub- and superscript markup of the labels), and wrapping of
// long text to a width and a number of lines.
#include "svg.hpp"

#include <algorithm>
#include <string>
#include <vector>

namespace uniparam::cli::svg {

std::size_t glyphs(const std::string& s) {
  std::size_t n = 0;
  for (char c : s)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
  return n;
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

}  // namespace uniparam::cli::svg
