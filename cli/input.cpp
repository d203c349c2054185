#include "input.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "uniparam/core/error.hpp"

namespace uniparam::cli {

namespace {

// Reads at most max_bytes + 1 bytes of `f` (one more than allowed, to tell
// an over-long input apart).
std::string read_bounded(std::FILE* f, const std::string& what, const std::string& source, std::size_t max_bytes,
                         const std::string& limit_option) {
  std::string out;
  char buf[65536];
  for (;;) {
    const std::size_t room = max_bytes + 1 - out.size();
    const std::size_t n = std::fread(buf, 1, room < sizeof buf ? room : sizeof buf, f);
    out.append(buf, n);
    if (out.size() > max_bytes) {
      const std::string m = what + ": " + source + " holds more than " + std::to_string(max_bytes) +
                            " bytes (the limit for " + what +
                            (limit_option.empty() ? std::string(")") : "; raise it with " + limit_option + ")");
      // A limit an option raises is a budget (as the parser's --max-length); a fixed one bounds valid input.
      if (limit_option.empty()) throw InvalidArgument(m);
      throw BudgetExceeded(m);
    }
    if (n == 0 || std::feof(f)) break;
  }
  if (std::ferror(f)) {
    const int e = errno;
    throw InvalidArgument(what + ": cannot read " + source + ": " + std::strerror(e));
  }
  return out;
}

}  // namespace

std::string read_argument_text(const std::string& what, const std::string& value, std::size_t max_bytes,
                               const std::string& limit_option) {
  if (value == "-") return read_bounded(stdin, what, "standard input", max_bytes, limit_option);
  if (value.empty() || value[0] != '@') return value;
  const std::string path = value.substr(1);
  if (path.empty()) throw InvalidArgument(what + ": '@' must be followed by a file name (@FILE)");
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) {
    const int e = errno;
    throw InvalidArgument(what + ": cannot open '" + path + "': " + std::strerror(e));
  }
  return read_bounded(f.get(), what, "the file '" + path + "'", max_bytes, limit_option);
}

}  // namespace uniparam::cli
