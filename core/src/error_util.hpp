// Private helpers of core: owning FLINT-allocated C strings.
#pragma once
#include <flint/flint.h>
#include <string>

namespace uniparam::detail {
/// Takes ownership of a string allocated by FLINT/Arb and frees it.
inline std::string take_flint_string(char* s) {
  std::string out(s ? s : "");
  flint_free(s);
  return out;
}
}  // namespace uniparam::detail
