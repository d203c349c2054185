#include "input.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <iterator>

#include "uniparam/core/error.hpp"

namespace uniparam::cli {

std::string read_argument_text(const std::string& what, const std::string& value, std::size_t max_bytes) {
  std::string text;
  if (value == "-") {
    text.assign(std::istreambuf_iterator<char>(std::cin), std::istreambuf_iterator<char>());
  } else if (!value.empty() && value[0] == '@') {
    const std::string path = value.substr(1);
    std::ifstream f(path, std::ios::binary);
    if (!f) throw InvalidArgument(what + ": cannot read '" + path + "': " + std::strerror(errno));
    text.assign(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
    if (f.bad()) throw InvalidArgument(what + ": cannot read '" + path + "': " + std::strerror(errno));
  } else {
    return value;
  }
  if (text.size() > max_bytes)
    throw InvalidArgument(what + ": " + std::to_string(text.size()) + " bytes, more than the " +
                          std::to_string(max_bytes) + " allowed (raise --max-length)");
  return text;
}

}  // namespace uniparam::cli
