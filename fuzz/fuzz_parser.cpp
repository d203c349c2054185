// fuzz/fuzz_parser.cpp -- libFuzzer target for the exact parser.
//
// Any bytes: parse_expression and parse_tuple must either succeed or throw a
// uniparam::Error (ParseError, DomainError, BudgetExceeded); anything else
// (another exception, a crash, a sanitizer report, a leak, a hang) is a bug.
// A successful parse must round-trip: printing the rational function and
// parsing the text again gives the same function.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "uniparam/core/error.hpp"
#include "uniparam/core/parser.hpp"

namespace {

uniparam::ParseLimits fuzz_limits() {
  // Smaller than the defaults so that every input runs in milliseconds; the
  // limits themselves are what is being fuzzed.
  uniparam::ParseLimits lim;
  lim.max_degree = 300;
  lim.max_exponent = 300;
  lim.max_bits = 1L << 18;
  lim.max_depth = 200;
  return lim;
}

void round_trip(const uniparam::RatFunc& r) {
  uniparam::ParseLimits wide;  // the printed text may be longer than the input
  wide.max_length = std::size_t(1) << 24;
  if (uniparam::parse_expression(r.str(), wide) != r) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  static const uniparam::ParseLimits lim = fuzz_limits();
  try {
    round_trip(uniparam::parse_expression(text, lim));
  } catch (const uniparam::Error&) {
  }
  try {
    for (const auto& c : uniparam::parse_tuple(text, lim)) round_trip(c);
  } catch (const uniparam::Error&) {
  }
  return 0;
}
