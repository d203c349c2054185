// Reading the SVG that `uniparam plot` writes, for the CLI tests.
#pragma once

#include <cstddef>
#include <string>

namespace uniparam::test_support {

/// The text of the first <g class="cls"> element at or after `from`, up to
/// its matching </g> (nested groups included); "" when there is none.
inline std::string group(const std::string& svg, const std::string& cls, std::size_t from = 0) {
  const std::size_t start = svg.find("<g class=\"" + cls + "\">", from);
  if (start == std::string::npos) return "";
  std::size_t depth = 0, i = start;
  while (i < svg.size()) {
    if (svg.compare(i, 2, "<g") == 0 && (svg[i + 2] == ' ' || svg[i + 2] == '>')) ++depth;
    if (svg.compare(i, 4, "</g>") == 0 && --depth == 0) return svg.substr(start, i + 4 - start);
    ++i;
  }
  return "";
}

}  // namespace uniparam::test_support
