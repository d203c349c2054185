// uniparam/core/error.hpp -- the exception hierarchy of the whole engine: the
// public uniparam/error.hpp; and how error messages show input characters.
#pragma once

#include <string>

#include "uniparam/error.hpp"

namespace uniparam {

/// How an error message shows one character of the input: 'c' quoted when it
/// is printable ASCII, else "byte 0xhh" (lower-case hex), so a message never
/// carries a control character or a partial UTF-8 sequence. Never throws.
inline std::string shown_char(char c) {
  const auto u = static_cast<unsigned char>(c);
  if (u < 0x20 || u >= 0x7f) {
    static const char* hex = "0123456789abcdef";
    return std::string("byte 0x") + hex[u >> 4] + hex[u & 15];
  }
  return std::string("'") + c + "'";
}

}  // namespace uniparam
